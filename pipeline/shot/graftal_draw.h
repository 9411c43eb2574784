// One graftal drawn for one frame: its example's primitives carried through its local frame to
// the screen and rasterised, antialiased (by pleinair's scanline coverage or by Cairo), into a
// small patch that the compositor lays into the frame's tiles in depth order with the strokes
// (composite.cpp).
#pragma once

#include <cstdint>
#include <vector>

#include "pipeline/input/camera.h"
#include "pipeline/input/graftal_desc.h"
#include "pipeline/input/settings.h"
#include "pipeline/shot/graftal_instances.h"
#include "pipeline/shot/graftal_lod.h"

namespace pleinair {

// The pixels [x0, x0 + width) x [y0, y0 + height) of the frame that a graftal touches, in
// Cairo's ARGB32: premultiplied sRGB, 8 bits a channel, alpha in the top byte. Drawn in sRGB
// as a designer's drawing program draws (its colours are the file's 8-bit colours exactly);
// the compositor turns each pixel back to linear light.
struct GraftalPatch {
    int x0 = 0, y0 = 0, width = 0, height = 0;
    std::vector<uint32_t> pixels;
    bool empty() const { return pixels.empty(); }
};

// The patch over the frame's pixels that the box [lo_x, hi_x] x [lo_y, hi_y] touches, at most
// max_px a side, its pixels cleared; empty when the box misses the frame.
GraftalPatch patch_over(double lo_x, double lo_y, double hi_x, double hi_y, const Camera& cam,
                        int max_px);

// What the graftals stage decided for one graftal in this frame.
struct GraftalPose {
    float lambda = 0;   // for its primitives' ramps
    float tau = 1;      // its growth: 0 not yet there, 1 fully in (scales it from grow_from)
    float opacity = 1;  // multiplies every primitive's (ρ when alpha_from_rho, times τ)
    float shade = 1;    // multiplies its colours (the sun's light)
};

// The graftal as `cam` sees it; an empty patch when any of its points lies behind the near
// plane or it misses the frame. Pure: the same arguments give the same bytes on any thread.
// `max_px` bounds the patch's side (a larger graftal is cropped), so a graftal at the eye of a
// very large frame cannot ask for a huge buffer.
GraftalPatch draw_graftal(const GraftalDesc& desc, const GraftalInstance& g, const Camera& cam,
                          const GraftalPose& pose, int max_px = 2048,
                          GraftalRaster raster = GraftalRaster::kScanline);

// A graftal's turn about its normal (its variation's angle), as a sine and cosine: worked out
// once per graftal, then applied to each of its points.
struct GraftalTurn {
    double s = 0, c = 1;
};
GraftalTurn graftal_turn(const GraftalInstance& g);

// Where an example's canonical point (x, y, z) goes in the world, relative to the graftal's base
// and before the growth scale: turned about the normal, then carried by the local frame's axes.
glm::dvec3 graftal_point(const GraftalAxes& axes, const GraftalTurn& turn, const glm::vec3& p,
                         float width_scale, float length_scale);

}  // namespace pleinair
