// MaterialTable: the families' leaf and bark shaders, then the scene's surface materials.
#include "pipeline/shot/materials.h"

#include <algorithm>

namespace pleinair {

MaterialTable::MaterialTable(const SceneDesc& scene)
    : families_(static_cast<uint32_t>(scene.families.size())),
      surfaces_(static_cast<uint32_t>(scene.materials.size())) {
    auto add = [&](SpriteKind kind, const StrokeShaderParams& shader, const Palette& palette,
                   const SurfaceShaderParams* surface) {
        materials_.push_back(
            {kind, std::make_shared<const StrokeShaderParams>(shader),
             std::make_shared<const Palette>(palette),
             surface ? std::make_shared<const SurfaceShaderParams>(*surface) : nullptr,
             make_edge_table(shader.stroke_fullness), make_dry_brush_table(shader),
             std::max(luminance(palette_lookup(palette, 0.5f)), 1e-3f)});
    };
    for (const Family& f : scene.families) {
        add(SpriteKind::kLeaf, f.leaf_shader, f.leaf_palette, nullptr);
        add(SpriteKind::kBark, f.bark_shader, f.bark_palette, nullptr);
    }
    for (const Material& m : scene.materials)
        add(SpriteKind::kSurface, m.shader, m.palette, &m.surface);
    if (scene.sky.present) add(SpriteKind::kSky, scene.sky.shader, scene.sky.palette, nullptr);
}

}  // namespace pleinair
