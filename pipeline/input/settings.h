// Painter settings split by what they change: BuildSettings change what build_shot builds,
// RenderSettings only how a frame is painted from it, so no frame setting rebuilds anything.
#pragma once

#include <glm/vec3.hpp>

namespace pleinair {

// How a shadow ray treats stroke casters: the opacity of the first card decides (above one
// half: shadow), or the light is attenuated by every card it crosses.
enum class ShadowMode { kThreshold, kTransmissive };

// Where shadow rays start: one per particle (the whole stroke shares it), or a 4 x 4 grid over
// each sprite interpolated per fragment.
enum class ShadowSamples { kParticle, kFragment };

// Who turns a graftal's shapes into pixels (graftal_draw.h): pleinair's own scanline coverage
// (graftal_raster.h), 1.3-1.5x faster frames than Cairo, which stays as the reference to compare
// with (BENCHMARKS.md, "Graftals").
enum class GraftalRaster { kCairo, kScanline };

// What the shot is built with (scene keys under /render; they regrow strokes).
struct BuildSettings {
    float bark_coverage = 2.5f;    // bark strokes' area over the limbs' area
    float surface_density = 1.0f;  // surface particles per cluster, relative
};

// Quality and style of a frame: what accuracy costs is measured over these.
struct RenderSettings {
    float stroke_perspective = 0.6f;  // 0: strokes keep their screen size, 1: true perspective
    float min_stroke_px = 1.5f;       // no stroke is drawn smaller
    int samples = 4;                  // stroke-mask samples per pixel: 1, 4 or 16
    // Sky strokes at least this wide on screen (the narrower half-width, px) take one sample a
    // pixel, the feather filtered; 0: all take `samples`.
    float sky_one_sample_px = 24.0f;
    // The same for the scene's own strokes (leaves, bark, ground, rocks, water).
    float one_sample_px = 16.0f;
    int octaves = 1;             // stroke-noise octaves
    bool palette_lut = true;     // colours from a per-sprite table instead of per fragment
    bool edge_lut = true;        // the edge mask from a table instead of sin and pow
    bool filter_strokes = true;  // at 1 sample per pixel, widen the feather by its footprint
    ShadowMode shadows = ShadowMode::kTransmissive;
    ShadowSamples shadow_samples = ShadowSamples::kParticle;
    float underpaint_scale = 0.5f;  // underpainting resolution over the image's
    // The underpainting's own colour (Corot's warm, translucent brown lay-in under everything
    // but the sky, issue 52 section 3), sRGB, and how far each surface's flat colour is taken
    // towards it before the atmosphere; 0 keeps the surfaces' own colours.
    glm::vec3 underpaint_tone{0.35f, 0.27f, 0.18f};
    float underpaint_tone_amount = 0.0f;
    // Light left at a pixel below which the strokes behind are not painted (front to back); 0
    // paints every stroke.
    float coverage_cutoff = 1.0f / 2048.0f;
    // Level of detail (IV.6), when the camera has distance circles.
    bool level_of_detail = true;
    float fade_gain = 0.6f;        // Perlin gain on a fade: above 0.5 it eases in and out
    float max_leaf_growth = 2.5f;  // survivors grow at most this much (linear)
    // With the level of detail: strokes drawn narrower than this on screen are thinned out,
    // the survivors grown to keep their area (lod.h's thin_presence); 0 thins none. Twice
    // min_stroke_px, so a stroke at the smallest size keeps about a third of its fellows, each
    // grown at most 2x (issue 53: a preview is the same painting seen smaller).
    float thin_below_px = 3.0f;
    // Most a thinned stroke's survivor grows (linear size); past it the strokes thin without
    // keeping all their area. Growth past about 2x reads as "balloon leaves" (ez-tree).
    float thin_max_growth = 2.0f;
    // Frames over which two overlapping strokes whose eye distances cross change order (V.3,
    // Fig. 31), instead of swapping in one; 0 swaps at once. Stills are unaffected.
    float order_blend_frames = 5.0f;
    // Frames of camera travel over which a stroke's visibility past the opaque surfaces is
    // averaged, so a stroke a silhouette uncovers or hides takes that many frames to change
    // whole; 1 decides it at the frame's time alone. Stills are unaffected.
    int occlusion_frames = 4;
    // Frames of camera travel between the eyes a water stroke traces its mirror from, its
    // colour interpolated between (reflection.h's MirrorLattice); 1 traces every frame from its
    // own eye. Stills are unaffected.
    int reflection_frames = 4;
    GraftalRaster graftal_raster = GraftalRaster::kScanline;
    // Strokes mix as pigments (shading/pigment.h) instead of alpha blending in linear RGB.
    bool pigment_mixing = false;
    // A canvas weave showing through thin paint and catching stroke edges; 0: none.
    float canvas_weave = 0.0f;
    float canvas_thread_px = 3.0f;  // width of a canvas thread, pixels
};

}  // namespace pleinair
