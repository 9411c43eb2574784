// frame_lightness, brush_texture, mean_flat_run, look_regions, mirror_correlation,
// mirror_sources and mirror_match.
#include "pipeline/bench/look_measures.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <limits>

#include "pipeline/bench/palette_look.h"
#include "pipeline/frame/frame_view.h"
#include "pipeline/frame/sprite.h"
#include "pipeline/input/camera.h"
#include "pipeline/shot/shot.h"
#include "shading/color.h"
#include "shading/portable_math.h"

namespace pleinair {

std::vector<float> frame_lightness(const Frame& f) {
    std::vector<float> l(static_cast<size_t>(f.width) * f.height);
    for (size_t i = 0; i < l.size(); ++i) {
        const float y =
            std::max(0.0f, luminance(Color(f.rgba[4 * i], f.rgba[4 * i + 1], f.rgba[4 * i + 2])));
        // CIE L*: the cube root above the linear toe.
        l[i] = y > 0.008856f ? 116.0f * pmath::cbrt(y) - 16.0f : 903.3f * y;
    }
    return l;
}

namespace {

// Calls fn(variance) with L*'s variance in the (2 r + 1)^2 window around each pixel of `mask`
// whose window lies wholly inside it.
template <class Fn>
void window_variances(const std::vector<float>& l, int w, int h, const std::vector<uint8_t>& mask,
                      int r, Fn&& fn) {
    // Summed-area tables of L*, L*^2 and the mask: each window's sums in four reads.
    const size_t W = static_cast<size_t>(w) + 1;
    std::vector<double> s1(W * (h + 1), 0.0), s2(s1.size(), 0.0), sm(s1.size(), 0.0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t i = static_cast<size_t>(y) * w + x, o = (y + 1) * W + (x + 1);
            const double v = mask[i] ? l[i] : 0.0;
            s1[o] = v + s1[o - 1] + s1[o - W] - s1[o - W - 1];
            s2[o] = v * v + s2[o - 1] + s2[o - W] - s2[o - W - 1];
            sm[o] = (mask[i] ? 1.0 : 0.0) + sm[o - 1] + sm[o - W] - sm[o - W - 1];
        }
    auto box = [&](const std::vector<double>& s, int x0, int y0, int x1, int y1) {
        return s[y1 * W + x1] - s[y0 * W + x1] - s[y1 * W + x0] + s[y0 * W + x0];
    };
    const double area = double(2 * r + 1) * double(2 * r + 1);
    for (int y = r; y < h - r; ++y)
        for (int x = r; x < w - r; ++x) {
            const int x0 = x - r, y0 = y - r, x1 = x + r + 1, y1 = y + r + 1;
            if (box(sm, x0, y0, x1, y1) < area) continue;  // the window leaves the region
            const double m = box(s1, x0, y0, x1, y1) / area;
            fn(std::max(0.0, box(s2, x0, y0, x1, y1) / area - m * m));
        }
}

}  // namespace

double brush_texture(const std::vector<float>& l, int w, int h, const std::vector<uint8_t>& mask,
                     int r, uint64_t* count) {
    double sum = 0;
    uint64_t n = 0;
    window_variances(l, w, h, mask, r, [&](double v) { sum += v, ++n; });
    if (count) *count = n;
    return n ? std::sqrt(sum / double(n)) : 0.0;
}

double smooth_share(const std::vector<float>& l, int w, int h, const std::vector<uint8_t>& mask,
                    int r, double max_spread) {
    uint64_t smooth = 0, n = 0;
    const double v_max = max_spread * max_spread;
    window_variances(l, w, h, mask, r, [&](double v) { smooth += v < v_max, ++n; });
    return n ? double(smooth) / double(n) : 0.0;
}

double mean_flat_run(const Frame& f, const std::vector<uint8_t>& mask) {
    auto code = [&](size_t i) {
        uint32_t c = 0;
        for (int k = 0; k < 3; ++k)
            c = c << 8 | static_cast<uint32_t>(
                             std::lround(255.0f * clamp01(linear_to_srgb(f.rgba[4 * i + k]))));
        return c;
    };
    uint64_t runs = 0, pixels = 0;
    for (int y = 0; y < f.height; ++y) {
        uint32_t last = ~0u;
        for (int x = 0; x < f.width; ++x) {
            const size_t i = static_cast<size_t>(y) * f.width + x;
            if (!mask[i]) {
                last = ~0u;
                continue;
            }
            const uint32_t c = code(i);
            runs += c != last;
            ++pixels;
            last = c;
        }
    }
    return runs ? double(pixels) / double(runs) : 0.0;
}

namespace {

// No stroke more than half opaque in front, no surface, the ray above the horizon; and at most
// `max_alpha` of strokes' paint over it (the thin edges of a crown have no id of their own).
// `d`: the camera ray through pixel i.
bool is_open_sky(const Frame& f, size_t i, const glm::dvec3& d, float max_alpha = 1.0f) {
    if (f.object_id[i] != 0.0f || f.depth[i] != std::numeric_limits<float>::max()) return false;
    return f.alpha[i] <= max_alpha && d.y > 0.02;
}

}  // namespace

std::vector<uint8_t> sky_region(const Camera& camera, const Frame& f) {
    std::vector<uint8_t> sky(static_cast<size_t>(f.width) * f.height, 0);
    if (!f.has_aovs) return sky;
    tbb::parallel_for(0, f.height, [&](int y) {
        for (int x = 0; x < f.width; ++x)
            sky[static_cast<size_t>(y) * f.width + x] =
                is_open_sky(f, static_cast<size_t>(y) * f.width + x,
                            ray_direction(camera, x + 0.5, y + 0.5), 0.02f);
    });
    return sky;
}

SkyGamut sky_gamut(const SceneDesc& scene) {
    SkyGamut g;
    auto take = [&](const Color& srgb) {
        for (int c = 0; c < 3; ++c)
            g.lo[c] = std::min(g.lo[c], srgb[c]), g.hi[c] = std::max(g.hi[c], srgb[c]);
    };
    take(scene.background.sky_zenith), take(scene.background.sky_horizon);
    if (scene.sky.present) {
        const Palette& p = scene.sky.palette;
        for (const ColorSpline* s : {&p.dark, &p.mid, &p.light})
            for (const Color& c : s->colors) take(linear_to_srgb(c));
        take(linear_to_srgb(scene.sky.shader.dist_hue_color));
    }
    return g;
}

uint64_t pixels_outside(const Frame& f, const std::vector<uint8_t>& mask, const SkyGamut& g,
                        float margin) {
    uint64_t n = 0;
    for (size_t i = 0; i < mask.size(); ++i) {
        if (!mask[i]) continue;
        const float a = f.rgba[4 * i + 3];
        bool out = false;
        for (int c = 0; c < 3; ++c) {
            // Premultiplied over an opaque background: alpha is 1 in the sky.
            const float v = linear_to_srgb(a > 0 ? f.rgba[4 * i + c] / a : 0.0f);
            out |= !(v >= g.lo[c] - margin && v <= g.hi[c] + margin);
        }
        n += out;
    }
    return n;
}

LookRegions look_regions(const Shot& shot, const FrameView& view, const Frame& f) {
    LookRegions r;
    const size_t n = static_cast<size_t>(f.width) * f.height;
    r.sky.assign(n, 0), r.trees.assign(n, 0), r.water.assign(n, 0), r.near_ground.assign(n, 0);
    if (!f.has_aovs) return r;
    const float water_id = water_stroke_id(shot.scene);
    const float first_surface = static_cast<float>(surface_object_id(0));
    const Camera& cam = view.camera;
    const bool water = shot.scene.water.present && shot.view_rays;
    const MaterialId water_mat = shot.materials.surface(shot.scene.water.material);
    tbb::parallel_for(0, f.height, [&](int y) {
        FlushDenormals ftz;
        for (int x = 0; x < f.width; ++x) {
            const size_t i = static_cast<size_t>(y) * f.width + x;
            const float id = f.object_id[i];
            r.trees[i] = id >= 1.0f && id < first_surface;
            const glm::dvec3 d = ray_direction(cam, x + 0.5, y + 0.5);
            r.sky[i] = is_open_sky(f, i, d);
            if (!shot.view_rays) continue;
            const RayHit h = shot.view_rays->intersect(cam.eye, glm::vec3(d));
            if (!h.hit) continue;
            const ViewSurface& vs = shot.view_surfaces[h.geometry];
            r.water[i] = water && !vs.terrain && vs.material == water_mat;
            // The near ground as a ground stroke paints it (not a tree's stroke in front).
            r.near_ground[i] =
                vs.terrain && h.t < kNearGround && id >= first_surface && id != water_id;
        }
    });
    return r;
}

namespace {

// Pearson's correlation of pairs, summed as they come; 0 under 16 pairs or without spread.
struct Pearson {
    double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
    uint64_t n = 0;
    void add(double a, double b) {
        sa += a, sb += b, saa += a * a, sbb += b * b, sab += a * b, ++n;
    }
    double r() const {
        if (n < 16) return 0.0;
        const double N = static_cast<double>(n);
        const double cov = sab / N - sa / N * sb / N;
        const double va = saa / N - sa / N * sa / N, vb = sbb / N - sb / N * sb / N;
        return va > 0 && vb > 0 ? cov / std::sqrt(va * vb) : 0.0;
    }
};

}  // namespace

double mirror_correlation(const std::vector<float>& l, int w, int h,
                          const std::vector<uint8_t>& water, uint64_t* pairs) {
    Pearson r;
    for (int x = 0; x < w; ++x) {
        int shore = -1;
        for (int y = 0; y < h; ++y) {
            const size_t i = static_cast<size_t>(y) * w + x;
            if (!water[i]) continue;
            if (shore < 0) shore = y;
            const int my = 2 * shore - 1 - y;
            if (my < 0) continue;
            const size_t j = static_cast<size_t>(my) * w + x;
            if (water[j]) continue;
            r.add(l[i], l[j]);
        }
    }
    if (pairs) *pairs = r.n;
    return r.r();
}

float water_stroke_id(const SceneDesc& scene) {
    return static_cast<float>(surface_object_id(scene.water.material));
}

std::vector<uint32_t> mirror_sources(const Frame& f, const Camera& cam, double level,
                                     const std::vector<uint8_t>& water, float water_id) {
    const size_t n = static_cast<size_t>(f.width) * f.height;
    std::vector<uint32_t> src(n, 0);
    if (!f.has_aovs) return src;
    std::vector<float> nearest(n, std::numeric_limits<float>::infinity());
    for (int y = 0; y < f.height; ++y)
        for (int x = 0; x < f.width; ++x) {
            const size_t i = static_cast<size_t>(y) * f.width + x;
            if (water[i] || !(f.depth[i] < std::numeric_limits<float>::max())) continue;
            const glm::dvec3 d = ray_direction(cam, x + 0.5, y + 0.5);
            glm::dvec3 p =
                cam.eye + d * (static_cast<double>(f.depth[i]) / glm::dot(d, cam.forward));
            if (!(p.y > level)) continue;
            p.y = 2.0 * level - p.y;
            const Projection q = project(cam, p);
            if (!q.in_front) continue;
            const double qx = std::floor(q.x), qy = std::floor(q.y);
            for (int dy = 0; dy <= 1; ++dy) {
                if (!(qx >= 0 && qx < f.width && qy + dy >= 0 && qy + dy < f.height)) continue;
                const size_t j = static_cast<size_t>(qy + dy) * f.width + static_cast<size_t>(qx);
                if (!water[j] || f.object_id[j] != water_id || !(q.depth < nearest[j])) continue;
                nearest[j] = q.depth, src[j] = static_cast<uint32_t>(i + 1);
            }
        }
    return src;
}

MirrorMatch mirror_match(const Frame& f, const std::vector<float>& l,
                         const std::vector<uint32_t>& src) {
    MirrorMatch m;
    Pearson px, blocks;
    double lw = 0, ls = 0, cw = 0, cs = 0;
    for (size_t j = 0; j < src.size(); ++j) {
        if (!src[j]) continue;
        const size_t i = src[j] - 1;
        px.add(l[j], l[i]);
        lw += l[j], ls += l[i], cw += pixel_chroma(f, j), cs += pixel_chroma(f, i);
    }
    const int B = kMirrorBlock;
    for (int by = 0; by + B <= f.height; by += B)
        for (int bx = 0; bx + B <= f.width; bx += B) {
            double a = 0, b = 0;
            int c = 0;
            for (int y = by; y < by + B; ++y)
                for (int x = bx; x < bx + B; ++x) {
                    const size_t j = static_cast<size_t>(y) * f.width + x;
                    if (src[j]) a += l[j], b += l[src[j] - 1], ++c;
                }
            if (2 * c >= B * B) blocks.add(a / c, b / c);
        }
    m.pairs = px.n;
    m.pixels = px.r(), m.forms = blocks.r();
    m.lightness = ls > 0 ? lw / ls : 0.0;
    m.chroma = cs > 0 ? cw / cs : 0.0;
    return m;
}

}  // namespace pleinair
