// Staffage: a small figure, posed, as touches on the surfaces of its body's parts, the way Corot
// set a woman gathering or a child at a tree's foot for the picture's scale and its one warm
// accent (issue 52 §6).
#pragma once

#include <cstdint>
#include <glm/vec3.hpp>
#include <vector>

namespace pleinair {

// What the figure does: stands, reaches up into a tree's branches (the woman of Souvenir de
// Mortefontaine), bends to gather from the ground, or sits on it.
enum class FigurePose { kStanding, kReaching, kBending, kSeated };

// Plain data; documented where a scene parses it (pipeline/input/scene.cpp, visit_figure).
struct FigureParams {
    FigurePose pose = FigurePose::kStanding;
    double height = 1.65;  // standing height, world units
    double facing = 0;     // degrees about +y; 0 faces +z
    bool dress = true;     // a long skirt to the ground; false: two legs
    // Linear RGB, each painted at mid lightness (the shader keeps its values).
    glm::vec3 skin{0.55f, 0.34f, 0.22f};
    glm::vec3 hair{0.07f, 0.05f, 0.03f};  // hair, cap or kerchief: the head's top and back
    glm::vec3 top{0.62f, 0.58f, 0.48f};   // blouse and sleeves
    glm::vec3 bottom{0.09f, 0.08f, 0.07f};
    double stroke_size = 0.1;  // a touch's width over the height
    double touches = 1.5;      // touches per square of a touch's width of body surface
};

// Which colour a touch takes.
enum class FigurePart : uint8_t { kSkin, kHair, kTop, kBottom };

// Touches in the world: where, the body's outward normal there, the width, the part.
struct FigureTouches {
    std::vector<glm::vec3> position, normal;
    std::vector<float> width;
    std::vector<FigurePart> part;
    size_t size() const { return position.size(); }
};

// Pure in (params, seed, foot): the figure stands at `foot` (its feet's level), its touches
// spread evenly over each part's surface in a fixed order, so a figure keeps its touches
// whatever else the scene holds. Parameters outside their parsed ranges are clamped.
FigureTouches generate_figure(const FigureParams& params, uint64_t seed, const glm::dvec3& foot);

// The colour of a part of the figure.
glm::vec3 figure_color(const FigureParams& params, FigurePart part);

}  // namespace pleinair
