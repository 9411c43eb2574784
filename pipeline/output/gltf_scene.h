// A scene as one glTF 2.0 binary (render --export scene.glb): its terrain, water, rocks and glTF
// meshes, every tree as an instance of its grown member, the sun as a directional light, and
// the camera with its track as an animation.
#pragma once

#include <string>
#include <vector>

#include "pipeline/input/scene.h"
#include "pipeline/shot/built_trees.h"
#include "pipeline/shot/landscape.h"

namespace pleinair {

// How trees drawn from one grown member share its mesh: `gpu` puts every member drawn more
// than once on one node with EXT_mesh_gpu_instancing (three.js, Babylon.js, Unity's glTFast,
// Godot 4 draw them in one call; a client without it shows the first tree alone); `nodes` gives
// each tree its own node over the shared mesh, which every client reads (Blender 3.4 among
// them: linked duplicates), with MSFT_lod's low-detail level.
enum class Instancing { kGpu, kNodes };
bool parse_instancing(const std::string& name, Instancing& out);

struct SceneExport {
    Instancing instancing = Instancing::kGpu;
    // Trees at their low-detail level alone (the trunk and first branches, the leaves that
    // never fade, grown): Mortefontaine's 134 trees take 393 MB in full, 94 MB so.
    bool low_detail = false;
};

// The file's bytes; the same scene gives the same bytes. Surfaces carry their material's
// palette colour (the middle of its lightness range) and, the terrain, texture coordinates over
// its extent; trees are as tree.glb holds them (gltf_tree.h), named FAMILY-MEMBER.
std::string scene_glb(const SceneDesc& scene, const BuiltLandscape& land,
                      const std::vector<BuiltTree>& trees, const SceneExport& options = {});

}  // namespace pleinair
