// The still painter: trees built from a scene, every particle turned into a camera-facing
// brush-stroke sprite, sprites depth-sorted and composited back to front in screen tiles.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "generators/bark.h"
#include "generators/tree.h"
#include "pipeline/landscape.h"
#include "pipeline/rays.h"
#include "pipeline/scene.h"

namespace pleinair {

struct BuiltTree {
    Tree tree;  // tree-local geometry; the transform below places it
    BarkParticles bark;
    uint32_t family = 0;
    glm::dvec3 position{0.0};
    double rotation = 0;  // about +y, degrees
    double scale = 1;
};

// Screen size in pixels of a world length at view depth z (thesis ch. I: brush strokes do not
// shrink like geometry): true perspective at stroke_perspective 1, the size it has at the
// camera's focus distance whatever the depth at 0, in between otherwise. The painter then
// enlarges anything under min_stroke_px.
float stroke_screen_px(const Camera& cam, const RenderSettings& r, double world, double depth);

// A tree's placement in the world: rotation about +y and scale, then its position (in double).
struct TreePlacement {
    double c = 1, s = 0, scale = 1;
    glm::dvec3 position{0.0};
    glm::dvec3 place(const glm::vec3& tree_local) const;
    glm::vec3 turn(const glm::vec3& direction) const;
    glm::dmat3 linear() const;  // place(p) = position + linear() * p
};
TreePlacement placement(const BuiltTree& tree);

// The tree's leaf strokes as shadow casters: cards facing the sun, sized and turned like the
// strokes, with the same noise (IV.4.2).
std::vector<StrokeCaster> leaf_casters(const SceneDesc& scene, const BuiltTree& tree,
                                       const glm::vec3& sun);
// The same, written to out[0 .. tree.tree.leaves.size() - 1].
void leaf_casters(const SceneDesc& scene, const BuiltTree& tree, const glm::vec3& sun,
                  StrokeCaster* out);

// Generates every tree of the scene (in parallel; the result does not depend on threads).
// `bark` is false when the frame does not paint bark.
std::vector<BuiltTree> build_trees(const SceneDesc& scene, bool bark = true);

// A linear, premultiplied RGBA frame; opaque where the background shows. AOVs are filled only
// when asked for: view depth and object id (tree id + 1, 0 for background) of the frontmost
// stroke more than half opaque, accumulated stroke alpha, and that stroke's lightness.
struct Frame {
    int width = 0, height = 0;
    std::vector<float> rgba;
    bool has_aovs = false;
    std::vector<float> depth, object_id, alpha, lightness;
};

struct PassReport {
    std::string name;
    bool ran = false;
    std::string why;  // why it ran or was skipped
    double ms = 0;
    std::string counts;  // e.g. "12,345 sprites"
};

struct FrameReport {
    std::vector<PassReport> passes;
    uint64_t leaf_sprites = 0, bark_sprites = 0, surface_sprites = 0, culled = 0;
    uint64_t shadow_rays = 0, underpaint_rays = 0;
    bool view_scene = false, sun_scene = false;  // which Embree scenes were built
    uint64_t fragments = 0;                      // pixel samples evaluated by the stroke shader
};

struct PaintOptions {
    bool aovs = false;
    bool bark = true;
};

// What the frame needs, decided from the scene alone (DESIGN.md: "the plan").
struct FramePlan {
    bool bark = true;         // bark strokes (bark_coverage > 0 and a bark shader)
    bool tint = false;        // some shader has unique_tint_amt > 0
    bool atmosphere = false;  // an atmosphere and some shader with a non-zero distance effect
    bool sub_stroke = false;  // some shader varies colour inside strokes
    bool aovs = false;
    bool shadows = false;     // the sun casts shadows and something is there to cast them
    bool underpaint = false;  // a visible mesh (terrain, water, rocks): flat colour under strokes
    // Benchmarks only: each sprite's footprint blended with a constant colour at opacity 0.5
    // instead of shaded, to measure what the shader costs over the bare blend.
    bool bare_blend = false;
    std::vector<PassReport> decisions;
};
FramePlan plan_frame(const SceneDesc& scene, const PaintOptions& options);

// Paints the frame. Same inputs, same bytes, on any number of threads.
Frame paint_frame(const SceneDesc& scene, const std::vector<BuiltTree>& trees,
                  const BuiltLandscape& landscape, const FramePlan& plan,
                  FrameReport* report = nullptr);
// The same for a scene of trees only.
Frame paint_frame(const SceneDesc& scene, const std::vector<BuiltTree>& trees,
                  const FramePlan& plan, FrameReport* report = nullptr);

}  // namespace pleinair
