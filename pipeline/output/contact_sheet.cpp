// Contact sheets: per member a scene with one tree, a camera fitted to the tree's bounds, the
// frame painted and copied into its cell, and the seed drawn in a small built-in digit font
// (digits are all a label needs, and a font file would be one more thing to install).
#include "pipeline/output/contact_sheet.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <string>

#include "generators/quad_mesh.h"
#include "pipeline/input/graftal_io.h"
#include "pipeline/input/presets.h"
#include "pipeline/input/shader_io.h"
#include "pipeline/shot/landscape.h"
#include "shading/portable_math.h"

namespace pleinair {

void sheet_grid(int n, int width, int height, int& cols, int& rows) {
    cols = rows = 1;
    double best = -1;
    for (int c = 1; c <= std::max(n, 1); ++c) {
        int r = std::max(1, (n + c - 1) / c);
        double w = double(width) / c, h = double(height) / r;
        double score = std::min(w, 0.8 * h);  // trees are taller than wide
        if (score > best) best = score, cols = c, rows = r;
    }
}

namespace {

// 3x5 digits, one row per 3 bits, top row first.
constexpr uint16_t kDigits[10] = {0x7B6F, 0x2C97, 0x73E7, 0x72CF, 0x5BC9,
                                  0x79CF, 0x79EF, 0x7249, 0x7BEF, 0x7BCF};

void draw_label(Frame& f, int x0, int y0, const std::string& text, int scale) {
    const int w = static_cast<int>(text.size()) * 4 * scale + scale, h = 7 * scale;
    auto put = [&](int x, int y, float r, float g, float b) {
        if (x < 0 || y < 0 || x >= f.width || y >= f.height) return;
        float* p = &f.rgba[4 * (static_cast<size_t>(y) * f.width + x)];
        p[0] = r, p[1] = g, p[2] = b, p[3] = 1.0f;
    };
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) put(x0 + x, y0 + y, 0.70f, 0.66f, 0.55f);  // a pale plate
    for (size_t i = 0; i < text.size(); ++i) {
        uint16_t bits = kDigits[text[i] - '0'];
        for (int row = 0; row < 5; ++row)
            for (int col = 0; col < 3; ++col)
                if (bits & (1u << (14 - (row * 3 + col))))
                    for (int dy = 0; dy < scale; ++dy)
                        for (int dx = 0; dx < scale; ++dx)
                            put(x0 + scale + static_cast<int>(i) * 4 * scale + col * scale + dx,
                                y0 + scale + row * scale + dy, 0.03f, 0.03f, 0.025f);
    }
}

}  // namespace

Family sheet_family(const std::string& name, const std::string& preset, const TreeParams& params,
                    const std::string& style) {
    Family family;
    family.name = name;
    family.preset = preset;
    family.params = params;
    ShaderPreset leaves = load_shader_preset("corot-leaves");
    ShaderPreset bark = load_shader_preset("corot-bark");
    family.leaf_shader = leaves.params;
    family.bark_shader = bark.params;
    family.leaf_palette = shader_palette(load_palette(leaves.palette), leaves.params);
    // The species' bark where its preset names one (the birch's white), as a scene paints it;
    // a name that finds no palette is the preset file's error.
    family.bark_palette =
        shader_palette(params.bark_palette.empty()
                           ? load_palette(bark.palette)
                           : load_palette(params.bark_palette, resolve_tree_preset(preset).string(),
                                          "/bark_palette"),
                       bark.params);
    if (style != "strokes") {
        family.style = style;
        family.graftal = std::make_shared<const GraftalDesc>(load_graftal(style, "--style"));
    }
    return family;
}

CameraParams side_camera(const BuiltTree& b, int width, int height) {
    std::vector<glm::vec3> pts = b.tree().render.positions;
    pts.insert(pts.end(), b.tree().leaves.position.begin(), b.tree().leaves.position.end());
    Bounds bb = bounds_of(pts);
    glm::dvec3 c = b.position + glm::dvec3(0.5f * (bb.min + bb.max));
    glm::dvec3 half = glm::dvec3(0.5f * (bb.max - bb.min));
    double across = std::max(pmath::hypot(half.x, half.z), 1e-6), up = std::max(half.y, 1e-6);
    const double fov = 30.0;
    double tan_v = pmath::tan(0.5 * fov * M_PI / 180.0);
    double tan_h = tan_v * width / height;
    double d = 0.5 * across + 1.08 * std::max(across / tan_h, up / tan_v);
    CameraParams cp;
    cp.look_at = c;
    cp.position = c + glm::dvec3(0.0, 0.1 * up, d);
    cp.fov = fov;
    cp.width = width;
    cp.height = height;
    return cp;
}

Frame paint_alone(const SceneDesc& scene, const BuiltTree& b, const CameraParams& cp, bool aovs,
                  FrameReport* report) {
    SceneDesc s = scene;
    make_camera(cp, s.camera);
    s.camera_params = cp;
    // The tree stands in the ground as in a scene: touches of it about its foot.
    auto land = std::make_shared<BuiltLandscape>();
    add_contact(s, {TreeFoot{b.position, b.scale}}, *land);
    const Shot shot = build_shot(std::move(s), std::make_shared<const std::vector<BuiltTree>>(1, b),
                                 std::move(land));
    return paint_frame(shot, still_view(shot.scene), scene_frame_settings(shot.scene, aovs),
                       report);
}

Frame paint_contact_sheet(const Family& family, const std::vector<Tree>& trees,
                          const SheetOptions& o, FrameReport* report) {
    Frame sheet;
    sheet.width = o.width;
    sheet.height = o.height;
    const Color canvas = srgb_to_linear(Color(0.86f, 0.82f, 0.72f));
    sheet.rgba.resize(4 * static_cast<size_t>(o.width) * o.height);
    for (size_t i = 0; i < sheet.rgba.size(); i += 4)
        sheet.rgba[i] = canvas.x, sheet.rgba[i + 1] = canvas.y, sheet.rgba[i + 2] = canvas.z,
        sheet.rgba[i + 3] = 1.0f;
    int cols, rows;
    sheet_grid(static_cast<int>(trees.size()), o.width, o.height, cols, rows);
    const int cell_w = (o.width - (cols + 1) * o.gap) / cols;
    const int cell_h = (o.height - (rows + 1) * o.gap) / rows;
    if (cell_w < 8 || cell_h < 8) return sheet;

    SceneDesc scene;
    scene.families = {family};
    scene.build = o.build;
    scene.render = o.render;
    scene.has_atmosphere = false;
    scene.contact.material = static_cast<int32_t>(add_ground_material(scene, ""));
    const bool bark = o.build.bark_coverage > 0;
    // Cells are independent: painted in parallel (each also parallel inside), each into its own
    // part of the sheet, so the bytes do not depend on threads.
    std::vector<FrameReport> reports(trees.size());
    tbb::parallel_for(size_t{0}, trees.size(), [&](size_t i) {
        BuiltTree b;
        b.tree() = trees[i];
        b.id = trees[i].id;
        b.position = b.tree().origin;
        if (bark) b.bark() = family_bark(family, b.tree(), o.build.bark_coverage, b.tree().seed);
        // The cell's camera frames its tree, so each cell is a shot of its own.
        Frame cell = paint_alone(scene, b, side_camera(b, cell_w, cell_h), false, &reports[i]);
        const int cx = o.gap + static_cast<int>(i % cols) * (cell_w + o.gap);
        const int cy = o.gap + static_cast<int>(i / cols) * (cell_h + o.gap);
        for (int y = 0; y < cell_h; ++y)
            std::copy_n(&cell.rgba[4 * static_cast<size_t>(y) * cell_w], 4 * cell_w,
                        &sheet.rgba[4 * (static_cast<size_t>(cy + y) * o.width + cx)]);
        int scale = std::clamp(cell_h / 120, 1, 4);
        draw_label(sheet, cx + 2 * scale, cy + cell_h - 9 * scale, std::to_string(b.tree().seed),
                   scale);
    });
    if (report)
        for (const FrameReport& rep : reports) {
            report->leaf_sprites += rep.leaf_sprites;
            report->bark_sprites += rep.bark_sprites;
            report->graftal_sprites += rep.graftal_sprites;
            report->fragments += rep.fragments;
            report->culled += rep.culled;
        }
    return sheet;
}

}  // namespace pleinair
