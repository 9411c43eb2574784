// `pleinair bench look SCENE`: the look's measures of a still or of a shot's frame, four
// tables of one row (look_measures.h; crown_look.h and palette_look.h; the near ground's brush;
// the plan, mass_look.h);
// --save writes the frame it measured.
#include <cstdio>

#include "pipeline/bench/contact_look.h"
#include "pipeline/bench/crown_look.h"
#include "pipeline/bench/edge_look.h"
#include "pipeline/bench/grain_look.h"
#include "pipeline/bench/look_measures.h"
#include "pipeline/bench/mass_look.h"
#include "pipeline/bench/palette_look.h"
#include "pipeline/cli/commands.h"
#include "pipeline/frame/paint_frame.h"
#include "pipeline/input/error.h"
#include "pipeline/input/presets.h"
#include "pipeline/output/image_io.h"
#include "pipeline/shot/shot.h"

namespace pleinair {

namespace {

// Trees smaller than this share of the frame are too few pixels for an outline to mean much.
constexpr double kCrownMinShare = 0.0005;

// A 5 x 5 window of paint whose L* spreads less than this is smooth: no brush mark shows in it
// (one L* unit is about the least step the eye sees between neighbouring greys).
constexpr double kSmoothSpread = 1.0;

// The second table: the crowns' median measures (crown_look.h) and the palette (palette_look.h).
void print_crowns_and_palette(const std::string& name, const Shot& shot, const FrameView& view,
                              const Frame& f, const Mask& sky) {
    const size_t min_px =
        static_cast<size_t>(kCrownMinShare * static_cast<double>(f.width) * f.height);
    const std::vector<CrownLook> crowns =
        measure_crowns(tree_pixels(shot, view, f), sky, f.width, f.height, min_px);
    const CrownLook c = median_crown(crowns), a = pooled_crown(crowns);
    const PaletteLook p = palette_look(f);
    std::printf(
        "\n| scene | crowns | crowns' medians: sky inside / edge / bark inside | weighed by area: "
        "sky inside / edge / bark inside | chroma: mean / p95 | warm accents | L* median | L* in "
        "0-20 / 20-40 / 40-60 / 60-80 / 80-100 |\n|---|---:|---:|---:|---:|---:|---:|---:|\n");
    // Shares of the frame as percentages, to the digits their targets need: a warm accent is a
    // few hundredths of a percent, the darkest band a percent or two (BENCHMARKS.md).
    std::printf(
        "| %s | %zu | %.3f / %.2f / %.3f | %.3f / %.2f / %.3f | %.1f / %.1f | %.3f%% | %.1f | "
        "%.2f%% / %.1f%% / %.1f%% / %.1f%% / %.1f%% |\n",
        name.c_str(), c.pixels, c.sky, c.edge, c.bark, a.sky, a.edge, a.bark, p.chroma_mean,
        p.chroma_p95, 100 * p.warm, p.lightness_median, 100 * p.lightness[0], 100 * p.lightness[1],
        100 * p.lightness[2], 100 * p.lightness[3], 100 * p.lightness[4]);
}

// The third table: the near ground's brush (issue 27 §4): its texture at the two scales, the
// share of it left smooth (kSmoothSpread), the inside of soft blobs, and its grain (issue 52
// §3, grain_look.h): touches laid along the land against round spots; and whether the trees
// stand in it (§3 and §7, contact_look.h): the ground darker beside each trunk's foot.
void print_foreground(const std::string& name, const Frame& f, const std::vector<float>& l,
                      const std::vector<uint8_t>& near, const ContactLook& feet) {
    uint64_t px = 0;
    for (uint8_t v : near) px += v;
    const double t5 = brush_texture(l, f.width, f.height, near, 2);
    const double t17 = brush_texture(l, f.width, f.height, near, 8);
    const double smooth = smooth_share(l, f.width, f.height, near, 2, kSmoothSpread);
    const GrainLook grain = grain_look(l, f.width, f.height, near);
    std::printf(
        "\n| scene | near ground (within %.0f m): pixels | L* texture 5 px / 17 px | smooth "
        "share (5 px windows under %.1f L*) | grain: edges within %.0f deg of horizontal "
        "(round spots 0.33) / coherence (angle) | trees' feet: measured / ground beside the "
        "trunk darker by, median L* / standing (%.0f L* or more) "
        "|\n|---|---:|---:|---:|---:|---:|\n",
        kNearGround, kSmoothSpread, kGrainTolerance, kContactStanding);
    std::printf("| %s | %llu | %.2f / %.2f | %.3f | %.2f / %.2f (%.0f) | %d / %.1f / %.2f |\n",
                name.c_str(), static_cast<unsigned long long>(px), t5, t17, smooth,
                grain.horizontal, grain.coherence, grain.angle, feet.bases, feet.median_drop,
                feet.standing_share);
}

// The fourth table: the picture's plan (issue 52 §7): whether the open sky repeats a motif, the
// values the frame holds blurred to its masses (mass_look.h), whether the crowns' touches keep
// an edge (edge_look.h) and which way they run (grain_look.h).
void print_plan(const std::string& name, const Frame& f, const std::vector<float>& l,
                const std::vector<uint8_t>& sky, const std::vector<uint8_t>& trees) {
    const RepeatLook rep = texture_repeat(l, f.width, f.height, sky);
    const EdgeLook edges = edge_look(l, f.width, f.height, trees);
    const ValueMasses v = value_masses(l, f.width, f.height);
    const GrainLook grain = grain_look(l, f.width, f.height, trees);
    std::string modes;
    for (size_t k = 0; k < v.modes.size(); ++k) {
        char buf[48];
        std::snprintf(buf, sizeof buf, "%s%.0f (%.0f%%)", k ? ", " : "", v.modes[k],
                      100 * v.shares[k]);
        modes += buf;
    }
    std::printf(
        "\n| scene | sky's repeat (offset px) | values at 1/30 blur | their L* (share) "
        "| trees' blurred edges (median width px) | trees' grain: edges within %.0f deg of "
        "horizontal / coherence |\n|---|---:|---:|---|---:|---:|\n",
        kGrainTolerance);
    std::printf("| %s | %.2f (%d, %d) | %d | %s | %.2f (%.1f) | %.2f / %.2f |\n", name.c_str(),
                rep.score, rep.dx, rep.dy, v.values, modes.c_str(), edges.blurred_share,
                edges.median_width, grain.horizontal, grain.coherence);
}

}  // namespace

int run_bench_look(const BenchCommand& cmd) {
    const std::string file = resolve_preset("scenes", cmd.scene, "SCENE").string();
    const SceneDesc scene = load_scene(file, cmd.set);
    // The frame `render` paints with the same --frame: one rule for the time and the view.
    const double t = frame_time_of(std::nullopt, cmd.frame, scene, file);
    if (!cmd.save.empty() && !is_image_path(cmd.save))
        throw InputError(
            "--save", "",
            "expected an image path ending in .png, .tif, .tiff or .exr, got \"" + cmd.save + "\"");
    FrameView view;
    try {
        view = view_at(scene, t);
    } catch (const std::runtime_error& e) {
        throw InputError(file, "/camera/track", e.what());
    }
    const Shot shot = build_shot(scene);
    PassTimer timer;
    const Frame f = paint_frame(shot, view, scene_frame_settings(shot.scene, true));
    const double ms = timer.ms();
    if (!cmd.save.empty()) write_frame(cmd.save, f);
    const LookRegions r = look_regions(shot, view, f);
    const std::vector<float> l = frame_lightness(f);
    uint64_t sky_px = 0, tree_px = 0, pairs = 0;
    const double sky2 = brush_texture(l, f.width, f.height, r.sky, 2, &sky_px);
    const double trees2 = brush_texture(l, f.width, f.height, r.trees, 2, &tree_px);
    const double sky8 = brush_texture(l, f.width, f.height, r.sky, 8);
    const double trees8 = brush_texture(l, f.width, f.height, r.trees, 8);
    const double mirror = mirror_correlation(l, f.width, f.height, r.water, &pairs);
    const MirrorMatch glass = mirror_match(f, l,
                                           mirror_sources(f, view.camera, shot.scene.water.level,
                                                          r.water, water_stroke_id(shot.scene)));
    std::string sets;
    for (const std::string& s : cmd.set) sets += (sets.empty() ? " " : ", ") + s;
    std::printf(
        "| scene | L* texture 5 px: sky / trees | 17 px: sky / trees | sky over trees, 5 / 17 "
        "px | sky pixels | sky: mean flat run, px | water vs bank mirrored about the shore: "
        "correlation (pairs) | water vs what it mirrors: correlation, pixels / 8 px forms "
        "(pairs) | water over what it mirrors: L* / chroma | frame "
        "|\n|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    std::printf(
        "| %s%s | %.2f / %.2f | %.2f / %.2f | %.2f / %.2f | %llu | %.2f | %.3f (%llu) | %.3f / "
        "%.4f (%llu) | %.2f / %.2f | %.0f ms |\n",
        cmd.scene.c_str(), sets.c_str(), sky2, trees2, sky8, trees8,
        trees2 > 0 ? sky2 / trees2 : 0.0, trees8 > 0 ? sky8 / trees8 : 0.0,
        static_cast<unsigned long long>(sky_px), mean_flat_run(f, r.sky), mirror,
        static_cast<unsigned long long>(pairs), glass.pixels, glass.forms,
        static_cast<unsigned long long>(glass.pairs), glass.lightness, glass.chroma, ms);
    (void)tree_px;
    print_crowns_and_palette(cmd.scene + sets, shot, view, f, r.sky);
    print_foreground(
        cmd.scene + sets, f, l, r.near_ground,
        contact_look(l, f.width, f.height, f.object_id, r.sky, tree_bases(shot, view, f)));
    print_plan(cmd.scene + sets, f, l, r.sky, r.trees);
    return 0;
}

}  // namespace pleinair
