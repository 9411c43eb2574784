// The sprites stage of a frame: every particle projected to a camera-facing brush-stroke sprite,
// frustum-culled, culled when hidden behind an opaque surface, and given the sun's light.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "pipeline/frame/frame_context.h"
#include "pipeline/frame/frame_plan.h"
#include "pipeline/frame/lod.h"
#include "pipeline/frame/sprite.h"
#include "pipeline/frame/stroke_size.h"
#include "pipeline/frame/wind_stage.h"
#include "pipeline/shot/graftal_draw.h"
#include "pipeline/shot/materials.h"
#include "shading/stroke_shader.h"

namespace pleinair {

struct SceneDesc;
class SeenMemo;
struct Shot;
class RayScene;

// Shadows per fragment: the light at a 4 x 4 grid of points over the sprite, interpolated.
constexpr int kShadowGrid = 4;
using ShadowGrid = std::array<float, kShadowGrid * kShadowGrid>;
float grid_at(const ShadowGrid& g, float s, float t);

// Boiling, for the coherence bench (FrameSettings::noise_reseed): every stroke's noise moves by
// an amount the reseed picks. 0 leaves it.
void reseed_noise(StrokeConstants& k, uint32_t noise_reseed);

// Half extents of a sprite's screen-aligned bounding box (the rotated rectangle's).
void sprite_extent(const Sprite& sp, float& ex, float& ey);

struct SpriteSet {
    std::vector<Sprite> sprites;  // per tree (bark, then leaves), then per surface chunk
    std::vector<ShadowGrid> grids;
    std::vector<GraftalPatch> patches;  // the graftals stage's, one per kGraftal sprite
    uint64_t leaf = 0, bark = 0, surface = 0, graftal = 0;
    uint64_t culled = 0;   // behind the camera, off screen, too faint, faded out, or hidden
    uint64_t faded = 0;    // of those, faded out by the level of detail
    uint64_t hidden = 0;   // of those, behind an opaque surface
    uint64_t thinned = 0;  // of those, thinned out for being small on screen (lod.h)
    uint64_t grouped = 0;  // of those, culled with their cluster, none looked at (group_cull.h)
    uint64_t shadow_rays = 0;
    uint64_t occlusion_rays = 0;  // a stroke's own, where its occlusion maps were unsure
    uint64_t map_rays = 0;        // cast this frame for occlusion maps (SeenMemo keeps maps)
};

// What the sprites stage reads.
struct SpriteStageInput {
    const Shot& shot;
    const FrameView& view;
    const FramePlan& plan;
    const RenderSettings& settings;
    const FrameLod& lod;
    // The sun's scene for this frame (the shot's, or one built for a moving sun); null when the
    // plan takes no light from rays.
    const RayScene* sun_rays = nullptr;
    const SeenWindow* seen = nullptr;  // null: the frame's eye only
    // Clusters that cannot show are culled whole (group_cull.h); false looks at every particle
    // (the same sprites, the reference the tests compare with).
    bool group_culling = true;
    // Occlusion maps kept from the frames before (seen_memo.h); null builds every map.
    SeenMemo* seen_memo = nullptr;
    // The trees' poses in the wind this frame (wind_stage.h); null or off: at rest.
    const FrameWind* wind = nullptr;
    // The sprite vectors' memory kept from the frame before (buffer_pool.h); null allocates it.
    BufferPool* buffers = nullptr;
};

SpriteSet make_sprites(const SpriteStageInput& input);

// Leaves of a graftal-styled family and strokes of a graftal-styled material: no sprite, the
// graftals stage draws those crowns and surfaces (graftal_stage.h).
bool drawn_as_graftals(const Shot& shot, size_t item, SpriteKind kind, size_t particle);

// The sprites stage: make_sprites with the frame's light source and seen window, its counts in
// the report and its pass line.
SpriteSet sprites_stage(const FrameContext& ctx, const FrameLod& lod, const FrameWind& wind,
                        const RayScene* sun_rays, const SeenWindow& seen);

}  // namespace pleinair
