// `pleinair bench coherence SHOT`: the coherence table of an animated shot (coherence_measures.h).
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <optional>

#include "pipeline/bench/coherence_measures.h"
#include "pipeline/cli/commands.h"
#include "pipeline/frame/paint_frame.h"
#include "pipeline/input/draft.h"
#include "pipeline/input/error.h"
#include "pipeline/input/frame_range.h"
#include "pipeline/input/presets.h"
#include "pipeline/output/image_io.h"

namespace pleinair {

int run_bench_coherence(const BenchCommand& cmd) {
    const std::string file = resolve_preset("scenes", cmd.scene, "SCENE").string();
    SceneDesc scene = load_scene(file, cmd.set);
    if (!scene.animated())
        throw InputError(file, "/camera/track", "coherence is measured on an animated shot");
    const std::vector<int> frames = frames_to_paint(scene, cmd.frames);
    check_views(scene, frames, file);
    if (cmd.preview) halve_for_preview(scene, file);
    if (cmd.draft) apply_draft(scene.render, cmd.set);
    std::optional<FramePattern> save;
    if (!cmd.save.empty()) {
        save = parse_frame_pattern(cmd.save, "--save");
        if (!is_image_path(save->path(1)))
            throw InputError("--save", "",
                             "expected frame images ending in .png, .tif, .tiff or .exr, got \"" +
                                 cmd.save + "\"");
        const std::filesystem::path dir = std::filesystem::path(save->path(0)).parent_path();
        if (!dir.empty()) std::filesystem::create_directories(dir);
    }
    ShotOptions options;
    options.cache_sun_light = true;
    PassTimer timer;
    const Shot shot = build_shot(scene, options);
    const bool tty = isatty(fileno(stderr));
    const CoherenceReport r = measure_coherence(
        shot, frames, scene_frame_settings(shot.scene),
        [&](int done) {
            if (tty) std::fprintf(stderr, "\r%d/%zu frames", done, frames.size());
        },
        [&](int frame, const Frame& f) {
            // The frame as planned, the one animate paints: what the figures above measured.
            if (save) write_frame(save->path(frame), f);
        });
    if (tty) std::fprintf(stderr, "\n");
    const int w = scene.camera_params.width, h = scene.camera_params.height;
    std::printf(
        "Coherence of %s: frames %d-%d (%zu) at %dx%d, each painted four times (level "
        "of detail as planned, frozen at frame %d, off, boiling noise) in %.0f s.\n\n",
        cmd.scene.c_str(), frames.front(), frames.back(), frames.size(), w, h, frames.front(),
        timer.ms() / 1000);
    auto fmt = [](const char* f, double v) {
        char b[32];
        std::snprintf(b, sizeof b, f, v);
        return std::string(b);
    };
    auto ratio = [](uint64_t a, uint64_t b) { return b ? double(a) / double(b) : 0.0; };
    const double pairs = std::max(1, r.frames - 1);
    std::printf(
        "| shot | flicker: floor / shot / boiling | flicker score | pops | steepest fade per "
        "frame | cull pops | order swaps per frame: all / in one frame | area, LOD on vs off | "
        "L*, on vs off | area step | shape overlap | sprites on / off | fragments on / off |\n"
        "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    std::printf(
        "| %s | %.4f / %.4f / %.4f | %.3f | %llu | %.3f | %llu | %.1f / %.2f | %s | %s | %s | %s | "
        "%.2f | %.2f |\n",
        cmd.scene.c_str(), r.flicker_floor, r.flicker, r.flicker_boiling, r.flicker_score(),
        static_cast<unsigned long long>(r.pops), r.steepest_fade,
        static_cast<unsigned long long>(r.cull_pops), r.order_swaps / pairs, r.abrupt_swaps / pairs,
        r.lod ? fmt("%.1f%%", 100 * r.area_difference).c_str() : "no LOD",
        r.lod ? fmt("%.2f", r.lightness_difference).c_str() : "-",
        r.lod ? fmt("%.2f%%", 100 * r.area_step).c_str() : "-",
        r.lod
            ? (fmt("%.3f", r.shape_overlap) + " (floor " + fmt("%.3f", r.shape_floor) + ")").c_str()
            : "-",
        ratio(r.sprites_on, r.sprites_off), ratio(r.fragments_on, r.fragments_off));
    if (r.water)
        std::printf(
            "\nStill water's strokes alone, flicker without the mirror / with it / boiling: "
            "%.4f / %.4f / %.4f\n",
            r.water_flicker_dry, r.water_flicker, r.water_flicker_boiling);
    if (r.wind)
        std::printf(
            "\nThe trees' strokes alone, flicker in still air / in the wind / boiling: "
            "%.4f / %.4f / %.4f\n",
            r.tree_flicker_calm, r.tree_flicker, r.tree_flicker_boiling);
    if (!cmd.per_frame) return 0;
    std::printf(
        "\n| frame | area on | area off | on vs off | L* on | L* off | shape overlap | order "
        "swaps | in one frame |\n|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    for (const CoherenceReport::Frame& f : r.per_frame)
        std::printf("| %d | %.4f | %.4f | %+.1f%% | %.2f | %.2f | %.3f | %llu | %llu |\n", f.frame,
                    f.area_on, f.area_off,
                    f.area_off > 0 ? 100 * (f.area_on / f.area_off - 1) : 0.0, f.lightness_on,
                    f.lightness_off, f.shape_overlap,
                    static_cast<unsigned long long>(f.order_swaps),
                    static_cast<unsigned long long>(f.abrupt_swaps));
    return 0;
}

}  // namespace pleinair
