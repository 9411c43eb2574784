// What graftals cost: one graftal drawn by Cairo and by pleinair's scanline coverage (per
// shipped description, at about 40 pixels), the graftals stage of a frame (tufts replayed along
// the track, posed and drawn), and whole frames of the same scenes painted in strokes and in
// graftals by either rasteriser, at 960 x 540 on all cores; and graftal imposters (file 002): one
// imposter drawn at three sizes on screen, the imposters stage of a frame, and the truffula frame
// with and without them.
// Figures: BENCHMARKS.md ("Graftals").
#include <benchmark/benchmark.h>

#include <string>

#include "pipeline/frame/graftal_stage.h"
#include "pipeline/frame/imposter_stage.h"
#include "pipeline/frame/paint_frame.h"
#include "pipeline/input/graftal_io.h"
#include "pipeline/input/imposter_io.h"
#include "pipeline/input/presets.h"
#include "pipeline/shot/graftal_draw.h"
#include "pipeline/shot/shot.h"

using namespace pleinair;

namespace {

const char* const kDescs[] = {"truffula-tuft", "seuss-leaf-tuft", "grass-tuft", "corot-leaf"};

// A 960 x 540 camera 10 units from the origin, looking at it down -z.
Camera facing_camera() {
    CameraParams cp;
    cp.position = {0, 0, 10};
    cp.look_at = {0, 0, 0};
    cp.width = 960, cp.height = 540;
    Camera cam;
    make_camera(cp, cam);
    return cam;
}

// One graftal of each example in turn, 40 pixels long, facing a 960 x 540 camera, drawn by
// Cairo (second argument 0) or by pleinair's scanline coverage (1).
void BM_GraftalDraw(benchmark::State& state) {
    const GraftalDesc d = load_graftal(kDescs[state.range(0)]);
    const GraftalRaster raster = state.range(1) ? GraftalRaster::kScanline : GraftalRaster::kCairo;
    state.SetLabel(std::string(kDescs[state.range(0)]) + (state.range(1) ? " scanline" : " cairo"));
    const Camera cam = facing_camera();
    GraftalInstance g;
    g.length = static_cast<float>(40.0 * 10.0 / cam.focal_px);
    g.position = {0, -0.5 * g.length, 0};
    int64_t pixels = 0, n = 0;
    for (auto _ : state) {
        g.example = static_cast<uint16_t>(n % static_cast<int64_t>(d.examples.size()));
        g.angle = static_cast<float>(n % 90);
        const GraftalPatch p = draw_graftal(d, g, cam, {3.0f, 1, 1, 1}, 2048, raster);
        pixels += static_cast<int64_t>(p.pixels.size());
        ++n;
        benchmark::DoNotOptimize(p.pixels.data());
    }
    state.counters["patch_px"] =
        benchmark::Counter(double(pixels) / double(std::max<int64_t>(n, 1)));
    state.SetItemsProcessed(n);
}
BENCHMARK(BM_GraftalDraw)->ArgsProduct({{0, 1, 2, 3}, {0, 1}})->Unit(benchmark::kMicrosecond);

SceneDesc scene(const char* name, std::vector<std::string> sets = {}) {
    sets.push_back("/camera/width=960");
    sets.push_back("/camera/height=540");
    return load_scene(resolve_preset("scenes", name, "SCENE"), sets);
}

// The graftals stage alone at frame 97 of the truffula walk (96 frames replayed).
void BM_GraftalStage(benchmark::State& state) {
    const Shot shot = build_shot(scene("truffula-walk"));
    const FrameView view = view_at(shot.scene, frame_time(97, shot.scene.fps));
    uint64_t drawn = 0;
    for (auto _ : state) {
        SpriteSet sprites;
        drawn = add_graftal_sprites(shot, view, shot.scene.render, sprites).drawn;
        benchmark::DoNotOptimize(sprites.sprites.data());
    }
    state.counters["graftals"] = double(drawn);
    state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(drawn));
}
BENCHMARK(BM_GraftalStage)->Unit(benchmark::kMillisecond)->UseRealTime();

// Whole frames: each scene in its two styles.
struct Pair {
    const char* label;
    const char* scene;
    std::vector<std::string> sets;
};
const Pair kFrames[] = {
    {"mortefontaine strokes", "mortefontaine", {}},
    {"mortefontaine graftals, cairo",
     "mortefontaine-graftals",
     {"/render/graftal_raster=\"cairo\""}},
    {"truffula strokes",
     "truffula",
     {"/families/truffula/style=\"strokes\"", "/materials/turf/style=\"strokes\"",
      "/families/truffula/imposters=\"\"", "/materials/turf/imposters=\"\""}},
    {"truffula graftals, cairo",
     "truffula",
     {"/render/graftal_raster=\"cairo\"", "/families/truffula/imposters=\"\"",
      "/materials/turf/imposters=\"\""}},
    {"mortefontaine graftals, scanline", "mortefontaine-graftals", {}},
    {"truffula graftals, scanline",
     "truffula",
     {"/families/truffula/imposters=\"\"", "/materials/turf/imposters=\"\""}},
    {"truffula graftals and imposters (as shipped)", "truffula", {}},
};

void BM_Frame(benchmark::State& state) {
    const Pair& p = kFrames[state.range(0)];
    state.SetLabel(p.label);
    const Shot shot = build_shot(scene(p.scene, p.sets));
    const FrameSettings settings = scene_frame_settings(shot.scene);
    FrameReport rep;
    for (auto _ : state) {
        rep = FrameReport{};
        benchmark::DoNotOptimize(paint_frame(shot, still_view(shot.scene), settings, &rep));
    }
    state.counters["leaf_strokes"] = double(rep.leaf_sprites);
    state.counters["surface_strokes"] = double(rep.surface_sprites);
    state.counters["graftals"] = double(rep.graftal_sprites);
    state.counters["imposters"] = double(rep.imposter_sprites);
}
BENCHMARK(BM_Frame)->DenseRange(0, 6)->Unit(benchmark::kMillisecond)->UseRealTime();

// One seuss-fringe imposter facing a 960 x 540 camera, its quad `state.range(0)` pixels a side:
// its exact coverage, each pixel's centre inverted into its cell, two atlas levels read, keyed.
void BM_ImposterDraw(benchmark::State& state) {
    const ImposterDesc d = load_imposter("seuss-fringe");
    const ImposterAtlas atlas = imposter_atlas(d);
    const Camera cam = facing_camera();
    const double half = 0.5 * double(state.range(0)) * 10.0 / cam.focal_px;
    ImposterQuad q;
    q.v0 = {-half, -half, 0}, q.v1 = {half, -half, 0}, q.t0 = {-half, half, 0},
    q.t1 = {half, half, 0};
    q.color0 = {0.4f, 0.3f, 0.1f}, q.color1 = {0.5f, 0.4f, 0.2f};
    size_t pixels = 0;
    int column = 0;
    for (auto _ : state) {
        q.column = column++ % atlas.columns;
        const GraftalPatch p = draw_imposter(atlas, q, cam);
        pixels = p.pixels.size();
        benchmark::DoNotOptimize(p.pixels.data());
    }
    state.counters["pixels"] = double(pixels);
    state.SetItemsProcessed(int64_t(state.iterations()));
}
BENCHMARK(BM_ImposterDraw)->Arg(8)->Arg(32)->Arg(128)->Unit(benchmark::kMicrosecond);

// The imposters stage alone on the truffula still: every mesh's silhouette and the edges near it,
// occlusion rays, drawing.
void BM_ImposterStage(benchmark::State& state) {
    const Shot shot = build_shot(scene("truffula"));
    const FrameView view = still_view(shot.scene);
    ImposterStageReport r;
    for (auto _ : state) {
        SpriteSet sprites;
        r = add_imposter_sprites(shot, view, sprites);
        benchmark::DoNotOptimize(sprites.sprites.data());
    }
    state.counters["edges"] = 0;
    for (const ImposterObject& o : shot.imposters)
        state.counters["edges"] += double(o.edges.size());
    state.counters["candidates"] = double(r.candidates);
    state.counters["imposters"] = double(r.drawn);
    state.counters["pixels"] = double(r.pixels);
    state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(r.drawn));
}
BENCHMARK(BM_ImposterStage)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
