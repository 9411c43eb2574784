// `pleinair bench accuracy SCENE`: what each quality setting costs in time and gains in
// accuracy, against a high-quality reference of the same scene.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>

#include "pipeline/cli/commands.h"
#include "pipeline/frame/paint_frame.h"
#include "pipeline/input/presets.h"
#include "pipeline/output/image_io.h"

namespace pleinair {

namespace {

struct Timed {
    Frame frame;
    double ms = 0;  // median over the repeats, of the whole paint (sprites to composite)
};

using SharedTrees = std::shared_ptr<const std::vector<BuiltTree>>;
using SharedLand = std::shared_ptr<const BuiltLandscape>;

// The time of what depends on the settings: the shot's ray scenes (the trees and the landscape
// are shared) and the frame.
Timed timed_paint(const SceneDesc& scene, const SharedTrees& trees, const SharedLand& land,
                  int repeat) {
    std::vector<double> ms;
    Timed out;
    for (int i = 0; i < repeat; ++i) {
        PassTimer t;
        const Shot shot = build_shot(scene, trees, land);
        out.frame = paint_frame(shot, still_view(shot.scene), scene_frame_settings(shot.scene));
        ms.push_back(t.ms());
    }
    std::sort(ms.begin(), ms.end());
    out.ms = ms[ms.size() / 2];
    return out;
}

}  // namespace

int run_bench_accuracy(const BenchCommand& cmd) {
    SceneDesc scene = load_scene(resolve_preset("scenes", cmd.scene, "SCENE"), cmd.set);
    const SharedTrees trees = std::make_shared<const std::vector<BuiltTree>>(
        build_trees(scene, scene.build.bark_coverage > 0));
    const bool landscape = scene.terrain.present || !scene.rocks.empty();

    // The reference: every setting at its most accurate (for a landscape: shadows through
    // every stroke, the underpainting at full resolution, surface strokes at 4 times the
    // scene's density).
    SceneDesc ref = scene;
    ref.render.samples = 16;
    ref.render.one_sample_px = 0;      // every stroke at 16
    ref.render.sky_one_sample_px = 0;  // the sky's too
    ref.render.octaves = 8;
    ref.render.palette_lut = false;
    ref.render.edge_lut = false;
    ref.render.filter_strokes = false;
    ref.render.shadows = ShadowMode::kTransmissive;
    ref.render.shadow_samples = ShadowSamples::kFragment;
    ref.render.underpaint_scale = 1.0f;
    ref.render.coverage_cutoff = 0;
    ref.build.surface_density = 4.0f;
    const SharedLand ref_land = std::make_shared<const BuiltLandscape>(build_landscape(ref));
    Timed reference = timed_paint(ref, trees, ref_land, 1);

    struct Row {
        std::string group, setting;
        std::function<void(SceneDesc&)> set;
    };
    std::vector<Row> rows = {
        {"antialiasing", "1 sample per pixel", [](SceneDesc& s) { s.render.samples = 1; }},
        {"antialiasing", "4 samples per pixel", [](SceneDesc& s) { s.render.samples = 4; }},
        {"antialiasing", "16 samples per pixel", [](SceneDesc& s) { s.render.samples = 16; }},
        {"antialiasing", "1 sample, filtered feather",
         [](SceneDesc& s) { s.render.samples = 1, s.render.filter_strokes = true; }},
        {"noise octaves", "1 octave", [](SceneDesc& s) { s.render.octaves = 1; }},
        {"noise octaves", "2 octaves", [](SceneDesc& s) { s.render.octaves = 2; }},
        {"noise octaves", "4 octaves", [](SceneDesc& s) { s.render.octaves = 4; }},
        {"palette", "exact per fragment", [](SceneDesc& s) { s.render.palette_lut = false; }},
        {"palette", "table per sprite", [](SceneDesc& s) { s.render.palette_lut = true; }},
        {"edge mask", "exact (sin, pow)", [](SceneDesc& s) { s.render.edge_lut = false; }},
        {"edge mask", "table", [](SceneDesc& s) { s.render.edge_lut = true; }},
        {"coverage cutoff", "0 (every stroke)", [](SceneDesc& s) { s.render.coverage_cutoff = 0; }},
        {"coverage cutoff", "1/2048", [](SceneDesc& s) { s.render.coverage_cutoff = 1.0f / 2048; }},
        {"coverage cutoff", "1/256", [](SceneDesc& s) { s.render.coverage_cutoff = 1.0f / 256; }},
    };
    rows.push_back({"large strokes", "every one at the samples above",
                    [](SceneDesc& s) { s.render.one_sample_px = 0; }});
    // The filter widens only the feathers of strokes at one sample: the reference's others keep
    // theirs.
    rows.push_back(
        {"large strokes", "at least 16 px across at one sample, filtered",
         [](SceneDesc& s) { s.render.one_sample_px = 8, s.render.filter_strokes = true; }});
    rows.push_back({"large strokes", "at least 32 px across at one sample, filtered (the default)",
                    [](SceneDesc& s) {
                        s.render.one_sample_px = RenderSettings{}.one_sample_px;
                        s.render.filter_strokes = true;
                    }});
    if (scene.sky.present) {
        rows.push_back({"sky strokes", "every one at the samples above",
                        [](SceneDesc& s) { s.render.sky_one_sample_px = 0; }});
        rows.push_back(
            {"sky strokes", "large ones at one sample, filtered (the default)", [](SceneDesc& s) {
                 s.render.sky_one_sample_px = RenderSettings{}.sky_one_sample_px;
                 s.render.filter_strokes = true;
             }});
    }
    if (scene.sun_casts_shadows) {
        rows.push_back({"shadows", "none", [](SceneDesc& s) { s.sun_casts_shadows = false; }});
        rows.push_back({"shadows", "per particle, threshold at 1/2", [](SceneDesc& s) {
                            s.render.shadows = ShadowMode::kThreshold;
                            s.render.shadow_samples = ShadowSamples::kParticle;
                        }});
        rows.push_back({"shadows", "per particle, transmissive",
                        [](SceneDesc& s) { s.render.shadow_samples = ShadowSamples::kParticle; }});
        rows.push_back({"shadows", "per fragment (4 x 4 rays a sprite), transmissive",
                        [](SceneDesc& s) { s.render.shadow_samples = ShadowSamples::kFragment; }});
    }
    if (landscape) {
        for (float u : {1.0f, 0.5f, 0.25f})
            rows.push_back({"underpainting", "at " + std::to_string(int(u * 100)) + "% resolution",
                            [u](SceneDesc& s) { s.render.underpaint_scale = u; }});
        for (float d : {0.25f, 0.5f, 1.0f, 2.0f, 4.0f}) {
            char label[48];
            std::snprintf(label, sizeof label, "%.2gx the scene's", d);
            rows.push_back(
                {"surface density", label, [d](SceneDesc& s) { s.build.surface_density = d; }});
        }
    }
    std::printf(
        "Reference: %s at %dx%d, 16 samples per pixel, 8 octaves, exact palette and edge "
        "mask, every stroke painted%s: %.0f ms.\nEach row changes one setting of the "
        "reference.\n\n",
        cmd.scene.c_str(), scene.camera.width, scene.camera.height,
        landscape
            ? ", transmissive shadows per fragment, full-resolution underpainting, 4x surface "
              "density"
            : "",
        reference.ms);
    std::printf("| setting | value | time (ms) | RMSE | PSNR (dB) |\n|---|---|---:|---:|---:|\n");
    for (const Row& row : rows) {
        SceneDesc s = ref;
        row.set(s);
        const bool rebuild = s.build.surface_density != ref.build.surface_density;
        const SharedLand land =
            rebuild ? std::make_shared<const BuiltLandscape>(build_landscape(s)) : ref_land;
        Timed t = timed_paint(s, trees, land, cmd.repeat);
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
    Timed t = timed_paint(def, trees, std::make_shared<const BuiltLandscape>(build_landscape(def)),
                          cmd.repeat);
    ImageError e = compare_frames(t.frame, reference.frame);
    std::printf(
        "| scene's settings | %d spp, %d octave(s), palette %s, edge %s | %.0f | %.5f | %.1f |\n",
        scene.render.samples, scene.render.octaves, scene.render.palette_lut ? "table" : "exact",
        scene.render.edge_lut ? "table" : "exact", t.ms, e.rmse, e.psnr);
    return 0;
}

}  // namespace pleinair
