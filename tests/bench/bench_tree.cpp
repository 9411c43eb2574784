// Generation time per preset and per stage (trunk, branches, subdivision, leaves, whole tree),
// and OpenMesh's Catmull-Clark beside the flat one generation uses. Every benchmark cycles
// through the same eight seeds, so a figure is a family's mean, not one lucky member's.
// Figures and the command: BENCHMARKS.md.
#include <benchmark/benchmark.h>

// OpenMesh's subdivider needs a mesh kernel included before it.
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Subdivider/Uniform/CatmullClarkT.hh>
#include <memory>

#include "generators/branches.h"
#include "generators/leaves.h"
#include "generators/subdivide.h"
#include "generators/tree.h"
#include "generators/tree_mesh.h"
#include "generators/trunk.h"
#include "pipeline/input/presets.h"

using namespace pleinair;

namespace {

const char* kPresets[] = {"oak", "poplar", "willow", "birch", "pine", "shrub"};
constexpr int kPresetCount = static_cast<int>(std::size(kPresets));
constexpr uint64_t kSeeds = 8;

TreeParams preset(const benchmark::State& state) {
    return load_tree_preset(resolve_tree_preset(kPresets[state.range(0)]));
}

// Mean counts over the seed cycle, as counters beside the time.
void report(benchmark::State& state, double render_vertices, double leaves) {
    state.SetLabel(kPresets[state.range(0)]);
    if (render_vertices > 0) state.counters["render_verts"] = render_vertices / kSeeds;
    if (leaves > 0) state.counters["leaves"] = leaves / kSeeds;
}

void BM_Trunk(benchmark::State& state) {
    TreeParams p = preset(state);
    uint64_t seed = 0;
    for (auto _ : state) {
        TreeMesh tm;
        grow_trunk(tm, p, 1 + seed++ % kSeeds);
        benchmark::DoNotOptimize(tm.limbs.data());
    }
    report(state, 0, 0);
}

// Branches and twigs on prebuilt trunks (copied with the timer paused).
void BM_Branches(benchmark::State& state) {
    TreeParams p = preset(state);
    std::vector<TreeMesh> trunks(kSeeds);
    for (uint64_t s = 0; s < kSeeds; ++s) grow_trunk(trunks[s], p, 1 + s);
    uint64_t seed = 0;
    for (auto _ : state) {
        state.PauseTiming();
        const uint64_t s = seed++ % kSeeds;
        auto tm = std::make_unique<TreeMesh>(trunks[s]);
        state.ResumeTiming();
        grow_branches(*tm, p.branches, 1, 1 + s);
        grow_branches(*tm, p.twigs, 2, 1 + s);
        benchmark::DoNotOptimize(tm->limbs.data());
        state.PauseTiming();
        tm.reset();
        state.ResumeTiming();
    }
    report(state, 0, 0);
}

std::vector<QuadMesh> controls(const TreeParams& p) {
    std::vector<QuadMesh> out;
    for (uint64_t s = 0; s < kSeeds; ++s) {
        TreeMesh tm;
        grow_skeleton(tm, p, 1 + s);
        out.push_back(to_quad_mesh(tm));
    }
    return out;
}

void BM_Subdivide(benchmark::State& state) {
    TreeParams p = preset(state);
    auto control = controls(p);
    double verts = 0;
    for (uint64_t s = 0; s < kSeeds; ++s)
        verts +=
            static_cast<double>(catmull_clark(control[s], p.subdivision_levels).positions.size());
    uint64_t seed = 0;
    for (auto _ : state) {
        QuadMesh r = catmull_clark(control[seed++ % kSeeds], p.subdivision_levels);
        benchmark::DoNotOptimize(r.positions.data());
    }
    report(state, verts, 0);
}

using OmMesh = OpenMesh::PolyMesh_ArrayKernelT<>;

OmMesh to_openmesh(const QuadMesh& q) {
    OmMesh m;
    for (const auto& p : q.positions) m.add_vertex({p.x, p.y, p.z});
    for (const auto& f : q.quads)
        m.add_face(OmMesh::VertexHandle(int(f[0])), OmMesh::VertexHandle(int(f[1])),
                   OmMesh::VertexHandle(int(f[2])), OmMesh::VertexHandle(int(f[3])));
    return m;
}

// The same subdivision through OpenMesh's CatmullClarkT (conversion to OpenMesh not timed).
void BM_SubdivideOpenMesh(benchmark::State& state) {
    TreeParams p = preset(state);
    auto control = controls(p);
    uint64_t seed = 0;
    for (auto _ : state) {
        state.PauseTiming();
        OmMesh m = to_openmesh(control[seed++ % kSeeds]);
        OpenMesh::Subdivider::Uniform::CatmullClarkT<OmMesh> cc;
        state.ResumeTiming();
        cc.attach(m);
        cc(static_cast<size_t>(p.subdivision_levels));
        cc.detach();
        benchmark::DoNotOptimize(m.n_vertices());
    }
    report(state, 0, 0);
}

void BM_Leaves(benchmark::State& state) {
    TreeParams p = preset(state);
    std::vector<TreeMesh> skeletons(kSeeds);
    double leaves = 0;
    for (uint64_t s = 0; s < kSeeds; ++s) {
        grow_skeleton(skeletons[s], p, 1 + s);
        glm::dvec3 center;
        leaves += static_cast<double>(emit_leaves(skeletons[s], p, 1 + s, 0, center).size());
    }
    uint64_t seed = 0;
    for (auto _ : state) {
        const uint64_t s = seed++ % kSeeds;
        glm::dvec3 center;
        LeafParticles l = emit_leaves(skeletons[s], p, 1 + s, 0, center);
        benchmark::DoNotOptimize(l.position.data());
    }
    report(state, 0, leaves);
}

// Everything generate_tree does: trunk, branches, twigs, control mesh, render mesh, low-detail
// mesh, leaves and skeleton records.
void BM_Tree(benchmark::State& state) {
    TreeParams p = preset(state);
    double verts = 0, leaves = 0;
    for (uint64_t s = 0; s < kSeeds; ++s) {
        Tree t = generate_tree(p, 1 + s);
        verts += static_cast<double>(t.render.positions.size());
        leaves += static_cast<double>(t.leaves.size());
    }
    uint64_t seed = 0;
    for (auto _ : state) {
        Tree t = generate_tree(p, 1 + seed++ % kSeeds);
        benchmark::DoNotOptimize(t.render.positions.data());
    }
    report(state, verts, leaves);
}

BENCHMARK(BM_Trunk)->DenseRange(0, kPresetCount - 1)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Branches)->DenseRange(0, kPresetCount - 1)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Subdivide)->DenseRange(0, kPresetCount - 1)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_SubdivideOpenMesh)->DenseRange(0, kPresetCount - 1)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Leaves)->DenseRange(0, kPresetCount - 1)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Tree)->DenseRange(0, kPresetCount - 1)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
