// Graftals to pixels: primitives projected through the graftal's local frame, then filled and
// outlined by pleinair's scanline coverage (graftal_raster.h) or by Cairo (its image backend:
// an exact-area scan converter, no state shared between surfaces). Either way each patch's
// bytes depend on its own arguments alone.
#include "pipeline/shot/graftal_draw.h"

#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

#include "generators/tree_mesh.h"
#include "pipeline/shot/graftal_raster.h"
#include "shading/color.h"
#include "shading/portable_math.h"

namespace pleinair {

namespace {

using Pt = glm::dvec2;

// A shape to fill and, optionally, outline: closed subpaths filled by the winding rule, and one
// polyline stroked over them.
struct Shape {
    std::vector<std::vector<Pt>> fill;
    std::vector<Pt> outline;
    bool outline_closed = false;
    double outline_px = 0;
    glm::vec3 color{0.0f}, outline_color{0.0f};  // sRGB
    float alpha = 1;
};

// A triangle as a subpath turning one way, so overlapping triangles of a strip or fan add up
// under the winding rule instead of cancelling.
std::vector<Pt> oriented(Pt a, Pt b, Pt c) {
    const double cross = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
    if (cross < 0) std::swap(b, c);
    return {a, b, c};
}

// A tapered ribbon along a screen path: each point pushed out by half its width on either side
// of the path's direction there (the mean of its two segments').
std::vector<Pt> ribbon(const std::vector<Pt>& path, const std::vector<double>& width_px) {
    const size_t n = path.size();
    std::vector<Pt> left, right;
    for (size_t i = 0; i < n; ++i) {
        const Pt a = path[i > 0 ? i - 1 : i], b = path[i + 1 < n ? i + 1 : i];
        Pt d = b - a;
        const double len = std::sqrt(d.x * d.x + d.y * d.y);
        d = len > 1e-9 ? d / len : Pt(0, -1);
        const Pt across(-d.y, d.x);
        const double h = 0.5 * width_px[i];
        left.push_back(path[i] + across * h);
        right.push_back(path[i] - across * h);
    }
    std::reverse(right.begin(), right.end());
    left.insert(left.end(), right.begin(), right.end());
    return left;
}

void add_path(cairo_t* cr, const std::vector<Pt>& pts, bool close) {
    if (pts.empty()) return;
    cairo_move_to(cr, pts[0].x, pts[0].y);
    for (size_t i = 1; i < pts.size(); ++i) cairo_line_to(cr, pts[i].x, pts[i].y);
    if (close) cairo_close_path(cr);
}

// The polygon turning the positive way (its signed area >= 0), so that shapes added to one
// coverage buffer add up where they overlap instead of cancelling.
std::vector<Pt> positive(std::vector<Pt> pts) {
    double area = 0;
    for (size_t i = 0; i < pts.size(); ++i) {
        const Pt& a = pts[i];
        const Pt& b = pts[(i + 1) % pts.size()];
        area += a.x * b.y - b.x * a.y;
    }
    if (area < 0) std::reverse(pts.begin(), pts.end());
    return pts;
}

// An outline as polygons: a quad along each segment and an octagon at each vertex (the round
// join and cap), all turning the same way.
void outline_polygons(CoverageRaster& r, const std::vector<Pt>& pts, bool closed, double width) {
    const double h = 0.5 * width;
    const size_t n = pts.size(), segments = closed ? n : n - 1;
    for (size_t i = 0; i < segments; ++i) {
        const Pt a = pts[i], b = pts[(i + 1) % n];
        Pt d = b - a;
        const double len = std::sqrt(d.x * d.x + d.y * d.y);
        if (!(len > 1e-9)) continue;
        d /= len;
        const Pt across(-d.y * h, d.x * h);
        r.polygon(positive({a + across, b + across, b - across, a - across}));
    }
    for (const Pt& c : pts) {
        std::vector<Pt> disc;
        for (int k = 0; k < 8; ++k) {
            // cos and sin of k x 45 degrees, exact enough as constants.
            static const double cs[8][2] = {{1, 0},  {0.70710678118654752, 0.70710678118654752},
                                            {0, 1},  {-0.70710678118654752, 0.70710678118654752},
                                            {-1, 0}, {-0.70710678118654752, -0.70710678118654752},
                                            {0, -1}, {0.70710678118654752, -0.70710678118654752}};
            disc.push_back(c + Pt(cs[k][0] * h, cs[k][1] * h));
        }
        r.polygon(positive(disc));
    }
}

// "Over" of one colour at a coverage into 8-bit premultiplied ARGB, as Cairo's image surface
// holds it.
void over(GraftalPatch& patch, const std::vector<float>& cover, const glm::vec3& color,
          float alpha) {
    for (size_t i = 0; i < cover.size(); ++i) {
        const float a = cover[i] * alpha;
        if (!(a > 0.0f)) continue;
        uint32_t& px = patch.pixels[i];
        const float keep = 1.0f - a;
        // Rounded to the nearest level; every term is in [0, 255.5), so truncation after +0.5
        // rounds (and is much cheaper than lround).
        auto channel = [&](int shift, float src) {
            const float v = src * 255.0f + static_cast<float>((px >> shift) & 0xffu) * keep;
            return std::min(static_cast<uint32_t>(v + 0.5f), 255u) << shift;
        };
        px = channel(24, a) | channel(16, color.x * a) | channel(8, color.y * a) |
             channel(0, color.z * a);
    }
}

void draw_scanline(const std::vector<Shape>& shapes, GraftalPatch& patch) {
    CoverageRaster r(patch.width, patch.height);
    std::vector<float> cover;
    const Pt origin(patch.x0, patch.y0);
    auto local = [&](std::vector<Pt> pts) {
        for (Pt& p : pts) p -= origin;
        return pts;
    };
    for (const Shape& s : shapes) {
        if (!s.fill.empty()) {
            r.clear();
            for (const auto& sub : s.fill) r.polygon(positive(local(sub)));
            r.coverage(cover);
            over(patch, cover, s.color, s.alpha);
        }
        if (!s.outline.empty()) {
            r.clear();
            outline_polygons(r, local(s.outline), s.outline_closed, s.outline_px);
            r.coverage(cover);
            over(patch, cover, s.outline_color, s.alpha);
        }
    }
}

}  // namespace

GraftalPatch patch_over(double lo_x, double lo_y, double hi_x, double hi_y, const Camera& cam,
                        int max_px) {
    // Missing the frame (or not a number): nothing, before any cast to int could overflow.
    if (!(lo_x < cam.width && lo_y < cam.height && hi_x > 0 && hi_y > 0)) return {};
    const int x0 = static_cast<int>(std::floor(std::max(lo_x, 0.0)));
    const int y0 = static_cast<int>(std::floor(std::max(lo_y, 0.0)));
    const int x1 = static_cast<int>(std::ceil(std::min(hi_x, double(cam.width))));
    const int y1 = static_cast<int>(std::ceil(std::min(hi_y, double(cam.height))));
    if (x1 <= x0 || y1 <= y0 || max_px < 1) return {};
    GraftalPatch patch;
    patch.x0 = x0, patch.y0 = y0;
    patch.width = std::min(x1 - x0, max_px), patch.height = std::min(y1 - y0, max_px);
    patch.pixels.assign(static_cast<size_t>(patch.width) * patch.height, 0u);
    return patch;
}

GraftalTurn graftal_turn(const GraftalInstance& g) {
    GraftalTurn t;
    pmath::sincos(double(g.angle) * (3.14159265358979323846 / 180.0), t.s, t.c);
    return t;
}

glm::dvec3 graftal_point(const GraftalAxes& axes, const GraftalTurn& turn, const glm::vec3& p,
                         float width_scale, float length_scale) {
    const double s = turn.s, c = turn.c;
    const double x = double(p.x) * width_scale, y = double(p.y) * length_scale,
                 z = double(p.z) * width_scale;
    // Turned about the normal (y): x towards z by the angle.
    const double xr = c * x - s * z, zr = s * x + c * z;
    return glm::dvec3(axes.x) * xr + glm::dvec3(axes.y) * y + glm::dvec3(axes.z) * zr;
}

GraftalPatch draw_graftal(const GraftalDesc& desc, const GraftalInstance& g, const Camera& cam,
                          const GraftalPose& pose, int max_px, GraftalRaster raster) {
    if (g.example >= desc.examples.size() || !(pose.tau > 0.0f) || !(pose.opacity > 0.0f))
        return {};
    const GraftalExample& ex = desc.examples[g.example];
    const glm::vec3 v(safe_normalize(cam.eye - g.position, -cam.forward));
    const GraftalAxes axes = graftal_axes(desc.frame, g.normal, v, glm::vec3(1, 0, 0));
    const GraftalTurn turn = graftal_turn(g);  // once per graftal, not per vertex
    const float tau = std::min(pose.tau, 1.0f);
    const double length =
        double(g.length) * (desc.tuft.grow_from + (1 - desc.tuft.grow_from) * tau);
    const Projection base = project(cam, g.position);
    if (!base.in_front || !(base.depth > cam.near_depth)) return {};
    const double px_per_world = cam.focal_px / double(base.depth);  // at the graftal's base

    std::vector<Shape> shapes;
    double lo_x = 1e300, lo_y = 1e300, hi_x = -1e300, hi_y = -1e300;
    for (const GraftalPrimitive& prim : ex.primitives) {
        const float lambda = pose.lambda;
        const float alpha = prim.opacity * lod_ramp(prim.opacity_ramp, lambda) * pose.opacity;
        if (!(alpha > 1.0f / 512.0f)) continue;
        const float wscale = g.width * lod_ramp(prim.width_ramp, lambda);
        const float lscale = lod_ramp(prim.length_ramp, lambda);
        std::vector<Pt> pts;
        std::vector<double> depth;
        for (uint32_t i : prim.vertices) {
            if (i >= ex.vertices.size()) return {};
            const glm::dvec3 w =
                g.position + length * graftal_point(axes, turn, ex.vertices[i], wscale, lscale);
            const Projection p = project(cam, w);
            if (!p.in_front || !(p.depth > cam.near_depth) || !std::isfinite(p.x) ||
                !std::isfinite(p.y))
                return {};  // a graftal through the near plane is not drawn at all
            pts.emplace_back(p.x, p.y);
            depth.push_back(p.depth);
        }
        if (pts.size() < 2) continue;
        Shape s;
        s.alpha = std::min(alpha, 1.0f);
        s.color = linear_to_srgb(prim.color * (g.lightness * pose.shade));
        s.outline_color = linear_to_srgb(prim.outline_color * (g.lightness * pose.shade));
        s.outline_px =
            prim.outline_width > 0 ? prim.outline_width * length * wscale * px_per_world : 0.0;
        switch (prim.type) {
            case PrimitiveType::kStroke: {
                std::vector<double> width_px(pts.size());
                for (size_t i = 0; i < pts.size(); ++i) {
                    const double w = i < prim.widths.size() ? prim.widths[i] : 0.0;
                    width_px[i] = w * length * wscale * cam.focal_px / depth[i];
                }
                s.fill.push_back(ribbon(pts, width_px));
                break;
            }
            case PrimitiveType::kStrip:
                for (size_t i = 2; i < pts.size(); ++i)
                    s.fill.push_back(oriented(pts[i - 2], pts[i - 1], pts[i]));
                s.outline = pts;
                break;
            case PrimitiveType::kFan:
                // One path from the centre round the rim: under the winding rule the same area as
                // its triangles wherever the rim turns one way round the centre (a puff, a
                // leaf), at a fraction of the cost of filling each triangle's antialiased edges
                // (BENCHMARKS.md, "Graftals"); a rim folding back over itself is filled once.
                s.fill.push_back(pts);
                // Its rim: the vertices after the centre, closed when the last repeats the first.
                s.outline.assign(pts.begin() + 1, pts.end());
                s.outline_closed =
                    prim.vertices.size() > 2 && prim.vertices.back() == prim.vertices[1];
                if (s.outline_closed) s.outline.pop_back();
                break;
            case PrimitiveType::kPolygon:
                s.fill.push_back(pts);
                s.outline = pts;
                s.outline_closed = true;
                break;
        }
        if (!(s.outline_px > 0)) s.outline.clear();
        const double pad = 0.5 * s.outline_px + 1.0;  // the outline's half width and the filter
        for (const auto& sub : s.fill)
            for (const Pt& p : sub)
                lo_x = std::min(lo_x, p.x - pad), lo_y = std::min(lo_y, p.y - pad),
                hi_x = std::max(hi_x, p.x + pad), hi_y = std::max(hi_y, p.y + pad);
        for (const Pt& p : s.outline)
            lo_x = std::min(lo_x, p.x - pad), lo_y = std::min(lo_y, p.y - pad),
            hi_x = std::max(hi_x, p.x + pad), hi_y = std::max(hi_y, p.y + pad);
        shapes.push_back(std::move(s));
    }
    if (shapes.empty() || !(hi_x > lo_x) || !(hi_y > lo_y)) return {};
    // The patch: the shapes' box, inside the frame and at most max_px a side.
    GraftalPatch patch = patch_over(lo_x, lo_y, hi_x, hi_y, cam, max_px);
    if (patch.empty()) return {};
    const int x0 = patch.x0, y0 = patch.y0;

    if (raster == GraftalRaster::kScanline) {
        draw_scanline(shapes, patch);
        return patch;
    }
    cairo_surface_t* surface = cairo_image_surface_create_for_data(
        reinterpret_cast<unsigned char*>(patch.pixels.data()), CAIRO_FORMAT_ARGB32, patch.width,
        patch.height, 4 * patch.width);
    cairo_t* cr = cairo_create(surface);
    cairo_translate(cr, -x0, -y0);
    cairo_set_fill_rule(cr, CAIRO_FILL_RULE_WINDING);
    cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
    cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
    for (const Shape& s : shapes) {
        if (!s.fill.empty()) {
            cairo_new_path(cr);
            for (const auto& sub : s.fill) add_path(cr, sub, true);
            cairo_set_source_rgba(cr, s.color.x, s.color.y, s.color.z, s.alpha);
            cairo_fill(cr);
        }
        if (!s.outline.empty()) {
            cairo_new_path(cr);
            add_path(cr, s.outline, s.outline_closed);
            cairo_set_line_width(cr, s.outline_px);
            // Round joins cost Cairo an arc at every vertex; on an outline a few pixels wide
            // a bevel covers the same pixels to within the antialiasing.
            cairo_set_line_join(cr,
                                s.outline_px < 4 ? CAIRO_LINE_JOIN_BEVEL : CAIRO_LINE_JOIN_ROUND);
            cairo_set_source_rgba(cr, s.outline_color.x, s.outline_color.y, s.outline_color.z,
                                  s.alpha);
            cairo_stroke(cr);
        }
    }
    cairo_destroy(cr);
    cairo_surface_flush(surface);
    cairo_surface_destroy(surface);
    return patch;
}

}  // namespace pleinair
