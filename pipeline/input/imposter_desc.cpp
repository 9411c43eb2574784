// Graftal imposters' atlas, textures and drawing: atlas cells drawn from graftal descriptions or
// cut from an image, halved level by level cell by cell, and one imposter's quad inverted
// pixel by pixel into its cell (file 002's equations 5.9.2-5.9.5) and keyed.
#include "pipeline/input/imposter_desc.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "generators/rng.h"
#include "pipeline/input/camera.h"
#include "pipeline/shot/graftal_instances.h"
#include "pipeline/shot/graftal_raster.h"
#include "shading/color.h"
#include "shading/portable_math.h"

namespace pleinair {

namespace {

glm::vec4 texel(const ImposterImage& img, int x, int y) {
    return img.pixels[static_cast<size_t>(y) * img.width + x];
}

// Each cell of `src` (rows x columns cells of w x h) halved on its own, so no cell bleeds into
// its neighbours at any level.
ImposterImage halve(const ImposterImage& src, int rows, int columns, int w, int h, int& w2,
                    int& h2) {
    // Rounded up, so an odd cell's last row (its base) is read too.
    w2 = std::max(1, (w + 1) / 2), h2 = std::max(1, (h + 1) / 2);
    ImposterImage out;
    out.width = columns * w2, out.height = rows * h2;
    out.pixels.assign(static_cast<size_t>(out.width) * out.height, glm::vec4(0.0f));
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < columns; ++c)
            for (int y = 0; y < h2; ++y)
                for (int x = 0; x < w2; ++x) {
                    glm::vec4 sum(0.0f);
                    int n = 0;
                    for (int dy = 0; dy < 2; ++dy)
                        for (int dx = 0; dx < 2; ++dx) {
                            const int sx = std::min(2 * x + dx, w - 1),
                                      sy = std::min(2 * y + dy, h - 1);
                            sum += texel(src, c * w + sx, r * h + sy), ++n;
                        }
                    out.pixels[static_cast<size_t>(r * h2 + y) * out.width + c * w2 + x] =
                        sum / float(n);
                }
    return out;
}

void build_levels(ImposterAtlas& a) {
    int w = a.cell_w, h = a.cell_h;
    while (w > 1 || h > 1) {
        int w2 = 0, h2 = 0;
        ImposterImage next = halve(a.levels.back(), a.rows, a.columns, w, h, w2, h2);
        a.levels.push_back(std::move(next));
        w = w2, h = h2;
    }
}

// Bilinear inside one cell of level `l` at (s, t): s across from v0 to v1, t from the base (the
// cell's bottom row) to the tip (its top).
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
    if (texel(img, bx + x0, by + y0).w == 0 && texel(img, bx + x1, by + y0).w == 0 &&
        texel(img, bx + x0, by + y1).w == 0 && texel(img, bx + x1, by + y1).w == 0)
        return glm::vec4(0.0f);
    const glm::vec4 top =
        texel(img, bx + x0, by + y0) * (1 - ax) + texel(img, bx + x1, by + y0) * ax;
    const glm::vec4 bot =
        texel(img, bx + x0, by + y1) * (1 - ax) + texel(img, bx + x1, by + y1) * ax;
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

glm::vec4 ImposterImage::sample(float u, float v, bool wrap_u) const {
    if (empty()) return glm::vec4(0.0f);
    if (!std::isfinite(u)) u = 0;
    if (!std::isfinite(v)) v = 0;
    if (wrap_u) {
        u -= std::floor(u);
    } else {
        // Clamped: the texel centres at either side hold to the edge.
        u = std::clamp(u, 0.5f / width, 1.0f - 0.5f / width);
    }
    const float fx = u * width - 0.5f;
    const float fy = std::clamp(v * height - 0.5f, 0.0f, float(height - 1));
    const int x0 = static_cast<int>(std::floor(fx)), y0 = static_cast<int>(fy);
    const float ax = fx - std::floor(fx), ay = fy - y0;
    const int xa = (x0 % width + width) % width, xb = (xa + 1) % width;
    const int y1 = std::min(y0 + 1, height - 1);
    const glm::vec4 top = texel(*this, xa, y0) * (1 - ax) + texel(*this, xb, y0) * ax;
    const glm::vec4 bot = texel(*this, xa, y1) * (1 - ax) + texel(*this, xb, y1) * ax;
    return top * (1 - ay) + bot * ay;
}

ImposterAtlas atlas_from_graftals(const std::vector<GraftalDesc>& descriptions, int columns,
                                  int cell_px) {
    ImposterAtlas a;
    a.rows = std::max<int>(1, static_cast<int>(descriptions.size()));
    a.columns = std::max(1, columns);
    a.cell_w = a.cell_h = std::max(1, cell_px);
    ImposterImage img;
    img.width = a.columns * a.cell_w, img.height = a.rows * a.cell_h;
    img.pixels.assign(static_cast<size_t>(img.width) * img.height, glm::vec4(0.0f));
    for (size_t r = 0; r < descriptions.size(); ++r) {
        // The key: fills red, outlines their own colour with red taken out.
        GraftalDesc d = descriptions[r];
        d.frame = GraftalFrame::kView;
        for (GraftalExample& ex : d.examples)
            for (GraftalPrimitive& p : ex.primitives) {
                p.color = glm::vec3(1, 0, 0);
                p.outline_color = glm::vec3(0, p.outline_color.y, p.outline_color.z);
            }
        for (int c = 0; c < a.columns; ++c) {
            const GraftalExample& ex = d.examples[static_cast<size_t>(c) % d.examples.size()];
            GraftalInstance inst;
            inst.example = static_cast<uint16_t>(static_cast<size_t>(c) % d.examples.size());
            Rng rng = make_rng(0x61746c6173ull /* "atlas" */, Purpose::kImposter, r, c);
            inst.length = static_cast<float>(rand_range(rng, -1, 1) * d.variation.length + 1);
            inst.width = static_cast<float>(rand_range(rng, -1, 1) * d.variation.width + 1);
            // The example's canonical box (widths and outlines as a margin), fitted to the cell
            // with its base (y = 0) on the cell's bottom row.
            float lo_x = 0, hi_x = 0, hi_y = 1e-3f, margin = 0;
            for (const glm::vec3& v : ex.vertices)
                lo_x = std::min(lo_x, v.x), hi_x = std::max(hi_x, v.x), hi_y = std::max(hi_y, v.y);
            for (const GraftalPrimitive& p : ex.primitives) {
                margin = std::max(margin, p.outline_width);
                for (float w : p.widths) margin = std::max(margin, 0.5f * w);
            }
            lo_x = (lo_x - margin) * inst.width, hi_x = (hi_x + margin) * inst.width;
            const float top = (hi_y + margin) * inst.length;
            const double scale = 0.96 * std::min(double(a.cell_h) / top,
                                                 double(a.cell_w) / std::max(hi_x - lo_x, 1e-3f));
            Camera cam;
            const double dist = 1000.0;
            cam.width = a.cell_w, cam.height = a.cell_h;
            cam.focal_px = scale * dist;
            cam.focus_distance = dist;
            cam.eye = glm::dvec3(0.5 * (lo_x + hi_x), 0.5 * a.cell_h / scale, dist);
            GraftalPose pose;
            pose.lambda = 1e6f;  // every primitive at its full detail
            const GraftalPatch p = draw_graftal(d, inst, cam, pose, 4096);
            for (int y = 0; y < p.height; ++y)
                for (int x = 0; x < p.width; ++x) {
                    const uint32_t px = p.pixels[static_cast<size_t>(y) * p.width + x];
                    const float al = float(px >> 24) / 255.0f;
                    if (!(al > 0)) continue;
                    auto straight = [&](int shift) {
                        return std::min(1.0f, float((px >> shift) & 0xffu) / 255.0f / al);
                    };
                    const glm::vec4 v(straight(16) * al, srgb_to_linear(straight(8)) * al,
                                      srgb_to_linear(straight(0)) * al, al);
                    img.pixels[static_cast<size_t>(int(r) * a.cell_h + p.y0 + y) * img.width +
                               c * a.cell_w + p.x0 + x] = v;
                }
        }
    }
    a.levels.push_back(std::move(img));
    build_levels(a);
    return a;
}

ImposterAtlas atlas_from_image(const ImposterImage& image, int rows, int columns) {
    ImposterAtlas a;
    a.rows = std::max(1, rows), a.columns = std::max(1, columns);
    a.cell_w = std::max(1, image.width / a.columns), a.cell_h = std::max(1, image.height / a.rows);
    ImposterImage img;
    img.width = a.cell_w * a.columns, img.height = a.cell_h * a.rows;
    img.pixels.resize(static_cast<size_t>(img.width) * img.height);
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            glm::vec4 v = texel(image, x, y);
            const float al = std::clamp(v.w, 0.0f, 1.0f);
            // Straight in the file; premultiplied (green and blue to linear light) here.
            v = glm::vec4(std::clamp(v.x, 0.0f, 1.0f) * al,
                          srgb_to_linear(std::clamp(v.y, 0.0f, 1.0f)) * al,
                          srgb_to_linear(std::clamp(v.z, 0.0f, 1.0f)) * al, al);
            img.pixels[static_cast<size_t>(y) * img.width + x] = v;
        }
    a.levels.push_back(std::move(img));
    build_levels(a);
    return a;
}

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

glm::vec2 imposter_uv(ImposterUv uv, const glm::vec3& p, const glm::vec3& lo, const glm::vec3& hi) {
    const glm::vec3 size = glm::max(hi - lo, glm::vec3(1e-6f));
    if (uv == ImposterUv::kPlan) return {(p.x - lo.x) / size.x, (p.z - lo.z) / size.z};
    const glm::vec3 c = 0.5f * (lo + hi);
    const float angle = static_cast<float>(pmath::atan2(double(p.z - c.z), double(p.x - c.x)));
    // v up the height: 0 at the bottom (the texture's last row), 1 at the top (its first).
    return {angle * (0.5f / 3.14159265f) + 0.5f, std::clamp((p.y - lo.y) / size.y, 0.0f, 1.0f)};
}

int control_row(const ImposterDesc& d, const glm::vec2& uv) {
    if (!d.control.empty()) {
        const glm::vec4 c = d.control.sample(uv.x, 1.0f - uv.y, d.uv == ImposterUv::kCylinder);
        if (c.w < 0.5f) return -1;
        return c.x >= c.y && c.x >= c.z ? 0 : c.y >= c.z ? 1 : 2;
    }
    if (d.rows.empty()) return 0;
    const size_t i = std::min(d.rows.size() - 1,
                              static_cast<size_t>(std::clamp(uv.y, 0.0f, 1.0f) * d.rows.size()));
    return d.rows[i];
}

}  // namespace pleinair
