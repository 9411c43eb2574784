// Frames that cost what they show (issue 26): the sprites stage of a forest-edge-walk frame
// at 480x270 and 1920x1080, particle by particle against cluster by cluster, each ray cast
// against answers kept from the frame before (SeenMemo), and with small strokes thinned
// (render/thin_below_px); the level of detail with and without the shot's leaf basis; and
// whole frames at both sizes. Measured in the same run; figures
// in BENCHMARKS.md, "Frames that cost what they show".
#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <string>

#include "pipeline/frame/buffer_pool.h"
#include "pipeline/frame/paint_frame.h"
#include "pipeline/frame/seen_memo.h"
#include "pipeline/frame/sprites.h"
#include "pipeline/input/presets.h"

using namespace pleinair;

namespace {

// The walk's shot at one image size, built once per size.
const Shot& walk(int width) {
    static std::map<int, std::unique_ptr<Shot>> shots;
    auto& s = shots[width];
    if (!s) {
        SceneDesc scene = load_scene(resolve_preset("scenes", "forest-edge-walk", "bench"));
        scene.camera_params.width = width;
        scene.camera_params.height = width * 9 / 16;
        ShotOptions options;
        options.cache_sun_light = true;  // as animate builds it
        s = std::make_unique<Shot>(build_shot(std::move(scene), options));
    }
    return *s;
}

constexpr int kFrame = 24;

// The walk at a width with strokes thinned below thin_px: its settings, frame 24's view and
// the frame before's.
struct Walk {
    const Shot& shot;
    FrameSettings fs;
    FrameView view, before;
    Walk(int width, int thin_px)
        : shot(walk(width)),
          fs(scene_frame_settings(shot.scene)),
          view(view_at(shot.scene, frame_time(kFrame, shot.scene.fps))),
          before(view_at(shot.scene, frame_time(kFrame - 1, shot.scene.fps))) {
        fs.render.thin_below_px = static_cast<float>(thin_px);
    }
};

// args: image width, group culling, memo (the frame before painted first), thin_below_px, and
// the sprite vectors' memory kept from the run before (buffer_pool.h, as animate keeps it).
void BM_Sprites(benchmark::State& state) {
    const Walk w(static_cast<int>(state.range(0)), static_cast<int>(state.range(3)));
    const Shot& shot = w.shot;
    const FrameSettings& fs = w.fs;
    const FrameView &view = w.view, &before = w.before;
    const FramePlan plan = plan_frame(shot, fs);
    const FrameLod lod = level_of_detail(shot, view, fs.render);
    const FrameLod lod_before = level_of_detail(shot, before, fs.render);
    const SeenWindow seen = seen_window(shot.scene, view, fs.render);
    const SeenWindow seen_before = seen_window(shot.scene, before, fs.render);
    BufferPool pool;
    BufferPool* kept = state.range(4) ? &pool : nullptr;
    SpriteSet set;
    size_t sprites = 0;
    for (auto _ : state) {
        SeenMemo memo;
        SpriteStageInput in{shot, view, plan, fs.render, lod, shot.sun_rays.get(), &seen};
        in.group_culling = state.range(1) != 0;
        in.buffers = kept;
        if (state.range(2)) {
            state.PauseTiming();
            SpriteStageInput b{
                shot, before, plan, fs.render, lod_before, shot.sun_rays.get(), &seen_before};
            b.seen_memo = &memo;
            b.buffers = kept;
            SpriteSet first = make_sprites(b);
            if (kept) kept->give_sprites(std::move(first.sprites));
            state.ResumeTiming();
            in.seen_memo = &memo;
        }
        set = make_sprites(in);
        benchmark::DoNotOptimize(set.sprites.data());
        sprites = set.sprites.size();
        if (kept) kept->give_sprites(std::move(set.sprites));
    }
    state.counters["sprites"] = static_cast<double>(sprites);
    state.counters["by_group"] = static_cast<double>(set.grouped);
    state.counters["rays"] = static_cast<double>(set.occlusion_rays);
}
BENCHMARK(BM_Sprites)
    ->ArgNames({"width", "group", "memo", "thin_px", "kept"})
    ->Args({480, 0, 0, 0, 0})
    ->Args({480, 1, 0, 0, 0})
    ->Args({480, 1, 1, 0, 0})
    ->Args({480, 1, 1, 0, 1})
    ->Args({480, 1, 1, 4, 0})
    ->Args({480, 1, 1, 6, 0})
    ->Args({1920, 0, 0, 0, 0})
    ->Args({1920, 1, 1, 0, 0})
    ->Args({1920, 1, 1, 0, 1})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// args: the shot keeps each member's leaf basis (as build_shot does) or not (each frame
// computes it, as before the basis was kept): the level-of-detail stage of frame 24 at 480x270.
void BM_LevelOfDetail(benchmark::State& state) {
    static std::unique_ptr<Shot> without;
    const Shot* shot = &walk(480);
    if (!state.range(0)) {
        if (!without) {
            SceneDesc scene = shot->scene;
            without = std::make_unique<Shot>(build_shot(std::move(scene)));
            without->leaf_basis.clear();
        }
        shot = without.get();
    }
    const FrameSettings fs = scene_frame_settings(shot->scene);
    const FrameView view = view_at(shot->scene, frame_time(kFrame, shot->scene.fps));
    for (auto _ : state) {
        const FrameLod lod = level_of_detail(*shot, view, fs.render);
        benchmark::DoNotOptimize(lod.trees.data());
    }
}
BENCHMARK(BM_LevelOfDetail)
    ->ArgNames({"basis_kept"})
    ->Arg(0)
    ->Arg(1)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// A whole frame (the frame before painted first, as animate does), at a width and thinning.
void BM_Frame(benchmark::State& state) {
    Walk w(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
    for (auto _ : state) {
        SeenMemo memo;
        w.fs.seen_memo = &memo;
        state.PauseTiming();
        paint_frame(w.shot, w.before, w.fs);
        state.ResumeTiming();
        const Frame f = paint_frame(w.shot, w.view, w.fs);
        benchmark::DoNotOptimize(f.rgba.data());
    }
}
BENCHMARK(BM_Frame)
    ->ArgNames({"width", "thin_px"})
    ->Args({480, 0})
    ->Args({480, 6})
    ->Args({1920, 0})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(3);

}  // namespace

BENCHMARK_MAIN();
