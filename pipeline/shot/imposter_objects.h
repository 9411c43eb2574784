// The meshes that carry graftal imposters (file 002), with everything about them that no view
// changes, built once per shot; the frame's imposters stage (frame/imposter_stage.h) finds their
// silhouettes.
#pragma once

#include <cstdint>
#include <glm/mat3x3.hpp>
#include <memory>
#include <vector>

#include "pipeline/input/imposter_desc.h"
#include "pipeline/input/scene.h"
#include "pipeline/shot/built_trees.h"
#include "pipeline/shot/imposter_atlas.h"
#include "pipeline/shot/landscape.h"
#include "pipeline/shot/silhouette.h"

namespace pleinair {

// A mesh that carries imposters, with everything about it that no view changes: its edges and
// their faces, unit face normals, each edge's atlas row (-1: none), each vertex's colour and each
// edge's direction, all in the mesh's own frame; world = position + linear x p.
struct ImposterObject {
    std::shared_ptr<const ImposterDesc> desc;
    std::shared_ptr<const ImposterAtlas> atlas;  // drawn once per description in the shot
    const QuadMesh* mesh = nullptr;  // the shot's (a tree's render or control mesh, a rock, the
                                     // terrain)
    glm::dvec3 position{0.0};
    glm::dmat3 linear{1.0};
    double scale = 1;   // world units per unit of the mesh
    double height = 0;  // world length of the extrusion
    std::vector<MeshEdge> edges;
    std::vector<glm::vec3> normals;  // unit, per face
    // Per edge: the control texture at its middle, thinned by `coverage`. The paper reads it at
    // the front face's centre; per edge, an edge keeps its row whichever face turns to the eye,
    // so nothing appears or goes as the silhouette passes over it.
    std::vector<int8_t> rows;
    std::vector<glm::vec3> colors;      // linear, per vertex
    std::vector<glm::vec3> directions;  // unit, per edge
    uint32_t object_id = 0;  // the sprites' object id (a tree's, a rock's, the terrain's)
    uint64_t key = 0;        // its columns' hash seed
};

// One object's fixed parts, from its description and mesh; excluded faces are those the
// scene paints otherwise (another material, under water): `excluded` per face, or empty. An
// edge carries imposters only if no face of it is excluded. `atlas`: the description's, drawn
// once and shared (drawn here when null).
ImposterObject make_imposter_object(std::shared_ptr<const ImposterDesc> desc, const QuadMesh& mesh,
                                    const glm::dvec3& position, const glm::dmat3& linear,
                                    double scale, uint32_t object_id, uint64_t key,
                                    const std::vector<bool>& excluded = {},
                                    std::shared_ptr<const ImposterAtlas> atlas = nullptr);

// Once per shot: every family's trees whose family names imposters, every rock whose material
// does, and the terrain where its material does (above any water).
std::vector<ImposterObject> build_imposters(const SceneDesc& scene,
                                            const std::vector<BuiltTree>& trees,
                                            const std::vector<TreePlacement>& placements,
                                            const BuiltLandscape& land);

}  // namespace pleinair
