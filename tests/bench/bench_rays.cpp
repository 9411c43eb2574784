// Embree throughput for shadow rays: against the forest-edge scene's terrain, rocks and trunks
// plus its leaf strokes as cards whose opacity is the stroke mask (the occlusion filter), and
// against the same cards as plain opaque quads (no filter), in rays per second on one core,
// measured in the same run; with Embree pinned to SSE2 (pleinair's default: the same hits on
// every x86-64 CPU) and left to pick its widest instruction set. And the shot's own sun scene,
// where each tree's cards are its member's, placed by instances. Figures: BENCHMARKS.md.
#include <benchmark/benchmark.h>
#include <tbb/task_arena.h>

#include <glm/geometric.hpp>
#include <map>
#include <memory>
#include <string>

#include "generators/rng.h"
#include "pipeline/frame/paint_frame.h"
#include "pipeline/input/presets.h"

using namespace pleinair;

namespace {

struct Fixture {
    SceneDesc scene;
    std::vector<BuiltTree> trees;
    BuiltLandscape land;
    std::vector<glm::dvec3> origins;  // leaf and surface particles: where shadow rays start
    RayMeshes limbs;
    std::unique_ptr<RayScene> filtered, opaque;
    glm::vec3 sun;

    explicit Fixture(const std::string& device_config) {
        set_ray_device_config(device_config);
        scene = load_scene(resolve_preset("scenes", "forest-edge", "bench"));
        trees = build_trees(scene, false);
        land = build_landscape(scene);
        sun = glm::vec3(scene.sun_direction);
        const glm::dvec3 anchor = scene.camera.eye;
        // As the painter builds them: each tree's limbs once, placed by instances.
        for (const BuiltTree& b : trees) limbs.add(b.tree().render);
        limbs.commit();
        filtered = std::make_unique<RayScene>(anchor, &limbs);
        opaque = std::make_unique<RayScene>(anchor, &limbs);
        for (RayScene* r : {filtered.get(), opaque.get()}) {
            r->add_mesh(land.terrain_mesh);
            for (const auto& rock : land.rocks) r->add_mesh(rock);
            for (size_t i = 0; i < trees.size(); ++i) {
                const TreePlacement pl = placement(trees[i]);
                r->add_instance(static_cast<uint32_t>(i), pl.linear(), pl.position);
            }
        }
        std::vector<std::vector<StrokeCaster>> per_family(scene.families.size());
        QuadMesh cards;
        for (const BuiltTree& b : trees)
            for (const StrokeCaster& c : leaf_casters(scene, b, sun)) {
                per_family[b.family].push_back(c);
                const glm::vec3 a = c.axis_s * c.half_w, t = c.axis_t * c.half_l;
                const glm::vec3 o(c.center - anchor);
                const unsigned k = static_cast<unsigned>(cards.positions.size());
                cards.positions.insert(cards.positions.end(),
                                       {o - a - t, o + a - t, o + a + t, o - a + t});
                cards.quads.push_back({k, k + 1, k + 2, k + 3});
                origins.push_back(c.center);
            }
        static std::vector<EdgeTable> edges;
        edges.clear();
        edges.reserve(scene.families.size());
        for (size_t f = 0; f < scene.families.size(); ++f) {
            edges.push_back(make_edge_table(scene.families[f].leaf_shader.stroke_fullness));
            if (!per_family[f].empty())
                filtered->add_casters(per_family[f], scene.families[f].leaf_shader, edges.back());
        }
        opaque->add_mesh(cards, anchor);
        filtered->commit();
        opaque->commit();
        const SurfaceParticles strokes = land.all_strokes();
        for (size_t i = 0; i < strokes.size(); i += 4)
            origins.push_back(glm::dvec3(strokes.position[i]));
    }
};

Fixture& fixture(const std::string& device_config) {
    static std::map<std::string, std::unique_ptr<Fixture>> built;
    auto& f = built[device_config];
    if (!f) f = std::make_unique<Fixture>(device_config);
    return *f;
}

void shadow_rays(benchmark::State& state, bool filter, const char* device_config) {
    Fixture& f = fixture(device_config);
    tbb::task_arena one(1);
    uint64_t rays = 0, lit = 0;
    for (auto _ : state) {
        one.execute([&] {
            FlushDenormals ftz;
            for (const glm::dvec3& o : f.origins) {
                float t = filter ? f.filtered->transmittance(o, f.sun, ShadowMode::kTransmissive)
                                 : (f.opaque->occluded(o, f.sun) ? 0.0f : 1.0f);
                lit += t > 0.5f;
            }
        });
        rays += f.origins.size();
    }
    state.counters["rays_per_s"] =
        benchmark::Counter(static_cast<double>(rays), benchmark::Counter::kIsRate);
    state.counters["lit_fraction"] = static_cast<double>(lit) / static_cast<double>(rays);
    state.counters["rays"] = static_cast<double>(f.origins.size());
}

// As the painter traces a particle's light (sun_light_at through the shot's sun scene): each
// tree's leaf cards are one member's Embree user geometry placed by instances, the card built
// from the ray's direction in the filter. Every leaf of forest-edge, pleinair's own device.
void member_rays(benchmark::State& state) {
    static const Shot shot = [] {
        set_ray_device_config(kPortableRayDevice);
        return build_shot(load_scene(resolve_preset("scenes", "forest-edge", "bench")));
    }();
    static const std::vector<RayOrigin> origins = [] {
        std::vector<RayOrigin> o;
        for (size_t i = 0; i < shot.trees->size(); ++i)
            for_each_particle(shot, i, [&](SpriteKind kind, size_t, const RayOrigin& r) {
                if (kind == SpriteKind::kLeaf) o.push_back(r);
            });
        return o;
    }();
    const glm::vec3 sun(shot.scene.sun_direction);
    tbb::task_arena one(1);
    uint64_t rays = 0;
    double light = 0;
    for (auto _ : state) {
        one.execute([&] {
            FlushDenormals ftz;
            for (const RayOrigin& o : origins)
                light += sun_light_at(*shot.sun_rays, o, sun, ShadowMode::kTransmissive);
        });
        rays += origins.size();
    }
    state.counters["rays_per_s"] =
        benchmark::Counter(static_cast<double>(rays), benchmark::Counter::kIsRate);
    state.counters["mean_light"] = light / static_cast<double>(rays);
    state.counters["rays"] = static_cast<double>(origins.size());
}

}  // namespace

BENCHMARK(member_rays)->Name("shadow_rays/MemberCasters")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(shadow_rays, StrokeFilter / sse2, true, "isa=sse2")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(shadow_rays, StrokeFilter / avx2, true, "isa=avx2")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(shadow_rays, StrokeFilter / widest, true, "")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(shadow_rays, OpaqueCards / sse2, false, "isa=sse2")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(shadow_rays, OpaqueCards / avx2, false, "isa=avx2")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(shadow_rays, OpaqueCards / widest, false, "")->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
