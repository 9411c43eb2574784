// What the studio's user waits for, on all cores: a tree key changed and the preview painted
// (480x270, the family regrown, the shot rebuilt, the frame painted and encoded as the page
// gets it), a camera step on a still scene (the preview painted from the shot already built),
// a shot scrubbed frame by frame at preview size, and a walk played. HTTP and the browser are
// not in it.
// Figures: BENCHMARKS.md, "The studio".
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "pipeline/output/image_io.h"
#include "pipeline/studio/workspace.h"

using namespace pleinair;

namespace {

// Every scene at 960x540, so its preview is 480x270.
const std::vector<std::string> kSize = {"/camera/width=960", "/camera/height=540"};

void encode(const StudioFrame& f) { benchmark::DoNotOptimize(encode_frame(f.frame, ".jpg", 88)); }

void BM_StudioTreeKey(benchmark::State& state) {
    Workspace ws("tree", {"/families/tree/preset=oak"});
    ws.set_all(ws.framing());
    encode(ws.paint(std::nullopt, true));
    int i = 0;
    for (auto _ : state) {
        // A slider dragged: each value differs from the last.
        ws.set("/families/tree/tree/trunk/taper/base", std::to_string(0.80 + 0.01 * (i++ % 8)));
        encode(ws.paint(std::nullopt, true));
    }
}
BENCHMARK(BM_StudioTreeKey)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(24);

// A leaf shader key: the shot rebuilt from the same trees and landscape.
void BM_StudioLeafShaderKey(benchmark::State& state, const std::string& scene,
                            const std::string& family) {
    Workspace ws(scene, kSize);
    encode(ws.paint(std::nullopt, true));
    int i = 0;
    for (auto _ : state) {
        ws.set("/families/" + family + "/leaf_shader_keys/stroke/stroke_fullness",
               std::to_string(0.4 + 0.02 * (i++ % 8)));
        encode(ws.paint(std::nullopt, true));
    }
}
BENCHMARK_CAPTURE(BM_StudioLeafShaderKey, tree, std::string("tree"), std::string("tree"))
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(24);
BENCHMARK_CAPTURE(BM_StudioLeafShaderKey, truffula, std::string("truffula"),
                  std::string("truffula"))
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(12);

// The same change without the workspace's levels: everything built again, as a fresh
// `render --preview` would (less reading the process's start), for the ratio.
void BM_StudioRebuildEverything(benchmark::State& state, const std::string& scene,
                                const std::string& family) {
    int i = 0;
    for (auto _ : state) {
        std::vector<std::string> sets = kSize;
        sets.push_back("/families/" + family + "/leaf_shader_keys/stroke/stroke_fullness=" +
                       std::to_string(0.4 + 0.02 * (i++ % 8)));
        Workspace ws(scene, sets);
        encode(ws.paint(std::nullopt, true));
    }
}
BENCHMARK_CAPTURE(BM_StudioRebuildEverything, tree, std::string("tree"), std::string("tree"))
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(24);
BENCHMARK_CAPTURE(BM_StudioRebuildEverything, truffula, std::string("truffula"),
                  std::string("truffula"))
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(12);

// The camera orbiting the still camera's look-at, a degree a step, as a mouse drag sends it.
void BM_StudioCameraMove(benchmark::State& state, const std::string& scene) {
    Workspace ws(scene, kSize);
    encode(ws.paint(std::nullopt, false));
    const CameraParams cp = ws.scene().camera_params;
    const glm::dvec3 off = cp.position - cp.look_at;
    int i = 0;
    for (auto _ : state) {
        const double a = 0.0175 * (++i % 20);
        const glm::dvec3 p =
            cp.look_at + glm::dvec3(off.x * std::cos(a) - off.z * std::sin(a), off.y,
                                    off.x * std::sin(a) + off.z * std::cos(a));
        char position[96];
        std::snprintf(position, sizeof position, "[%.4f,%.4f,%.4f]", p.x, p.y, p.z);
        ws.set("/camera/position", position);
        encode(ws.paint(std::nullopt, true));
    }
}
BENCHMARK_CAPTURE(BM_StudioCameraMove, tree, std::string("tree"))
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(20);
BENCHMARK_CAPTURE(BM_StudioCameraMove, truffula, std::string("truffula"))
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(20);
BENCHMARK_CAPTURE(BM_StudioCameraMove, grove, std::string("grove"))
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(20);
BENCHMARK_CAPTURE(BM_StudioCameraMove, mortefontaine, std::string("mortefontaine"))
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(10);

// A shot's timeline scrubbed: each iteration paints the next frame at preview size.
void BM_StudioScrub(benchmark::State& state, const std::string& scene) {
    Workspace ws(scene, kSize);
    encode(ws.paint(1, true));
    int f = 1;
    for (auto _ : state) encode(ws.paint(1 + (f++ * 4) % 96, true));
    state.counters["frames_per_s"] =
        benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK_CAPTURE(BM_StudioScrub, tree_dolly, std::string("tree-dolly"))
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(24);
BENCHMARK_CAPTURE(BM_StudioScrub, mortefontaine_walk, std::string("mortefontaine-walk"))
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(8);

// A walk played: each iteration paints the next frame at preview size, as the page's Play
// steps, from frame 20 on. `kept` 0 empties the workspace's memos of the frames before (each
// frame as if painted alone), for the ratio.
void BM_StudioPlay(benchmark::State& state, const std::string& scene) {
    Workspace ws(scene, kSize);
    const bool kept = state.range(0) != 0;
    encode(ws.paint(20, true));
    int f = 21;
    for (auto _ : state) {
        if (!kept) ws.forget_frames();
        encode(ws.paint(f++, true));
    }
    state.counters["frames_per_s"] =
        benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
void play_runs(benchmark::internal::Benchmark* b) {
    b->ArgName("kept")->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();
    b->Iterations(12);
}
BENCHMARK_CAPTURE(BM_StudioPlay, mortefontaine_walk, std::string("mortefontaine-walk"))
    ->Apply(play_runs);
BENCHMARK_CAPTURE(BM_StudioPlay, forest_edge_walk, std::string("forest-edge-walk"))
    ->Apply(play_runs);

// A frame's encoding for the page: JPEG previews, PNG at rest.
void BM_StudioEncode(benchmark::State& state, const std::string& ext, bool preview) {
    static Workspace ws("tree", {"/families/tree/preset=oak"});
    const Frame f = ws.paint(std::nullopt, preview).frame;
    size_t bytes = 0;
    for (auto _ : state) bytes = encode_frame(f, ext, 88).size();
    state.counters["kB"] = static_cast<double>(bytes) / 1000.0;
}
BENCHMARK_CAPTURE(BM_StudioEncode, jpeg_480x270, std::string(".jpg"), true)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_StudioEncode, png_480x270, std::string(".png"), true)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_StudioEncode, png_960x540, std::string(".png"), false)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
