// The typed material table of a shot: every stroke shader with its palette, edge table and
// surface section loaded once, looked up by leaf(family), bark(family) and surface(material).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "pipeline/input/scene.h"
#include "shading/dry_brush.h"

namespace pleinair {

// What a sprite is: a leaf, a bark stroke on a limb, or a stroke of a surface (grass, earth,
// water, rock). Stated by whoever makes the sprite, never inferred from its other fields.
// kGraftal: a graftal's patch drawn by the graftals stage (graftal_stage.h), not a stroke; it
// has no material. kSky: a stroke of the painted sky (sky_sprites.h), at infinity.
enum class SpriteKind : uint8_t { kLeaf, kBark, kSurface, kGraftal, kSky };

// A stroke shader ready to paint: its parameters, palette and edge table (the shader's own
// stroke_fullness, tabulated once).
struct SpriteMaterial {
    SpriteKind kind = SpriteKind::kLeaf;
    // Owned by the table (shared by its copies), so a shot can move or be copied: a table that
    // pointed into its scene broke when the shot holding both moved (issue 24: animate's sky).
    std::shared_ptr<const StrokeShaderParams> shader;
    std::shared_ptr<const Palette> palette;
    std::shared_ptr<const SurfaceShaderParams> surface;  // surface materials only
    EdgeTable edge;
    DryBrushTable dry_brush;  // how its strokes fade (composite.cpp)
    // The luminance of the palette's middle colour: a particle's own colour is painted relative
    // to it (StrokeConstants::own).
    float mid_luminance = 1;
};

// An index into a MaterialTable.
struct MaterialId {
    uint32_t index = 0;
    bool operator==(const MaterialId&) const = default;
};

// Built once from a scene; holds its own copy of every shader and palette, so it does not
// depend on where the scene lives.
class MaterialTable {
  public:
    MaterialTable() = default;
    explicit MaterialTable(const SceneDesc& scene);

    MaterialId leaf(uint32_t family) const { return {2 * family}; }
    MaterialId bark(uint32_t family) const { return {2 * family + 1}; }
    MaterialId surface(uint32_t material) const { return {2 * families_ + material}; }
    // The painted sky's strokes (the scene has a /sky), after the surfaces.
    MaterialId sky() const { return {2 * families_ + surfaces_}; }
    const SpriteMaterial& operator[](MaterialId id) const { return materials_[id.index]; }
    size_t size() const { return materials_.size(); }

  private:
    uint32_t families_ = 0, surfaces_ = 0;
    std::vector<SpriteMaterial> materials_;  // per family leaves then bark; the surfaces; the sky
};

}  // namespace pleinair
