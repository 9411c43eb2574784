// `pleinair bench accuracy SCENE`: what each quality setting costs in time and gains in
// accuracy, against a high-quality reference of the same scene.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>

#include "pipeline/cli/commands.h"
#include "pipeline/image_io.h"
#include "pipeline/paint.h"
#include "pipeline/presets.h"

namespace pleinair {

namespace {

struct Timed {
    Frame frame;
    double ms = 0;  // median over the repeats, of the whole paint (sprites to composite)
};

Timed timed_paint(const SceneDesc& scene, const std::vector<BuiltTree>& trees, int repeat) {
    FramePlan plan = plan_frame(scene, {});
    std::vector<double> ms;
    Timed out;
    for (int i = 0; i < repeat; ++i) {
        auto t0 = std::chrono::steady_clock::now();
        out.frame = paint_frame(scene, trees, plan);
        ms.push_back(
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                .count());
    }
    std::sort(ms.begin(), ms.end());
    out.ms = ms[ms.size() / 2];
    return out;
}

}  // namespace

int run_bench_accuracy(const BenchCommand& cmd) {
    SceneDesc scene = load_scene(resolve_preset("scenes", cmd.scene, "SCENE"), cmd.set);
    std::vector<BuiltTree> trees = build_trees(scene, scene.render.bark_coverage > 0);

    // The reference: every setting at its most accurate.
    SceneDesc ref = scene;
    ref.render.samples = 16;
    ref.render.octaves = 8;
    ref.render.palette_lut = false;
    ref.render.edge_lut = false;
    ref.render.filter_strokes = false;
    Timed reference = timed_paint(ref, trees, 1);

    struct Row {
        std::string group, setting;
        std::function<void(RenderSettings&)> set;
    };
    std::vector<Row> rows = {
        {"antialiasing", "1 sample per pixel", [](RenderSettings& r) { r.samples = 1; }},
        {"antialiasing", "4 samples per pixel", [](RenderSettings& r) { r.samples = 4; }},
        {"antialiasing", "16 samples per pixel", [](RenderSettings& r) { r.samples = 16; }},
        {"antialiasing", "1 sample, filtered feather",
         [](RenderSettings& r) { r.samples = 1, r.filter_strokes = true; }},
        {"noise octaves", "1 octave", [](RenderSettings& r) { r.octaves = 1; }},
        {"noise octaves", "2 octaves", [](RenderSettings& r) { r.octaves = 2; }},
        {"noise octaves", "4 octaves", [](RenderSettings& r) { r.octaves = 4; }},
        {"palette", "exact per fragment", [](RenderSettings& r) { r.palette_lut = false; }},
        {"palette", "table per sprite", [](RenderSettings& r) { r.palette_lut = true; }},
        {"edge mask", "exact (sin, pow)", [](RenderSettings& r) { r.edge_lut = false; }},
        {"edge mask", "table", [](RenderSettings& r) { r.edge_lut = true; }},
    };
    std::printf(
        "Reference: %s at %dx%d, 16 samples per pixel, 8 octaves, exact palette and edge "
        "mask: %.0f ms.\nEach row changes one setting of the reference.\n\n",
        cmd.scene.c_str(), scene.camera.width, scene.camera.height, reference.ms);
    std::printf("| setting | value | time (ms) | RMSE | PSNR (dB) |\n|---|---|---:|---:|---:|\n");
    for (const Row& row : rows) {
        SceneDesc s = ref;
        row.set(s.render);
        Timed t = timed_paint(s, trees, cmd.repeat);
        ImageError e = compare_frames(t.frame, reference.frame);
        char psnr[32];
        if (std::isfinite(e.psnr))
            std::snprintf(psnr, sizeof psnr, "%.1f", e.psnr);
        else
            std::snprintf(psnr, sizeof psnr, "identical");
        std::printf("| %s | %s | %.0f | %.5f | %s |\n", row.group.c_str(), row.setting.c_str(),
                    t.ms, e.rmse, psnr);
    }
    SceneDesc def = scene;
    Timed t = timed_paint(def, trees, cmd.repeat);
    ImageError e = compare_frames(t.frame, reference.frame);
    std::printf(
        "| scene's settings | %d spp, %d octave(s), palette %s, edge %s | %.0f | %.5f | %.1f |\n",
        scene.render.samples, scene.render.octaves, scene.render.palette_lut ? "table" : "exact",
        scene.render.edge_lut ? "table" : "exact", t.ms, e.rmse, e.psnr);
    return 0;
}

}  // namespace pleinair
