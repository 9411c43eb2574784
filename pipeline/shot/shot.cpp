// build_shot: trees and landscape, the material table, the Embree scenes and the sun's stroke
// casters, and (for animations under a still sun) each particle's light.
#include "pipeline/shot/shot.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <limits>
#include <map>
#include <set>

#include "pipeline/shot/cluster_build.h"
#include "pipeline/shot/leaf_basis.h"
#include "shading/pigment.h"
#include "shading/portable_math.h"
#include "shading/surface_shader.h"

namespace pleinair {

namespace {

ShotPlan plan_shot(const SceneDesc& scene, const ShotOptions& options) {
    ShotPlan plan;
    plan.bark = scene.build.bark_coverage > 0;
    const bool meshes = scene.terrain.present || !scene.rocks.empty();
    // Figures cast the sun's shadows as a particle file's strokes do (pipeline/shot/figures.h).
    const bool casting_particles =
        !scene.figures.empty() ||
        std::any_of(scene.particles.begin(), scene.particles.end(),
                    [](const ParticleFileDesc& p) { return p.casts_shadows; });
    plan.shadows = scene.sun_casts_shadows && (meshes || !scene.trees.empty() || casting_particles);
    plan.sun_moves = plan.shadows && !scene.sun_track.empty();
    plan.underpaint = meshes;
    plan.sun_light = plan.shadows && !plan.sun_moves && options.cache_sun_light &&
                     scene.render.shadow_samples == ShadowSamples::kParticle;
    // Wind that blows at some time, over trees: a mean or a key above zero.
    const WindDesc& w = scene.wind;
    plan.wind = w.present && !scene.trees.empty() &&
                (w.strength > 0 || std::any_of(w.track.begin(), w.track.end(),
                                               [](const WindKey& k) { return k.strength > 0; }));
    return plan;
}

std::unique_ptr<RayScene> build_view_scene(const Shot& shot, std::vector<ViewSurface>& surfaces) {
    const BuiltLandscape& land = *shot.land;
    const SceneDesc& scene = shot.scene;
    auto rays = std::make_unique<RayScene>(shot.anchor, shot.limbs.get());
    if (land.has_terrain) rays->add_mesh(land.terrain_mesh), surfaces.push_back({true, {}});
    if (land.has_water)
        rays->add_mesh(land.water_mesh),
            surfaces.push_back({false, shot.materials.surface(scene.water.material)});
    for (size_t i = 0; i < land.rocks.size(); ++i)
        rays->add_mesh(land.rocks[i]),
            surfaces.push_back({false, shot.materials.surface(land.rock_material[i])});
    const std::vector<BuiltTree>& trees = *shot.trees;
    for (size_t i = 0; i < trees.size(); ++i)
        rays->add_instance(shot.limb_mesh[i], shot.placements[i].linear(),
                           shot.placements[i].position),
            surfaces.push_back({false, shot.materials.bark(trees[i].family)});
    rays->commit();
    return rays;
}

}  // namespace

std::vector<StrokeCaster> leaf_casters(const SceneDesc& scene, const BuiltTree& b,
                                       const glm::vec3& sun) {
    std::vector<StrokeCaster> out(b.tree().leaves.size());
    leaf_casters(scene, b, sun, out.data());
    return out;
}

void leaf_casters(const SceneDesc& scene, const BuiltTree& b, const glm::vec3& sun,
                  StrokeCaster* out) {
    const TreePlacement pl = placement(b);
    const StrokeShaderParams& p = scene.families[b.family].leaf_shader;
    const LeafParticles& L = b.tree().leaves;
    const double w = tree_stroke_width(scene.families[b.family], p, b.scale);
    // A frame perpendicular to the sun; each card turned by its stroke's angle jitter.
    glm::vec3 a0, b0;
    sun_card_frame(sun, a0, b0);
    for (size_t j = 0; j < L.size(); ++j) {
        StrokeCaster& c = out[j];
        c.center = pl.place(L.position[j]);
        const float jitter = stroke_size_jitter(p, L.label[j]);
        sun_card_axes(p, L.label[j], a0, b0, c.axis_s, c.axis_t);
        c.half_w = static_cast<float>(0.5 * w * jitter);
        c.half_l = c.half_w * p.stroke_aspect;
        c.noise = noise_of(stroke_constants(p, glm::dot(pl.turn(L.normal[j]), sun),
                                            L.center_distance[j], L.branch_distance[j], L.label[j],
                                            b.id, 1.0f, 0.0f, 0.0f, false, false));
    }
}

MemberCasters member_casters(const Shot& shot, const BuiltTree& b) {
    const Family& family = shot.scene.families[b.family];
    const LeafParticles& L = b.tree().leaves;
    MemberCasters m;
    m.count = L.size();
    m.position = L.position.data();
    m.normal = L.normal.data();
    m.label = L.label.data();
    m.center_distance = L.center_distance.data();
    m.branch_distance = L.branch_distance.data();
    m.stroke_width = static_cast<float>(tree_stroke_width(family, family.leaf_shader, 1.0));
    m.shader = &family.leaf_shader;
    m.edge = &shot.materials[shot.materials.leaf(b.family)].edge;
    return m;
}

std::vector<std::vector<StrokeCaster>> imported_casters(const Shot& shot, const glm::vec3& sun) {
    const SceneDesc& scene = shot.scene;
    const BuiltLandscape& land = *shot.land;
    std::vector<std::vector<StrokeCaster>> out(scene.materials.size());
    glm::vec3 a0, b0;
    sun_card_frame(sun, a0, b0);
    const ParticleSource particles = shot.particles();
    const size_t trees = shot.trees->size();
    for (size_t c = 0; c < land.chunks.size(); ++c) {
        if (c >= land.chunk_source.size() || !land.chunk_source[c].file ||
            !land.chunk_source[c].casts_shadows)
            continue;
        const SurfaceParticles& S = land.chunks[c];
        for (size_t j = 0; j < S.size(); ++j) {
            MaterialId mat;
            const ParticleInput in =
                particle_input(particles, trees + c, SpriteKind::kSurface, j,
                               particle_origin(particles, trees + c, SpriteKind::kSurface, j), mat);
            const StrokeShaderParams& p = *shot.materials[mat].shader;
            // The same card as a leaf stroke's: facing the sun, turned by the stroke's angle
            // jitter, the stroke's size and noise.
            StrokeCaster k;
            k.center = in.world;
            const float jitter = stroke_size_jitter(p, in.label);
            sun_card_axes(p, in.label, a0, b0, k.axis_s, k.axis_t);
            k.half_w = static_cast<float>(0.5 * in.width * jitter);
            k.half_l = k.half_w * p.stroke_aspect *
                       surface_aspect(*shot.materials[mat].surface, S.height(j));
            k.noise = noise_of(stroke_constants(p, glm::dot(in.normal, sun), 0.5f, 0.5f, in.label,
                                                0, 1.0f, 0.0f, 0.0f, false, false));
            out[S.material[j]].push_back(k);
        }
    }
    return out;
}

float sun_light_at(const RayScene& sun_rays, const RayOrigin& o, const glm::vec3& sun,
                   ShadowMode mode) {
    return sun_rays.transmittance(o.lifted(), sun, mode, std::numeric_limits<float>::infinity(),
                                  o.surface_normal());
}

std::unique_ptr<RayScene> build_sun_scene(const Shot& shot, const glm::vec3& sun) {
    const SceneDesc& scene = shot.scene;
    const BuiltLandscape& land = *shot.land;
    const std::vector<BuiltTree>& trees = *shot.trees;
    auto rays = std::make_unique<RayScene>(shot.anchor, shot.limbs.get());
    // Surfaces that grow grass and rock strokes cast shadows though the camera never sees
    // them (IV.7); water casts none.
    if (land.has_terrain) rays->add_mesh(land.terrain_mesh);
    for (const auto& r : land.rocks) rays->add_mesh(r);
    for (size_t i = 0; i < trees.size(); ++i)
        rays->add_instance(shot.limb_mesh[i], shot.placements[i].linear(),
                           shot.placements[i].position);
    // Leaf strokes as cards facing the sun: each tree's member's cards, placed like its limbs
    // (so trees shade each other in the one scene), the cards turned to the sun by the filter.
    for (size_t i = 0; i < trees.size(); ++i)
        if (!trees[i].tree().leaves.position.empty())
            rays->add_caster_instance(shot.limb_mesh[i], shot.placements[i].linear(),
                                      shot.placements[i].position);
    // Particles from other tools cast like leaf strokes, one caster set per material.
    std::vector<std::vector<StrokeCaster>> by_material = imported_casters(shot, sun);
    for (uint32_t m = 0; m < by_material.size(); ++m)
        if (!by_material[m].empty())
            rays->add_casters(by_material[m], scene.materials[m].shader,
                              shot.materials[shot.materials.surface(m)].edge);
    rays->commit();
    return rays;
}

Shot build_shot(SceneDesc scene, const ShotOptions& options) {
    PassTimer timer;
    const ShotPlan plan = plan_shot(scene, options);
    auto trees = std::make_shared<const std::vector<BuiltTree>>(build_trees(scene, plan.bark));
    auto land = std::make_shared<const BuiltLandscape>(build_landscape(scene));
    size_t leaves = 0, bark = 0;
    for (const auto& t : *trees) leaves += t.tree().leaves.size(), bark += t.bark().size();
    PassReport generate{"generate", true,
                        "trees grown from their presets, surfaces turned into strokes", timer.ms(),
                        std::to_string(trees->size()) + " trees, " + std::to_string(leaves) +
                            " leaves, " + std::to_string(bark) + " bark strokes, " +
                            std::to_string(land->stroke_count()) + " surface strokes"};
    Shot shot = build_shot(std::move(scene), std::move(trees), std::move(land), options);
    shot.passes.insert(shot.passes.begin(), generate);
    return shot;
}

namespace {

// Whether `from`'s graftals and imposters are `shot`'s too: built from the same trees and
// landscape (the same objects, so their meshes are the ones the imposters point into), for
// families and materials that name the same styles and imposters.
bool can_carry(const Shot* from, const Shot& shot) {
    if (!from || from->trees != shot.trees || from->land != shot.land) return false;
    const SceneDesc &a = from->scene, &b = shot.scene;
    if (a.families.size() != b.families.size() || a.materials.size() != b.materials.size())
        return false;
    for (size_t i = 0; i < a.families.size(); ++i)
        if (a.families[i].style != b.families[i].style ||
            a.families[i].imposters_name != b.families[i].imposters_name)
            return false;
    for (size_t i = 0; i < a.materials.size(); ++i)
        if (a.materials[i].style != b.materials[i].style ||
            a.materials[i].imposters_name != b.materials[i].imposters_name)
            return false;
    return true;
}

// Each tree's member's make(first tree of the member), one per member: the trees drawn from
// one member share it.
template <class T, class Make>
std::vector<std::shared_ptr<const T>> per_member(const Shot& shot, Make&& make) {
    const std::vector<BuiltTree>& trees = *shot.trees;
    std::map<const Tree*, size_t> member;
    std::vector<size_t> first;  // per member, its first tree
    std::vector<size_t> of(trees.size());
    for (size_t i = 0; i < trees.size(); ++i) {
        auto [it, fresh] = member.emplace(&trees[i].tree(), first.size());
        if (fresh) first.push_back(i);
        of[i] = it->second;
    }
    std::vector<std::shared_ptr<const T>> made(first.size());
    tbb::parallel_for(size_t{0}, first.size(), [&](size_t m) {
        made[m] = std::make_shared<const T>(make(trees[first[m]]));
    });
    std::vector<std::shared_ptr<const T>> out(trees.size());
    for (size_t i = 0; i < trees.size(); ++i) out[i] = made[of[i]];
    return out;
}

}  // namespace

Shot build_shot(SceneDesc scene, std::shared_ptr<const std::vector<BuiltTree>> trees,
                std::shared_ptr<const BuiltLandscape> land, const ShotOptions& options) {
    Shot shot;
    shot.plan = plan_shot(scene, options);
    shot.scene = std::move(scene);
    shot.trees = std::move(trees);
    shot.land = std::move(land);
    shot.materials = MaterialTable(shot.scene);
    // Near where the camera is: the still camera, or the track's first key.
    shot.anchor = shot.scene.camera_track.keys.empty() ? shot.scene.camera.eye
                                                       : shot.scene.camera_track.keys[0].position;
    for (const BuiltTree& b : *shot.trees) shot.placements.push_back(placement(b));
    // Surface strokes' rays start above the deepest strokes, so none is hidden or shadowed by
    // the very ground it was emitted from.
    double max_displacement = shot.scene.terrain.strokes.displacement_height;
    max_displacement = std::max(max_displacement, shot.scene.water.strokes.displacement_height);
    for (const auto& r : shot.scene.rocks)
        max_displacement = std::max(max_displacement, r.strokes.displacement_height);
    shot.surface_lift = 2.0f * static_cast<float>(max_displacement) + 0.01f;
    const bool carry = can_carry(options.carry_from, shot);
    if (std::any_of(shot.scene.families.begin(), shot.scene.families.end(),
                    [](const Family& f) { return f.graftal != nullptr; }) ||
        std::any_of(shot.scene.materials.begin(), shot.scene.materials.end(),
                    [](const Material& m) { return m.graftal != nullptr; })) {
        PassTimer timer;
        shot.graftals = carry
                            ? options.carry_from->graftals
                            : build_graftals(shot.scene, *shot.trees, shot.placements, *shot.land);
        size_t tufts = 0, graftals = 0;
        for (const ShotGraftals& g : shot.graftals)
            tufts += g.sites.size(), graftals += g.instances.size();
        shot.passes.push_back({"graftals", true,
                               carry ? "tufts carried over from the shot before (same trees, "
                                       "landscape and styles)"
                                     : "tufts placed on the graftal-styled crowns and surfaces",
                               timer.ms(),
                               std::to_string(tufts) + " tufts of " + std::to_string(graftals) +
                                   " graftals in " + std::to_string(shot.graftals.size()) +
                                   " groups"});
    }
    if (std::any_of(shot.scene.families.begin(), shot.scene.families.end(),
                    [](const Family& f) { return f.imposters != nullptr; }) ||
        std::any_of(shot.scene.materials.begin(), shot.scene.materials.end(),
                    [](const Material& m) { return m.imposters != nullptr; })) {
        PassTimer timer;
        shot.imposters =
            carry ? options.carry_from->imposters
                  : build_imposters(shot.scene, *shot.trees, shot.placements, *shot.land);
        size_t edges = 0;
        for (const ImposterObject& o : shot.imposters) edges += o.edges.size();
        shot.passes.push_back({"imposters", true,
                               "edges, control rows, colours and directions of the meshes that "
                               "carry graftal imposters",
                               timer.ms(),
                               std::to_string(shot.imposters.size()) + " meshes, " +
                                   std::to_string(edges) + " edges"});
    }

    if (shot.scene.render.pigment_mixing) {
        // Process-wide and built once; here, so frames do not pay for it.
        PassTimer timer;
        PigmentTable::shared();
        shot.passes.push_back({"pigment table", true,
                               "concentrations of four Kubelka-Munk pigments over colour, and "
                               "their mixtures (once per process)",
                               timer.ms(), ""});
    }
    if (shot.scene.sky.present && !shot.scene.background.canvas) {
        PassTimer timer;
        shot.sky = build_sky_strokes(shot.scene);
        shot.passes.push_back({"sky", true, "the painted sky's strokes over the sky's directions",
                               timer.ms(), std::to_string(shot.sky.size()) + " strokes"});
    }

    const ShotPlan& plan = shot.plan;
    const bool still_sun = plan.shadows && !plan.sun_moves;
    if (plan.underpaint || plan.shadows) {
        PassTimer timer;
        shot.limbs = std::make_unique<RayMeshes>();
        // One mesh per grown tree (and, when the sun casts shadows, one set of leaf casters
        // in its space): the trees drawn from one member share them.
        std::map<const Tree*, uint32_t> mesh;
        for (const BuiltTree& b : *shot.trees) {
            auto [it, fresh] = mesh.emplace(&b.tree(), 0u);
            if (fresh) {
                it->second = shot.limbs->add(b.tree().render);
                if (plan.shadows) shot.limbs->add_casters(member_casters(shot, b));
            }
            shot.limb_mesh.push_back(it->second);
        }
        shot.limbs->commit();
        const glm::vec3 sun(shot.scene.sun_direction);
        // The two scenes only read what they share (the device, the committed limbs): built
        // side by side (Embree's builds are partly serial).
        auto view = [&] { shot.view_rays = build_view_scene(shot, shot.view_surfaces); };
        auto sun_scene = [&] { shot.sun_rays = build_sun_scene(shot, sun); };
        if (plan.underpaint && still_sun)
            tbb::parallel_invoke(view, sun_scene);
        else if (plan.underpaint)
            view();
        else if (still_sun)
            sun_scene();
        shot.passes.push_back(
            {"ray scenes", true, "Embree scenes the plan asks for", timer.ms(),
             std::to_string(shot.limbs->size()) + " trees' limbs built once and placed " +
                 std::to_string(shot.limb_mesh.size()) + " times in each; " +
                 (shot.view_rays
                      ? std::to_string(shot.view_rays->mesh_count()) + " meshes for the camera"
                      : std::string("no camera scene")) +
                 (shot.sun_rays ? ", " + std::to_string(shot.sun_rays->mesh_count()) +
                                      " meshes + " + std::to_string(shot.sun_rays->caster_count()) +
                                      " stroke casters for the sun (" +
                                      std::to_string(shot.limbs->caster_sets()) +
                                      " trees' leaf cards built once, placed per tree)"
                  : plan.sun_moves ? ", the sun's scene per frame (the sun moves)"
                                   : std::string(", no shadow scene"))});
    }
    {
        PassTimer timer;
        shot.clusters = build_clusters(shot.particles());
        size_t clusters = 0;
        for (const ItemClusters& c : shot.clusters) clusters += c.clusters.size();
        shot.passes.push_back({"clusters", true,
                               "each item's particles grouped by place, bounded, so frames cull "
                               "them a group at a time",
                               timer.ms(),
                               std::to_string(clusters) + " clusters of up to " +
                                   std::to_string(kClusterSize) + " particles"});
    }
    if (shot.scene.render.level_of_detail) {
        PassTimer timer;
        shot.leaf_basis = per_member<LeafBasis>(shot, [&](const BuiltTree& b) {
            return leaf_basis(b.tree(), shot.scene.families[b.family].leaf_shader);
        });
        size_t leaves = 0;
        std::set<const LeafBasis*> counted;
        for (const auto& b : shot.leaf_basis)
            if (counted.insert(b.get()).second) leaves += b->size();
        shot.passes.push_back({"leaf basis", true,
                               "each member's leaves' lightness and direction from the crown's "
                               "centre, which every frame's level of detail reads",
                               timer.ms(), std::to_string(leaves) + " leaves"});
    }
    if (plan.wind) {
        PassTimer timer;
        shot.wind_rigs = per_member<WindRig>(shot, [&](const BuiltTree& b) {
            return build_wind_rig(b.tree(), plan.bark ? &b.bark() : nullptr);
        });
        size_t joints = 0;
        std::set<const WindRig*> counted;
        for (const auto& r : shot.wind_rigs)
            if (counted.insert(r.get()).second) joints += r->center.size();
        shot.passes.push_back({"wind rigs", true,
                               "each member's limbs' rings as joints and each particle's joint, "
                               "which every frame's wind poses",
                               timer.ms(), std::to_string(joints) + " joints"});
    }
    if (plan.sun_light) {
        PassTimer timer;
        std::vector<size_t> sizes(shot.item_count());
        size_t slots = 0;
        for (size_t i = 0; i < sizes.size(); ++i) slots += sizes[i] = item_particles(shot, i);
        shot.sun_light = std::make_unique<SunLightCache>(sizes, glm::vec3(shot.scene.sun_direction),
                                                         shot.scene.render.shadows);
        shot.passes.push_back({"sun light", true,
                               "a slot for the still sun's light at every particle, traced when "
                               "a frame first shows it and kept for the frames after",
                               timer.ms(), std::to_string(slots) + " slots"});
    }
    return shot;
}

}  // namespace pleinair
