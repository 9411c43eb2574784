// A tree as one glTF 2.0 binary (tree.glb): bark as a textured triangle mesh, leaves as
// alpha-masked crossed cards carrying every particle attribute, the low-detail model as
// MSFT_lod's second level, the preset and seed in extras.
#pragma once

#include <cstdint>
#include <glm/vec2.hpp>
#include <string>
#include <vector>

#include "generators/tree.h"
#include "shading/color.h"
#include "shading/stroke_shader.h"

namespace pleinair {

// What a tree looks like outside the painter: the leaf shader sizes the cards and draws their
// mask; the palettes colour the leaf texture and the bark (contact_sheet's sheet_family gives
// the ones `family -o sheet.png` paints with).
struct TreeLook {
    StrokeShaderParams leaf_shader;
    Palette leaf_palette;
    Palette bark_palette;
    double unit = 1;  // the preset's /unit: world size of a stroke is sprite_size * unit
};

// A triangle mesh as glTF's attributes want it: a vertex per distinct (position, uv).
struct GltfSurface {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;
    std::vector<glm::vec2> uv;
    std::vector<uint32_t> indices;  // counter-clockwise triangles
    std::vector<uint32_t> source;   // per vertex: the mesh vertex or leaf particle it came from
};

// The bark: every quad as two triangles, smooth normals, and cylindrical texture coordinates
// about the limb whose surface is nearest the face (u: 0..1 around it, v: along it in its base
// circumferences, so a tiling bark texture keeps square texels). Vertices are split where u
// wraps around.
GltfSurface bark_surface(const QuadMesh& mesh, const std::vector<BranchInfo>& limbs);

// Two crossed cards per particle in `which`: centred on the particle, the long side along its
// normal (the implied branch's direction), sized as the painter sizes its stroke (sprite_size *
// unit * label jitter * crown edge size, times `grow`), turned about the normal by the label.
// UVs pick one of 16 stroke masks in leaf_texture's atlas by the label.
GltfSurface leaf_cards(const Tree& tree, const TreeLook& look, const std::vector<uint32_t>& which,
                       float grow = 1.0f);

// The leaf atlas: 4 x 4 cells of `cell` pixels, each one stroke of the leaf shader's mask
// (noise thresholded under the rounded edge mask) as alpha, coloured from the leaf palette by
// the noise's lightness. RGBA8, top row first.
std::vector<uint8_t> leaf_texture(const TreeLook& look, int cell = 128);

// The whole file. Level 0 is the render mesh and every leaf; level 1 (MSFT_lod) the low-detail
// mesh and the leaves that never fade, grown to cover the crown's area as the painter grows
// them beyond the far circle. Custom vertex attributes of the leaf cards, one value per card
// vertex from its particle: _BRANCH_DISTANCE, _CENTER_DISTANCE, _LABEL, _TREE_ID, _FADE_BEGIN,
// _FADE_END, _LIMB, _LIMB_LEVEL, _STIFFNESS (floats) and _PIVOT, _PARTICLE_POSITION,
// _PARTICLE_NORMAL (vec3, tree-local).
std::string tree_glb(const Tree& tree, const std::string& preset_name,
                     const WindStiffness& stiffness, const TreeLook& look);

// The pieces tree_glb is made of, for files of many trees (a scene's export).
class GltfBuilder;
struct TreeMaterials {
    int bark = -1, leaves = -1;
};
// The bark and leaf materials of a look (the leaf atlas among its textures), named with
// `prefix`.
TreeMaterials add_tree_materials(GltfBuilder& g, const TreeLook& look,
                                 const std::string& prefix = "");
struct TreeMeshes {
    int lod0 = -1, lod1 = -1;  // meshes; lod1 -1 without a low-detail model
    size_t kept = 0;           // leaves on level 1
};
// `low_only`: the low-detail level alone, as level 0 (a big scene's light export); a tree
// grown without its low-detail mesh gives its control mesh there.
TreeMeshes add_tree_meshes(GltfBuilder& g, const Tree& tree, const std::string& name,
                           const WindStiffness& stiffness, const TreeLook& look,
                           TreeMaterials materials, bool low_only = false);
// A node NAME_LOD0 holding level 0, with level 1 as MSFT_lod's NAME_LOD1 node (in no scene).
int add_tree_lod_node(GltfBuilder& g, const std::string& name, const TreeMeshes& meshes);

}  // namespace pleinair
