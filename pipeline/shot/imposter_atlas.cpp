// atlas_from_graftals, atlas_from_image and imposter_atlas: cells drawn or cut, then halved level
// by level cell by cell, so no cell bleeds into its neighbours at any level.
#include "pipeline/shot/imposter_atlas.h"

#include <algorithm>
#include <cmath>
#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "generators/rng.h"
#include "pipeline/shot/graftal_draw.h"
#include "pipeline/shot/graftal_instances.h"
#include "pipeline/shot/graftal_raster.h"
#include "shading/color.h"
#include "shading/portable_math.h"

namespace pleinair {

namespace {

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
                            sum += src.texel(c * w + sx, r * h + sy), ++n;
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

}  // namespace

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
            glm::vec4 v = image.texel(x, y);
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

ImposterAtlas imposter_atlas(const ImposterDesc& d) {
    if (!d.atlas_descs.empty())
        return atlas_from_graftals(d.atlas_descs, d.atlas_columns, d.atlas_cell_px);
    return atlas_from_image(d.atlas_source, d.atlas_rows, d.atlas_columns);
}

}  // namespace pleinair
