// keyed_blend and draw_imposter: a quad inverted pixel by pixel into its atlas cell, sampled
// between the two levels that bracket its size, keyed.
#include "pipeline/frame/imposter_draw.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "pipeline/shot/graftal_raster.h"
#include "shading/color.h"
#include "shading/portable_math.h"

namespace pleinair {

namespace {

glm::vec4 cell_sample(const ImposterAtlas& a, int l, int row, int column, float s, float t) {
    const ImposterImage& img = a.levels[static_cast<size_t>(l)];
    const int w = img.width / a.columns, h = img.height / a.rows;
    const float sx = s * w - 0.5f, sy = (1.0f - t) * h - 0.5f;
    const float fx = sx > 0.0f ? std::min(sx, float(w - 1)) : 0.0f;  // NaN: 0
    const float fy = sy > 0.0f ? std::min(sy, float(h - 1)) : 0.0f;
    const int x0 = static_cast<int>(fx), y0 = static_cast<int>(fy);
    const int x1 = std::min(x0 + 1, w - 1), y1 = std::min(y0 + 1, h - 1);
    const float ax = fx - x0, ay = fy - y0;
    const int bx = column * w, by = row * h;
    // Most of a cell is empty: no blend where none of the four texels is drawn.
    if (img.texel(bx + x0, by + y0).w == 0 && img.texel(bx + x1, by + y0).w == 0 &&
        img.texel(bx + x0, by + y1).w == 0 && img.texel(bx + x1, by + y1).w == 0)
        return glm::vec4(0.0f);
    const glm::vec4 top = img.texel(bx + x0, by + y0) * (1 - ax) + img.texel(bx + x1, by + y0) * ax;
    const glm::vec4 bot = img.texel(bx + x0, by + y1) * (1 - ax) + img.texel(bx + x1, by + y1) * ax;
    return top * (1 - ay) + bot * ay;
}

double cross2(const glm::dvec2& a, const glm::dvec2& b) { return a.x * b.y - a.y * b.x; }

// linear_to_srgb from a table of 4096 steps, interpolated: three of them a pixel were half an
// imposter's cost through pow, and the patch keeps 8 bits (the table is within 1e-4 of it).
float to_srgb(float c) {
    static const std::array<float, 4098> table = [] {
        std::array<float, 4098> t{};
        for (int i = 0; i <= 4096; ++i) t[size_t(i)] = linear_to_srgb(float(i) / 4096.0f);
        t[4097] = t[4096];
        return t;
    }();
    const float x = (c > 0.0f ? std::min(c, 1.0f) : 0.0f) * 4096.0f;  // NaN: 0
    const int i = static_cast<int>(x);
    return table[size_t(i)] + (table[size_t(i) + 1] - table[size_t(i)]) * (x - float(i));
}

// (s, t) of screen point p in the bilinear quad a (0,0), b (1,0), c (1,1), d (0,1) (Quilez's
// inverse); false outside it.
bool inverse_bilinear(const glm::dvec2& p, const glm::dvec2& a, const glm::dvec2& b,
                      const glm::dvec2& c, const glm::dvec2& d, double& s, double& t) {
    const glm::dvec2 e = b - a, f = d - a, g = a - b + c - d, h = p - a;
    const double k2 = cross2(g, f), k1 = cross2(e, f) + cross2(h, g), k0 = cross2(h, e);
    auto solve_s = [&](double tt) {
        const glm::dvec2 den = e + g * tt, num = h - f * tt;
        const double dd = glm::dot(den, den);
        return dd > 0 ? glm::dot(num, den) / dd : -1.0;
    };
    auto inside = [](double x) { return x >= 0.0 && x <= 1.0; };
    if (std::abs(k2) < 1e-9 * (std::abs(k1) + 1e-30)) {
        if (k1 == 0) return false;
        t = -k0 / k1, s = solve_s(t);
        return inside(s) && inside(t);
    }
    double w = k1 * k1 - 4.0 * k0 * k2;
    if (w < 0) return false;
    w = std::sqrt(w);
    const double ik2 = 0.5 / k2;
    t = (-k1 - w) * ik2, s = solve_s(t);
    if (inside(s) && inside(t)) return true;
    t = (-k1 + w) * ik2, s = solve_s(t);
    return inside(s) && inside(t);
}

}  // namespace

glm::vec4 keyed_blend(const glm::vec4& s, const glm::vec3& surface) {
    if (!(s.w > 0.0f)) return glm::vec4(0.0f);
    const float key = std::clamp(s.x / s.w, 0.0f, 1.0f);
    // lerp((0, g, b), surface, key), premultiplied by alpha.
    const glm::vec3 rgb = glm::vec3(0.0f, s.y, s.z) * (1.0f - key) + surface * (key * s.w);
    return glm::vec4(rgb, s.w);
}

GraftalPatch draw_imposter(const ImposterAtlas& a, const ImposterQuad& q, const Camera& cam,
                           int max_px) {
    if (a.levels.empty() || q.row < 0 || q.row >= a.rows || q.column < 0 || q.column >= a.columns ||
        !(q.opacity > 0.0f))
        return {};
    const glm::dvec3 world[4] = {q.v0, q.v1, q.t1, q.t0};  // a, b, c, d of the inverse
    glm::dvec2 p[4];
    for (int i = 0; i < 4; ++i) {
        const Projection pr = project(cam, world[i]);
        if (!pr.in_front || !(pr.depth > cam.near_depth) || !std::isfinite(pr.x) ||
            !std::isfinite(pr.y))
            return {};
        p[i] = glm::dvec2(pr.x, pr.y);
    }
    const float opacity = q.opacity;
    double lo_x = 1e300, lo_y = 1e300, hi_x = -1e300, hi_y = -1e300;
    for (const glm::dvec2& v : p) {
        lo_x = std::min(lo_x, v.x), hi_x = std::max(hi_x, v.x);
        lo_y = std::min(lo_y, v.y), hi_y = std::max(hi_y, v.y);
    }
    GraftalPatch patch = patch_over(lo_x, lo_y, hi_x, hi_y, cam, max_px);
    if (patch.empty()) return {};
    const int x0 = patch.x0, y0 = patch.y0;
    // The quad's exact share of each pixel (its sides are straight on screen even when it is
    // bilinear), so a quad turning edge-on keeps the ink its area gives, however thin.
    CoverageRaster raster(patch.width, patch.height);
    const glm::dvec2 origin(x0, y0);
    raster.polygon({p[0] - origin, p[1] - origin, p[2] - origin, p[3] - origin});
    std::vector<float> cover;
    raster.coverage(cover);
    // The level whose texels are a pixel's size along the quad's longer reach, and the next.
    const double along = std::max(glm::length(p[1] - p[0]), glm::length(p[2] - p[3]));
    const double up = std::max(glm::length(p[3] - p[0]), glm::length(p[2] - p[1]));
    const double texels = std::max(a.cell_w / std::max(along, 1e-9), a.cell_h / std::max(up, 1e-9));
    const double lod =
        std::clamp(pmath::log2(std::max(texels, 1.0)), 0.0, double(a.levels.size() - 1));
    const int l0 = static_cast<int>(lod), l1 = std::min(l0 + 1, int(a.levels.size()) - 1);
    const float lf = static_cast<float>(lod - l0);
    // Where a pixel's centre falls in the cell: an affine inverse for a parallelogram on screen
    // to within a twentieth of a pixel (the usual case: both ends are extruded alike and an
    // imposter is small against its distance), else the bilinear one; a centre outside the quad
    // (a pixel it only partly covers) reads the nearest point of the cell.
    const glm::dvec2 e = p[1] - p[0], f = p[3] - p[0];
    const double det = cross2(e, f);
    const bool flat = std::abs(det) > 1e-12;
    const bool affine = flat && glm::length(p[0] - p[1] + p[2] - p[3]) < 0.05;
    bool any = false;
    for (int y = 0; y < patch.height; ++y)
        for (int x = 0; x < patch.width; ++x) {
            const float c = cover[static_cast<size_t>(y) * patch.width + x] * opacity;
            if (!(c * 255.0f >= 0.5f)) continue;
            const glm::dvec2 at(x0 + x + 0.5, y0 + y + 0.5);
            double s = 0.5, t = 0.5;
            if (affine || !inverse_bilinear(at, p[0], p[1], p[2], p[3], s, t)) {
                if (flat) {
                    const glm::dvec2 h = at - p[0];
                    s = cross2(h, f) / det, t = cross2(e, h) / det;
                }
                s = std::clamp(s, 0.0, 1.0), t = std::clamp(t, 0.0, 1.0);
            }
            const float fs = static_cast<float>(s), ft = static_cast<float>(t);
            glm::vec4 tex = cell_sample(a, l0, q.row, q.column, fs, ft);
            if (lf > 0) tex += (cell_sample(a, l1, q.row, q.column, fs, ft) - tex) * lf;
            // The colour texture read at each end, carried across (file 002: an imposter may
            // cross a colour boundary).
            const glm::vec4 k = keyed_blend(tex, q.color0 + (q.color1 - q.color0) * fs);
            const float al = std::min(1.0f, k.w * c);
            if (!(al * 255.0f >= 0.5f)) continue;
            const glm::vec3 straight = glm::vec3(k) / k.w;
            auto channel = [&](float v, int shift) {
                return std::min(static_cast<uint32_t>(v * 255.0f + 0.5f), 255u) << shift;
            };
            patch.pixels[static_cast<size_t>(y) * patch.width + x] =
                channel(al, 24) | channel(to_srgb(straight.x) * al, 16) |
                channel(to_srgb(straight.y) * al, 8) | channel(to_srgb(straight.z) * al, 0);
            any = true;
        }
    if (!any) return {};
    return patch;
}

}  // namespace pleinair
