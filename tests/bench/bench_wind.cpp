// What the wind costs (issue 28): one tree's pose (per joint), the move of every particle of a
// tree (per particle), the wind stage of a mortefontaine-breeze frame (every tree posed twice),
// and the sprites stage and whole frames of the breeze against the still-air walk at preview
// size, in the same run. Figures in BENCHMARKS.md, "Wind".
#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <string>

#include "generators/wind.h"
#include "pipeline/frame/paint_frame.h"
#include "pipeline/frame/sprites.h"
#include "pipeline/frame/wind_stage.h"
#include "pipeline/input/presets.h"

using namespace pleinair;

namespace {

const Shot& shot_of(const std::string& name) {
    static std::map<std::string, std::unique_ptr<Shot>> shots;
    auto& s = shots[name];
    if (!s) {
        SceneDesc scene = load_scene(resolve_preset("scenes", name, "bench"));
        scene.camera_params.width = 480;
        scene.camera_params.height = 270;
        ShotOptions options;
        options.cache_sun_light = true;  // as animate builds it
        s = std::make_unique<Shot>(build_shot(std::move(scene), options));
    }
    return *s;
}

constexpr int kFrame = 121;

WindAtTree breeze(double t) {
    WindAtTree w;
    w.direction = {0.93f, 0.0f, -0.37f};
    w.speed = 6;
    w.time = t;
    w.seed = 5;
    return w;
}

void BM_PoseTree(benchmark::State& state, const char* preset) {
    const Tree tree = generate_tree(load_tree_preset(resolve_preset("trees", preset, "bench")), 4);
    const WindRig rig = build_wind_rig(tree, nullptr);
    double t = 0;
    for (auto _ : state) {
        TreePose p = pose_tree(tree, rig, {}, breeze(t), {});
        benchmark::DoNotOptimize(p.joints.data());
        t += 1.0 / 24;
    }
    state.counters["joints"] = static_cast<double>(rig.center.size());
    state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(rig.center.size()));
}
BENCHMARK_CAPTURE(BM_PoseTree, willow, "willow")->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_PoseTree, oak, "oak")->Unit(benchmark::kMicrosecond);

// Every leaf of the breeze's first tree moved as the sprites stage moves it.
void BM_WindMovePerParticle(benchmark::State& state) {
    const Shot& shot = shot_of("mortefontaine-breeze");
    const FrameView view = view_at(shot.scene, frame_time(kFrame, shot.scene.fps));
    const FrameLod lod = level_of_detail(shot, view, shot.scene.render);
    const FrameWind wind = frame_wind(shot, view.time, lod);
    const LeafParticles& L = (*shot.trees)[0].tree().leaves;
    for (auto _ : state) {
        for (size_t j = 0; j < L.size(); ++j) {
            WindMove m = wind_move(shot, wind, 0, true, j, L.position[j], L.label[j]);
            benchmark::DoNotOptimize(m);
        }
    }
    state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(L.size()));
}
BENCHMARK(BM_WindMovePerParticle)->Unit(benchmark::kMillisecond);

void BM_WindStage(benchmark::State& state) {
    const Shot& shot = shot_of("mortefontaine-breeze");
    const FrameView view = view_at(shot.scene, frame_time(kFrame, shot.scene.fps));
    const FrameLod lod = level_of_detail(shot, view, shot.scene.render);
    for (auto _ : state) {
        FrameWind w = frame_wind(shot, view.time, lod);
        benchmark::DoNotOptimize(w.now.data());
    }
    state.counters["trees"] = static_cast<double>(shot.trees->size());
}
BENCHMARK(BM_WindStage)->Unit(benchmark::kMillisecond);

// Whole frames at preview size: the breeze against the still walk, interleaved by the
// benchmark's repetitions.
void BM_Frame(benchmark::State& state, const char* name) {
    const Shot& shot = shot_of(name);
    const FrameSettings fs = scene_frame_settings(shot.scene);
    const FrameView view = view_at(shot.scene, frame_time(kFrame, shot.scene.fps));
    for (auto _ : state) {
        Frame f = paint_frame(shot, view, fs);
        benchmark::DoNotOptimize(f.rgba.data());
    }
}
BENCHMARK_CAPTURE(BM_Frame, walk, "mortefontaine-walk")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Frame, breeze, "mortefontaine-breeze")->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
