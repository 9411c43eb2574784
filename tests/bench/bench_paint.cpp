// What a painted fragment costs: the full stroke shader against a bare constant-colour alpha
// blend over the same sprites, one core, measured in the same run. Times are of the paint pass
// only (the sprites, sort and bins are built the same way for both), and the composite pass's
// beside it (where pigment mixing decodes each pixel). Figures: BENCHMARKS.md.
#include <benchmark/benchmark.h>
#include <tbb/task_arena.h>

#include "pipeline/frame/paint_frame.h"
#include "pipeline/input/presets.h"
#include "shading/pigment.h"

using namespace pleinair;

namespace {

struct Fixture {
    Shot shot;
    Fixture() {
        SceneDesc scene = load_scene(resolve_preset("scenes", "grove", "bench"));
        scene.render.samples = 1;  // one fragment per covered pixel, for both kernels
        shot = build_shot(std::move(scene));
    }
};

const Fixture& fixture() {
    static Fixture f;
    return f;
}

enum class Mix { kLinear, kPigment, kPigmentCanvas };

void paint_pass(benchmark::State& state, bool bare, bool exact, Mix mix = Mix::kLinear) {
    const Shot& shot = fixture().shot;
    FrameSettings settings = scene_frame_settings(shot.scene);
    settings.render.palette_lut = settings.render.edge_lut = !exact;
    settings.bare_blend = bare;
    settings.render.pigment_mixing = mix != Mix::kLinear;
    if (mix == Mix::kPigmentCanvas) settings.render.canvas_weave = 0.35f;
    PigmentTable::shared();  // built once per process, outside the timing
    tbb::task_arena one(1);
    double ms = 0, composite_ms = 0;
    uint64_t fragments = 0;
    for (auto _ : state) {
        FrameReport rep;
        one.execute([&] {
            benchmark::DoNotOptimize(paint_frame(shot, still_view(shot.scene), settings, &rep));
        });
        double paint_ms = 0;
        for (const auto& p : rep.passes) {
            if (p.name == "paint") paint_ms = p.ms;
            if (p.name == "composite") composite_ms += p.ms;
        }
        state.SetIterationTime(paint_ms / 1000.0);
        ms += paint_ms;
        fragments += rep.fragments;
    }
    state.counters["fragments"] = static_cast<double>(fragments) / state.iterations();
    state.counters["ns_per_fragment"] = ms * 1e6 / static_cast<double>(fragments);
    state.counters["composite_ms"] = composite_ms / static_cast<double>(state.iterations());
}

void BM_PaintShaded(benchmark::State& state) { paint_pass(state, false, false); }
void BM_PaintShadedExact(benchmark::State& state) { paint_pass(state, false, true); }
void BM_PaintBareBlend(benchmark::State& state) { paint_pass(state, true, false); }
// Issue 13 §3: strokes mixed as pigments (each fragment encoded to the latent space, each pixel
// decoded once), and with the canvas weave on top.
void BM_PaintPigment(benchmark::State& state) { paint_pass(state, false, false, Mix::kPigment); }
void BM_PaintPigmentCanvas(benchmark::State& state) {
    paint_pass(state, false, false, Mix::kPigmentCanvas);
}

}  // namespace

BENCHMARK(BM_PaintShaded)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PaintShadedExact)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PaintBareBlend)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PaintPigment)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PaintPigmentCanvas)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
