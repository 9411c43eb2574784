// Generation time per preset and per stage (trunk, branches, subdivision, leaves, whole tree),
// and OpenMesh's Catmull-Clark beside the flat one generation uses. Figures: BENCHMARKS.md.
#include <benchmark/benchmark.h>

// OpenMesh's subdivider needs a mesh kernel included before it.
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Subdivider/Uniform/CatmullClarkT.hh>

#include "generators/branches.h"
#include "generators/leaves.h"
#include "generators/subdivide.h"
#include "generators/tree.h"
#include "generators/tree_mesh.h"
#include "generators/trunk.h"
#include "pipeline/presets.h"

using namespace pleinair;

namespace {

constexpr uint64_t kSeed = 7;
const char* kPresets[] = {"oak", "poplar", "willow", "birch", "pine", "shrub"};

TreeParams preset(int i) { return load_tree_preset(resolve_tree_preset(kPresets[i])); }

void label(benchmark::State& state, int i) { state.SetLabel(kPresets[i]); }

void BM_Trunk(benchmark::State& state) {
    TreeParams p = preset(static_cast<int>(state.range(0)));
    for (auto _ : state) {
        TreeMesh tm;
        grow_trunk(tm, p, kSeed);
        benchmark::DoNotOptimize(tm.limbs.data());
    }
    label(state, static_cast<int>(state.range(0)));
}

// Branches and twigs; the trunk they grow from is built with the timer paused.
void BM_Branches(benchmark::State& state) {
    TreeParams p = preset(static_cast<int>(state.range(0)));
    for (auto _ : state) {
        state.PauseTiming();
        auto* tm = new TreeMesh;
        grow_trunk(*tm, p, kSeed);
        state.ResumeTiming();
        grow_branches(*tm, p.branches, 1, kSeed);
        grow_branches(*tm, p.twigs, 2, kSeed);
        benchmark::DoNotOptimize(tm->limbs.data());
        state.PauseTiming();
        delete tm;
        state.ResumeTiming();
    }
    label(state, static_cast<int>(state.range(0)));
}

QuadMesh control_of(const TreeParams& p) {
    TreeMesh tm;
    grow_skeleton(tm, p, kSeed);
    return to_quad_mesh(tm);
}

void BM_Subdivide(benchmark::State& state) {
    TreeParams p = preset(static_cast<int>(state.range(0)));
    QuadMesh control = control_of(p);
    size_t verts = 0;
    for (auto _ : state) {
        QuadMesh r = catmull_clark(control, p.subdivision_levels);
        verts = r.positions.size();
        benchmark::DoNotOptimize(r.positions.data());
    }
    state.counters["render_vertices"] = static_cast<double>(verts);
    label(state, static_cast<int>(state.range(0)));
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

// The same subdivision through OpenMesh's CatmullClarkT (conversion not timed).
void BM_SubdivideOpenMesh(benchmark::State& state) {
    TreeParams p = preset(static_cast<int>(state.range(0)));
    QuadMesh control = control_of(p);
    for (auto _ : state) {
        state.PauseTiming();
        OmMesh m = to_openmesh(control);
        OpenMesh::Subdivider::Uniform::CatmullClarkT<OmMesh> cc;
        state.ResumeTiming();
        cc.attach(m);
        cc(static_cast<size_t>(p.subdivision_levels));
        cc.detach();
        benchmark::DoNotOptimize(m.n_vertices());
    }
    label(state, static_cast<int>(state.range(0)));
}

void BM_Leaves(benchmark::State& state) {
    TreeParams p = preset(static_cast<int>(state.range(0)));
    TreeMesh tm;
    grow_skeleton(tm, p, kSeed);
    size_t n = 0;
    for (auto _ : state) {
        glm::dvec3 center;
        LeafParticles l = emit_leaves(tm, p, kSeed, 0, center);
        n = l.size();
        benchmark::DoNotOptimize(l.position.data());
    }
    state.counters["leaves"] = static_cast<double>(n);
    label(state, static_cast<int>(state.range(0)));
}

void BM_Tree(benchmark::State& state) {
    TreeParams p = preset(static_cast<int>(state.range(0)));
    size_t verts = 0, leaves = 0;
    for (auto _ : state) {
        Tree t = generate_tree(p, kSeed);
        verts = t.render.positions.size();
        leaves = t.leaves.size();
        benchmark::DoNotOptimize(t.render.positions.data());
    }
    state.counters["render_vertices"] = static_cast<double>(verts);
    state.counters["leaves"] = static_cast<double>(leaves);
    label(state, static_cast<int>(state.range(0)));
}

constexpr int kCount = static_cast<int>(std::size(kPresets));
BENCHMARK(BM_Trunk)->DenseRange(0, kCount - 1)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Branches)->DenseRange(0, kCount - 1)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Subdivide)->DenseRange(0, kCount - 1)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_SubdivideOpenMesh)->DenseRange(0, kCount - 1)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Leaves)->DenseRange(0, kCount - 1)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Tree)->DenseRange(0, kCount - 1)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
