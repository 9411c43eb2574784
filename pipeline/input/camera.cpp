// Camera frame construction, guarded against degenerate inputs, and projection in double.
#include "pipeline/input/camera.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

#include "shading/portable_math.h"

namespace pleinair {

std::string make_camera(const CameraParams& p, Camera& c) {
    glm::dvec3 view = p.look_at - p.position;
    double dist = glm::length(view);
    double scale = std::max({1.0, glm::length(p.position), glm::length(p.look_at)});
    if (!(dist > 1e-9 * scale) || !std::isfinite(dist)) return "look_at must differ from position";
    if (!(p.fov > 0 && p.fov < 180)) return "fov must be in (0, 180) degrees";
    if (p.width < 1 || p.height < 1) return "width and height must be at least 1";
    c.eye = p.position;
    c.forward = view / dist;
    glm::dvec3 up = p.up;
    double ul = glm::length(up);
    up = ul > 0 && std::isfinite(ul) ? up / ul : glm::dvec3(0, 1, 0);
    glm::dvec3 right = glm::cross(c.forward, up);
    if (glm::length(right) < 1e-6) {
        // Looking along up: borrow the axis least aligned with the view.
        glm::dvec3 alt = std::abs(c.forward.z) < 0.9 ? glm::dvec3(0, 0, -1) : glm::dvec3(-1, 0, 0);
        right = glm::cross(c.forward, alt);
    }
    c.right = glm::normalize(right);
    c.up = glm::cross(c.right, c.forward);
    c.width = p.width;
    c.height = p.height;
    c.focal_px = 0.5 * p.height / pmath::tan(0.5 * p.fov * M_PI / 180.0);
    c.focus_distance = dist;
    c.near_depth = 1e-4 * dist;
    return "";
}

Projection project(const Camera& c, const glm::dvec3& world) {
    glm::dvec3 d = world - c.eye;
    Projection out;
    double z = glm::dot(d, c.forward);
    out.depth = static_cast<float>(z);
    if (!(z > c.near_depth)) return out;
    double k = c.focal_px / z;
    out.x = static_cast<float>(0.5 * c.width + k * glm::dot(d, c.right));
    out.y = static_cast<float>(0.5 * c.height - k * glm::dot(d, c.up));
    out.in_front = std::isfinite(out.x) && std::isfinite(out.y);
    return out;
}

glm::dvec3 ray_direction(const Camera& c, double x, double y) {
    glm::dvec3 d =
        c.forward * c.focal_px + c.right * (x - 0.5 * c.width) - c.up * (y - 0.5 * c.height);
    return glm::normalize(d);
}

}  // namespace pleinair
