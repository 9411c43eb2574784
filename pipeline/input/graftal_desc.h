// A graftal description (Markosian et al. 2000, file 000 of the seeds): a designer's example
// leaves, blades or tufts drawn from a few primitives, with the rules that place them, orient
// them to the view and choose how much of them to draw. Plain data, read by graftal_io.cpp from
// presets/graftals/NAME.json; the level-of-detail arithmetic is in graftal_lod.h.
#pragma once

#include <cstdint>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <string>
#include <vector>

namespace pleinair {

// How a graftal's local frame is built from its surface normal n and the view vector v (from
// the graftal to the eye). Its y axis is n, its x axis as named, z completes the frame.
enum class GraftalFrame {
    kView,     // x = n x v: the graftal turns to face the viewer (bushes, truffula tufts)
    kUpright,  // x = n x (n x up): hangs from its base whatever the view (pine branches)
    kSurface,  // x = the surface's own tangent: fixed to the surface (grass, bumps)
};

// ρ, the orientation term of the level of detail, in [0, 1].
enum class GraftalRho {
    kSilhouette,   // 1 - |n.v|: detail where the surface turns away (tree tops, bushes)
    kFrontFacing,  // |n.v|: detail on surfaces that face the viewer (ground tufts)
    kNone,         // 1: size alone decides
};

// λ, the desired amount of detail, from σ (size), ρ (orientation) and τ (transition).
enum class GraftalLambda {
    kRhoSigma,     // λ = ρσ
    kTauRhoSigma,  // λ = τρσ: primitives also fade in as the graftal grows in
    kSigma,        // λ = σ
};

// Where the scene's surfaces get graftals.
enum class GraftalPlacement {
    kLeafParticles,  // one per leaf particle of a tree (its position, normal and label)
    kVertices,       // one per mesh vertex
    kFaces,          // one per mesh face, at its centre
    kEveryKthFace,   // one face in every k, chosen by the seed
    kDensity,        // at a density per unit area, by the seed
    kDifference,     // by the difference-image algorithm (file 004), per frame
};

// A value that a primitive interpolates as λ moves through [lambda_from, lambda_to] (file 000
// §2.2.3: "each attribute to be varied is given a start and end value").
struct LodRamp {
    float lambda_from = 0, lambda_to = 0;  // equal: no ramp, `at_end` throughout
    float at_start = 1, at_end = 1;
};

enum class PrimitiveType {
    kStroke,   // a path of vertices with a width at each: a tapered ribbon
    kStrip,    // a triangle strip over the listed vertices
    kFan,      // a triangle fan: the first vertex and each following pair
    kPolygon,  // a filled polygon, optionally outlined
};

struct GraftalPrimitive {
    PrimitiveType type = PrimitiveType::kStroke;
    std::vector<uint32_t> vertices;  // indices into the example's canonical vertices
    std::vector<float> widths;       // strokes: full width at each path vertex, canonical units
    glm::vec3 color{0.0f};           // linear RGB (files give sRGB)
    glm::vec3 outline_color{0.0f};
    float outline_width = 0;  // 0: no outline
    float opacity = 1;
    LodRamp width_ramp, length_ramp, opacity_ramp;  // multipliers as λ varies
};

// One example graftal: canonical vertices in its local frame (y along the normal, x across,
// z completing it; units of the graftal's length) and the primitives drawn over them.
struct GraftalExample {
    std::string name;
    std::vector<glm::vec3> vertices;
    std::vector<GraftalPrimitive> primitives;
    glm::vec3 extent_from{0.0f}, extent_to{0.0f, 1.0f, 0.0f};  // W: the distance between these
};

// How copies vary from their example, each a symmetric fraction or angle drawn by the seed.
struct GraftalVariation {
    float length = 0;  // scale of length: 1 +- this
    float width = 0;   // scale of width: 1 +- this
    float angle = 0;   // degrees of turn about the normal: +- this
    float color = 0;   // lightness: 1 +- this
};

// A tuft level: the graftals drawn once the tuft's level reaches it.
struct TuftLevel {
    float lambda = 0;                   // λ_i: the level is chosen while λ >= this (λ_0 is 0)
    int count = 1;                      // graftals added at this level, around the tuft's base
    std::vector<std::string> examples;  // drawn from, in turn; empty: all of them
};

// Multi-level tufts (file 000 §2.3): the level is filtered over recent frames and switched with
// hysteresis, and levels grow in and fade out over a set time.
struct TuftRules {
    std::vector<TuftLevel> levels;  // at least one; λ_i strictly increasing from 0
    int queue = 8;                  // frames averaged (the paper's LIFO queue of choices)
    float hysteresis = 0.25f;       // past the half-way point: up at i + 0.75, down below i - 0.75
    float transition_seconds = 0.5f;
    float grow_from = 0.2f;  // a growing graftal's scale at τ = 0
    float spread = 0.35f;    // children sit within this many graftal lengths of the base
};

struct GraftalDesc {
    std::string description;
    GraftalFrame frame = GraftalFrame::kView;
    GraftalRho rho = GraftalRho::kSilhouette;
    GraftalLambda lambda = GraftalLambda::kRhoSigma;
    float preferred_size_px = 25;  // the screen size at which σ = 1
    float length = 1;              // world length of a graftal of canonical length 1
    GraftalPlacement placement = GraftalPlacement::kLeafParticles;
    int every_k = 4;     // kEveryKthFace and kLeafParticles
    float per_area = 1;  // kDensity: graftals per square world unit; kDifference's candidates
    // kDifference (file 004): the desire image's cell, the dot and the desire a tuft needs.
    int cell_px = 4;
    int dot_cells = 5;
    float threshold = 0.35f;
    float band = 0.3f;            // tufts fade in over this much desire above the threshold
    bool alpha_from_rho = false;  // file 001: opacity = ρ, so graftals fade away from silhouettes
    float light = 0;              // how much the sun shades them (graftal_io.cpp)
    std::vector<GraftalExample> examples;
    GraftalVariation variation;
    TuftRules tuft;
};

}  // namespace pleinair
