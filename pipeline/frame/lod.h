// The level-of-detail stage of a frame (thesis IV.6): each tree's distance values from the
// camera's circles, how much of its foliage remains and how much the survivors grow, and the
// per-stroke fades the sprites stage applies.
#pragma once

#include <cstdint>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <vector>

#include "pipeline/frame/frame_context.h"
#include "pipeline/frame/frame_view.h"
#include "pipeline/input/camera.h"
#include "pipeline/input/distance_circles.h"
#include "pipeline/input/settings.h"
#include "pipeline/shot/leaf_basis.h"
#include "pipeline/shot/materials.h"
#include "pipeline/shot/particle_clusters.h"

namespace pleinair {

struct Shot;
struct SceneDesc;

// Survivors grow linearly by kept^-kGrowthPower: Cook et al.'s 1/2 (area by 1 / kept), a
// little less since the survivors' spread also widens what they fill (lod.cpp).
constexpr float kGrowthPower = 0.45f;

struct TreeLod {
    // The leaves' distance value at the tree's centre (0 full detail, 1 least), and the bark's
    // (strokes on twigs fade towards 1): replayed along the track (replay_path).
    float leaf = 0;
    float trunk = 0;
    float kept = 1;    // the mean opacity of its leaves at `leaf` (Cook et al.'s u)
    float growth = 1;  // each surviving leaf stroke's linear scale: kept^-kGrowthPower, bounded
    // How much the interior darkening weakens (the shader's lod_distance): as much as keeps the
    // survivors' mean lightness the whole tree's.
    float darkening_lift = 0;
    // Survivors move out from the centre locator to fill the crown's extent direction by
    // direction (the thesis's survivors only grew, so its far trees shrank to their core):
    // per bin of directions (kElevationBins x kAzimuthBins) an exponent gamma and the crown's
    // extent R there; a survivor at distance r < R moves to R (r / R)^gamma, gamma chosen so
    // the survivors' RMS distance (weighted by their fade) becomes the whole crown's. Leaves
    // at the edge stay there, so the silhouette neither shrinks nor grows.
    glm::vec3 center{0.0f};
    std::vector<glm::vec2> radial;  // (gamma, R) per bin; empty: nothing moves
    float max_spread = 1;           // bound on a survivor's move (a factor on its distance)
};

// What the sprites stage needs to know of the level of detail, for one frame.
struct FrameLod {
    bool leaves = false;      // leaves fade by their thresholds, survivors grow
    bool trunks = false;      // bark strokes on twigs cross-fade to the low-detail model
    bool surfaces = false;    // surface detail strokes fade with the leaf circles
    bool near_field = false;  // foliage opens up near the camera
    DistanceCircles circles;
    Camera camera;  // what the level of detail was seen from (the frame's camera)
    float fade_gain = 0.5f;
    // Strokes drawn under render/thin_below_px are thinned out (thin_presence), with the level
    // of detail on and circles on the camera.
    bool thin_small = false;
    std::vector<TreeLod> trees;  // one per tree, when leaves or trunks
};

// The frame's level of detail: off (every flag false but the camera's) when the settings turn
// it off or the view carries no circles. Pure: a function of the shot, the view and the
// settings.
FrameLod level_of_detail(const Shot& shot, const FrameView& view, const RenderSettings& settings);

// Depth of a world point along the camera's view axis (the plane through the eye).
double view_depth(const Camera& cam, const glm::dvec3& world);

// Where a surviving leaf at p (tree-local) is painted: moved along its direction from the
// centre by the bins' ratios, interpolated bilinearly over directions so no leaf jumps.
glm::vec3 spread_leaf(const TreeLod& t, const glm::vec3& p);
// The same for a leaf whose distance r from t.center and direction bins (e, a) are known
// (LeafBasis): the same bits, without the direction's arc sine and arc tangent.
glm::vec3 spread_leaf(const TreeLod& t, const glm::vec3& p, float r, float e, float a);
// The same as a factor on the distance r from the centre, in bin coordinates (e, a).
float spread_factor(const TreeLod& t, float r, float e, float a);

// No leaf or bark fade completes in fewer frames than this, however fast the camera moves.
constexpr int kMinFadeFrames = 4;

// The most a tree's distance value may change in one frame so that a fade of length
// `shortest_fade` (eased by gain g) takes at least kMinFadeFrames frames.
double max_fade_rate(double shortest_fade, float g);

// A leaf's opacity at its tree's distance value: 1 up to fade_begin, 0 from fade_end, eased
// between by Perlin's gain (IV.6); a step at fade_begin when the two are equal.
float leaf_fade(float value, float fade_begin, float fade_end, float gain);

// A bark stroke's opacity at its tree's trunk distance value: strokes on the trunk and first
// branches (the low-detail model) stay, and so do those on twigs that bear a leaf which never
// fades (twig_bark_fades); other twigs' strokes fade, each over its own span of 0.4 starting
// between 0 and 0.6 (drawn from its label), so the model cross-fades.
float bark_fade(float trunk_value, bool fades, float label, float gain);

// A leaf's size factor in the near field (value from near_field_value): interior leaves (small
// centre distance) shrink away first, each from its own threshold; outer ones stay, so the
// crown keeps its shape while the viewer sees into it. Below kThinnedOut the leaf is gone.
float near_field_fade(float near_value, float center_distance, float label, float gain);

// How much strokes shrink in the near field (1 at its circle, 0.6 at the camera), so they
// separate instead of blurring into large blobs (V.3).
constexpr float kThinnedOut = 0.05f;

// Strokes whose level-of-detail fade is below this are not drawn: each would change any pixel
// by less than the compositing cutoff's order.
constexpr float kFadedOut = 1.0f / 1024.0f;

// What the level of detail does to one particle's stroke in a frame.
struct ParticleLod {
    float fade = 1;          // 1 whole, 0 gone (a dry-brush fade, composite.cpp)
    float thin = 1;          // the near field's size factor alone
    float scale = 1;         // the stroke's size on screen: growth, near field
    float lod_distance = 0;  // how much its tree's interior darkening weakens
    float growth = 1;        // a survivor's growth (its tree's)
    // How much of the sun's shadow on it is lifted: the shadow of leaves that have faded.
    float shadow_lift = 0;
    bool moved = false;  // a survivor spread to its crown: painted at `world`
    glm::dvec3 world{0.0};
    // How much of the stroke is there: what the coherence bench follows from frame to frame.
    float presence() const { return fade * thin; }
    bool gone() const { return fade < kFadedOut || thin < kThinnedOut; }
};

// The one rule for a particle (item, kind, index j, at `world`) of the shot: leaves fade by
// their thresholds, grow and spread; twigs' bark strokes cross-fade; leaves in the near field
// thin; surface detail strokes fade by their own depth, in the leaf circles when the camera
// carries them, in the atmosphere's range otherwise (IV.7); the near field's ground strokes
// appear as the camera comes near them.
ParticleLod particle_lod(const Shot& shot, const FrameLod& lod, size_t item, SpriteKind kind,
                         size_t j, const glm::dvec3& world);
inline float near_field_scale(float near_value) { return 1.0f - 0.4f * near_value; }

// Thinning of small strokes (stochastic pruning, Cook et al. 2007): a stroke drawn d pixels
// wide, under the thinning size T, is kept by its own draw u (uniform in [0, 1)) with presence
// thin_presence(d / T, u): whole for u < q = (d / T)^2, fading out (a dry-brush fade) as u
// rises to q (1 + kThinBand), so as the camera comes nearer and q grows a stroke fades in over
// that band and none appears at once; at d = T every stroke is whole. The presences' mean over
// draws is thin_kept(q), and the survivors grow in area by 1 / thin_kept(q): the strokes
// cover the area they all covered, with fewer of them.
constexpr float kThinBand = 0.5f;
float thin_presence(float r, float u);
float thin_kept(float q);
// The draw u of particle j of kind `kind` of item `item`: a hash, the same in every frame.
float thin_draw(size_t item, SpriteKind kind, size_t j);

// The level-of-detail stage: level_of_detail as seen from the frame's view (or the settings'
// lod_view), its pass line when the plan has it.
FrameLod lod_stage(const FrameContext& ctx);

}  // namespace pleinair
