// The pleinair command line: CLI11 binds each command's options to its plain struct; errors
// become one line on stderr and exit code 2 (bad input) or 1 (runtime failure).
#include <tbb/global_control.h>

#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>

#include "generators/tree.h"
#include "pipeline/cli/commands.h"
#include "pipeline/error.h"
#include "pipeline/partial_files.h"

int main(int argc, char** argv) {
    using namespace pleinair;
    CLI::App app{"pleinair: seeded trees and landscapes, painted like Corot."};
    app.require_subcommand(1);
    app.fallthrough();  // global options such as --threads may follow the command
    app.set_help_all_flag("--help-all", "Help for every command");
    int threads = 0;
    app.add_option("--threads", threads, "Worker threads (default: all cores)")
        ->check(CLI::Range(1, 1024));

    TreeCommand tree;
    auto* t =
        app.add_subcommand("tree", "Grow one tree: meshes (OBJ, PLY) and leaf particles (PLY)");
    t->add_option("--preset", tree.preset, "Preset name (see `pleinair presets`) or JSON file")
        ->required();
    t->add_option("--seed", tree.seed, "Random seed; the same seed gives the same bytes");
    t->add_option("-o,--out", tree.out, "Output directory");
    t->add_flag("--stats", tree.stats, "Print one JSON line: counts, bounding box, median time");
    t->add_option("--repeat", tree.repeat, "Generations to time for --stats")
        ->check(CLI::Range(1, 100000));
    t->add_option("--set", tree.set,
                  "Override a preset key: POINTER=VALUE, e.g. /trunk/taper/base=0.9");
    t->add_option("--save-preset", tree.save_preset, "Write the fully resolved parameters to FILE");
    t->add_option("--position", tree.position, "Where the tree stands: x,y,z")
        ->delimiter(',')
        ->expected(3);
    t->add_option("--id", tree.id, "Tree id stored in every particle (seeds the painter's tint)");
    bool no_lod = false;
    t->add_flag("--no-lod", no_lod, "Skip the low-detail mesh");

    FamilyCommand family;
    auto* f = app.add_subcommand("family",
                                 "Grow N members of a family, seeds derived from one base seed");
    f->add_option("--preset", family.preset, "Preset name or JSON file")->required();
    f->add_option("--count", family.count, "Number of members")->check(CLI::Range(1, 100000));
    f->add_option("--seed", family.seed, "Base seed");
    f->add_option("-o,--out", family.out,
                  "Output directory (one folder per member), or an image path (.png, .tif, .exr) "
                  "for a painted contact sheet")
        ->required();
    f->add_option("--width", family.width, "Contact sheet width")->check(CLI::Range(16, 16384));
    f->add_option("--height", family.height, "Contact sheet height")->check(CLI::Range(16, 16384));
    f->add_option("--samples", family.samples,
                  "Contact sheet samples per pixel (1, 4 or 16; the feather is filtered)")
        ->check(CLI::IsMember({1, 4, 16}));
    f->add_option("--set", family.set, "Override a preset key: POINTER=VALUE");
    f->add_option("--save-preset", family.save_preset,
                  "Write the fully resolved parameters to FILE");

    RenderCommand render;
    auto* r = app.add_subcommand("render", "Paint a scene into an image (PNG, TIFF or EXR)");
    r->add_option("scene", render.scene, "Scene name (presets/scenes) or JSON file")->required();
    r->add_option("-o,--out", render.out, "Image to write: .png (8-bit sRGB), .tif, .exr (linear)")
        ->required();
    r->add_flag("--explain", render.explain,
                "Print the frame's plan: passes run or skipped and why, times, counts");
    r->add_flag("--aovs", render.aovs, "Add depth, object id, alpha, lightness channels (EXR)");
    r->add_option("--set", render.set, "Override a scene key: POINTER=VALUE, e.g. /camera/fov=30");
    double render_time = 0;
    int render_frame = 0;
    auto* r_time = r->add_option("--time", render_time,
                                 "Seconds into an animated scene (its camera and sun tracks)");
    auto* r_frame = r->add_option("--frame", render_frame,
                                  "Frame of an animated scene, from 1 at the scene's fps");

    AnimateCommand animate;
    auto* a = app.add_subcommand(
        "animate", "Paint the frames of an animated scene: one shot, then each frame in turn");
    a->add_option("scene", animate.scene, "Scene name (presets/scenes) or JSON file")->required();
    a->add_option("-o,--out", animate.out,
                  "Frame files; a run of # (or %04d) is the frame number: out/frame_####.png")
        ->required();
    a->add_option("--frames", animate.frames,
                  "Frames A-B or A-BxSTEP, from 1 (default: every frame of the track)");
    a->add_flag("--resume", animate.resume,
                "Keep frames already complete; clear temporaries left by killed runs");
    a->add_option("--video", animate.video, "Also encode the frames into FILE.mp4 (ffmpeg, H.264)");
    a->add_flag("--preview", animate.preview, "Half resolution, for a quick look");
    a->add_flag("--aovs", animate.aovs, "Add depth, object id, alpha, lightness channels (EXR)");
    a->add_flag("--explain", animate.explain, "Print the shot's passes and the first frame's plan");
    a->add_option("--set", animate.set, "Override a scene key: POINTER=VALUE");
    std::string progress = "auto";
    a->add_option("--progress", progress,
                  "auto: a bar on a terminal, else Progress/Saved lines; bar; log")
        ->check(CLI::IsMember({"auto", "bar", "log"}));

    BenchCommand bench;
    auto* b = app.add_subcommand("bench", "Measure what accuracy costs in time");
    b->add_option("what", bench.what, "What to measure: accuracy")
        ->required()
        ->check(CLI::IsMember({"accuracy"}));
    b->add_option("scene", bench.scene, "Scene name or JSON file")->required();
    b->add_option("--repeat", bench.repeat, "Renders per setting (median time reported)")
        ->check(CLI::Range(1, 1000));
    b->add_option("--set", bench.set, "Override a scene key: POINTER=VALUE");

    PresetsCommand presets;
    auto* p = app.add_subcommand("presets", "List the shipped presets, one line each");
    p->add_option("--reference", presets.reference,
                  "Print the Markdown reference of every key of one kind of file")
        ->check(CLI::IsMember({"trees", "shaders", "scenes"}));

    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::cerr << "pleinair: " << e.what() << " (see --help)\n";
        return 2;
    }
    tree.lod = !no_lod;
    if (*r_time) render.time = render_time;
    if (*r_frame) render.frame = render_frame;
    animate.progress = progress == "bar"   ? AnimateCommand::Progress::kBar
                       : progress == "log" ? AnimateCommand::Progress::kLog
                                           : AnimateCommand::Progress::kAuto;
    // From here on outputs are written; an interrupted run removes its temporaries.
    install_partial_cleanup();

    std::unique_ptr<tbb::global_control> limit;
    if (threads > 0)
        limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                      static_cast<size_t>(threads));
    try {
        if (*t) return run_tree(tree);
        if (*f) return run_family(family);
        if (*p) return run_presets(presets);
        if (*r) return run_render(render);
        if (*a) return run_animate(animate);
        if (*b) return run_bench_accuracy(bench);
    } catch (const InputError& e) {
        std::cerr << e.what() << "\n";
        return 2;
    } catch (const InvalidParams& e) {
        for (const auto& line : e.problems) std::cerr << "pleinair: " << line << "\n";
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "pleinair: error: " << e.what() << "\n";
        return 1;
    }
    return 2;
}
