// particle_input and particle_origin: one particle read from the trees or the landscape.
#include "pipeline/shot/particle_input.h"

#include <glm/geometric.hpp>

#include "shading/surface_shader.h"

namespace pleinair {

namespace {

ParticleInput surface_input(const ParticleSource& shot, size_t chunk, size_t j, MaterialId& mat) {
    ParticleInput in;
    in.kind = SpriteKind::kSurface;
    const SurfaceParticles& S = shot.land.chunks[chunk];
    mat = shot.materials.surface(S.material[j]);
    const SpriteMaterial& m = shot.materials[mat];
    double w = m.shader->sprite_size * shot.land.chunk_size[chunk] *
               inside_size(S.height(j), m.surface->inside_growth);
    // A particle file's own sizes and colours, where it has them.
    const BuiltLandscape::ChunkSource from = chunk < shot.land.chunk_source.size()
                                                 ? shot.land.chunk_source[chunk]
                                                 : BuiltLandscape::ChunkSource{};
    if (from.file) {
        if (!from.file->width.empty()) w = from.file->width[from.first + j];
        if (!from.file->color.empty() && from.color_amount > 0)
            in.own_color = &from.file->color[from.first + j], in.own_amount = from.color_amount;
    }
    if (from.contact) {
        // Deep over most of the disc, lifting only towards the rim (1 - q^2).
        const float q = S.uv(j).x;  // 0 at the foot, 1 at the rim
        in.contact = 1.0f - clamp01(shot.scene.contact.shade) * (1.0f - q * q);
    }
    in.normal = lighting_normal(S.normal(j), S.random_normal(j), m.surface->random_normal_weight);
    in.tangent = surface_stroke_direction(*m.surface, S.normal(j), S.height(j));
    in.width = w;
    in.length = w * m.shader->stroke_aspect * surface_aspect(*m.surface, S.height(j));
    in.label = S.label[j];
    in.surface = &S;
    in.index = j;
    return in;
}

}  // namespace

ParticleInput particle_input(const ParticleSource& shot, size_t item, SpriteKind kind, size_t j,
                             const RayOrigin& o, MaterialId& mat) {
    const std::vector<BuiltTree>& trees = shot.trees;
    if (kind == SpriteKind::kSurface) {
        ParticleInput in = surface_input(shot, item - trees.size(), j, mat);
        in.world = o.world;
        return in;
    }
    ParticleInput in;
    in.kind = kind;
    in.world = o.world;
    const BuiltTree& b = trees[item];
    const TreePlacement& pl = shot.placements[item];
    const Family& fam = shot.scene.families[b.family];
    const bool bark = kind == SpriteKind::kBark;
    mat = bark ? shot.materials.bark(b.family) : shot.materials.leaf(b.family);
    const StrokeShaderParams& p = bark ? fam.bark_shader : fam.leaf_shader;
    in.width = tree_stroke_width(fam, p, b.scale);
    in.length = in.width * p.stroke_aspect;
    if (bark) {
        in.normal = o.normal;
        in.tangent = pl.turn(b.bark().tangent[j]);
        in.label = b.bark().label[j];
        in.tree_id = b.id;
    } else {
        const LeafParticles& L = b.tree().leaves;
        in.normal = pl.turn(L.normal[j]);
        // A falling twig's leaves are painted down along it (shader's hanging_slope); the rest
        // take the shader's stroke_angle (sprites.cpp: no tangent).
        // (Only a falling one can pass: the sine of 0-90 degrees is not negative, so the sine
        // is taken for those alone, not for every leaf every frame.)
        if (p.hanging_slope <= 90.0f && in.normal.y < 0.0f &&
            -in.normal.y > pmath::sin(static_cast<double>(p.hanging_slope) * M_PI / 180.0))
            in.tangent = in.normal;
        in.center_distance = L.center_distance[j];
        in.branch_distance = L.branch_distance[j];
        in.label = L.label[j];
        in.tree_id = b.id;
        const glm::vec3 out = L.position[j] - b.tree().center;
        const float len = glm::length(out);
        if (len > 1e-6f && std::isfinite(len)) in.from_center = pl.turn(out / len);
        in.hole =
            crown_hole(p, L.position[j].x, L.position[j].y, L.position[j].z, L.center_distance[j]);
    }
    return in;
}

RayOrigin particle_origin(const ParticleSource& shot, size_t item, SpriteKind kind, size_t j) {
    const std::vector<BuiltTree>& trees = shot.trees;
    if (kind == SpriteKind::kSurface) {
        const SurfaceParticles& S = shot.land.chunks[item - trees.size()];
        return RayOrigin{glm::dvec3(S.position[j]), S.normal(j), true, shot.surface_lift};
    }
    const BuiltTree& b = trees[item];
    const TreePlacement& pl = shot.placements[item];
    if (kind == SpriteKind::kBark)
        return RayOrigin{
            pl.place(b.bark().position[j]), pl.turn(b.bark().normal[j]), true,
            static_cast<float>(0.02 * shot.scene.families[b.family].params.unit * b.scale)};
    return RayOrigin{pl.place(b.tree().leaves.position[j]), glm::vec3(0.0f), false, 0.0f};
}

size_t item_particles(const ParticleSource& shot, size_t item) {
    const std::vector<BuiltTree>& trees = shot.trees;
    if (item >= trees.size()) return shot.land.chunks[item - trees.size()].size();
    return (shot.bark ? trees[item].bark().size() : 0) + trees[item].tree().leaves.size();
}

size_t particle_slot(const ParticleSource& shot, size_t item, SpriteKind kind, size_t j) {
    if (kind != SpriteKind::kLeaf) return j;
    return shot.bark ? shot.trees[item].bark().size() + j : j;
}

}  // namespace pleinair
