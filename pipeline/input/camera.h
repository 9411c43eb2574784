// A perspective camera (position, look-at, up, vertical field of view, resolution) and the
// projection of world points to pixels with their view depth.
#pragma once

#include <glm/vec3.hpp>
#include <string>

namespace pleinair {

struct CameraParams {
    glm::dvec3 position{0, 1.6, 12};
    glm::dvec3 look_at{0, 2.5, 0};
    glm::dvec3 up{0, 1, 0};
    double fov = 40;  // vertical, degrees
    int width = 960;
    int height = 540;
};

struct Camera {
    glm::dvec3 eye{0.0};
    glm::dvec3 forward{0, 0, -1}, right{1, 0, 0}, up{0, 1, 0};  // orthonormal, right-handed
    double focal_px = 1;        // pixels per unit of lateral offset at depth 1
    double focus_distance = 1;  // |look_at - position|: the depth where strokes keep their size
    int width = 1, height = 1;
    double near_depth = 1e-3;  // points nearer than this (or behind) are not drawn
};

// Returns an empty string and fills `out`, or a message naming what is wrong (look_at equal to
// position, non-positive fov or size). An up vector parallel to the view (a camera looking
// straight up or down) is replaced by the nearest of +z or -x that is not, so the frame stays
// defined.
std::string make_camera(const CameraParams& params, Camera& out);

struct Projection {
    float x = 0, y = 0;  // pixels, y down
    float depth = 0;     // along the view axis
    bool in_front = false;
};

Projection project(const Camera& cam, const glm::dvec3& world);

// Unit direction of the ray through pixel position (x, y).
glm::dvec3 ray_direction(const Camera& cam, double x, double y);

}  // namespace pleinair
