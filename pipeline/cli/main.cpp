// The pleinair command line: CLI11 binds each command's options to its plain struct; errors
// become one line on stderr and exit code 2 (bad input) or 1 (runtime failure).
#include <tbb/global_control.h>

#include <CLI/CLI.hpp>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <limits>
#include <memory>

#include "generators/tree.h"
#include "pipeline/cli/commands.h"
#include "pipeline/input/error.h"
#include "pipeline/input/limits.h"
#include "pipeline/input/scene.h"
#include "pipeline/output/partial_files.h"
#include "pipeline/shot/rays.h"

namespace {

using namespace pleinair;

// A whole number from 0 to `max`, in digits: CLI11 alone would read "-1" into an unsigned
// option as its largest value and clamp a number past the type's range to it.
CLI::Validator whole_number(uint64_t max) {
    return CLI::Validator(
        [max](std::string& s) -> std::string {
            const std::string expected = "expected a whole number from 0 to " + std::to_string(max);
            if (s.empty() || s.find_first_not_of("0123456789") != std::string::npos)
                return expected + ", got " + s;
            errno = 0;
            const unsigned long long v = std::strtoull(s.c_str(), nullptr, 10);
            if (errno == ERANGE || v > max) return expected + ", got " + s;
            return "";
        },
        "0.." + std::to_string(max));
}

// A finite number whose magnitude is at most `limit` ("nan" and "inf" read as doubles, and
// would flow into every output); `expected` is the message's description of it.
CLI::Validator finite_number(double limit, const std::string& expected, const std::string& name) {
    return CLI::Validator(
        [limit, expected](std::string& s) -> std::string {
            char* end = nullptr;
            const double v = std::strtod(s.c_str(), &end);
            if (end == s.c_str() || *end != '\0' || !(std::abs(v) <= limit))
                return "expected " + expected + ", got " + s;
            return "";
        },
        name);
}

const CLI::Validator kFinite =
    finite_number(std::numeric_limits<double>::max(), "a finite number", "FINITE");
// A world coordinate: within the world a scene may use (scene.h).
const CLI::Validator kWorldCoordinate = finite_number(
    kMaxWorldCoordinate,
    "a finite number within +-" + std::to_string(static_cast<long long>(kMaxWorldCoordinate)) +
        " (the world pleinair supports)",
    "COORDINATE");

// A subcommand and what runs it.
struct Command {
    CLI::App* app;
    std::function<int()> run;
};

// The `tree` command's options; returns what runs it once they are parsed.
Command add_tree(CLI::App& app) {
    auto c = std::make_shared<TreeCommand>();
    auto* t = app.add_subcommand("tree",
                                 "Grow one tree: meshes (OBJ, PLY), leaf particles (PLY) and the "
                                 "tree as glTF 2.0 (tree.glb)");
    t->add_option("--preset", c->preset, "Preset name (see `pleinair presets`) or JSON file")
        ->required();
    t->add_option("--seed", c->seed, "Random seed; the same seed gives the same bytes")
        ->check(whole_number(UINT64_MAX));
    t->add_option("-o,--out", c->out, "Output directory");
    t->add_flag("--stats", c->stats, "Print one JSON line: counts, bounding box, median time");
    t->add_option("--repeat", c->repeat, "Generations to time for --stats")
        ->check(CLI::Range(1, 100000));
    t->add_option("--set", c->set,
                  "Override a preset key: POINTER=VALUE, e.g. /trunk/taper/base=0.9");
    t->add_option("--save-preset", c->save_preset, "Write the fully resolved parameters to FILE");
    t->add_option("--position", c->position, "Where the tree stands: x,y,z")
        ->delimiter(',')
        ->expected(3)
        ->check(kWorldCoordinate);
    t->add_option("--id", c->id, "Tree id stored in every particle (seeds the painter's tint)")
        ->check(whole_number(UINT32_MAX));
    t->add_option("--format", c->format,
                  "Files in the tree folder besides tree.json: \"all\" (OBJ, PLY and tree.glb), "
                  "\"glb\" (tree.glb alone) or \"obj-ply\"")
        ->check(CLI::IsMember({"all", "glb", "obj-ply"}));
    auto no_lod = std::make_shared<bool>(false);
    t->add_flag("--no-lod", *no_lod, "Skip the low-detail mesh");

    return {t, [=] {
                c->lod = !*no_lod;
                return run_tree(*c);
            }};
}

// The `family` command's options; returns what runs it once they are parsed.
Command add_family(CLI::App& app) {
    auto c = std::make_shared<FamilyCommand>();
    CLI::App* f = app.add_subcommand(
        "family", "Grow N members of a family, seeds derived from one base seed");
    f->add_option("--preset", c->preset, "Preset name or JSON file")->required();
    f->add_option("--count", c->count, "Number of members (at most --limit members)")
        ->check(CLI::Range(1, 100000000));
    f->add_option("--seed", c->seed, "Base seed")->check(whole_number(UINT64_MAX));
    f->add_option("-o,--out", c->out,
                  "Output directory (one folder per member), or an image path (.png, .tif, .exr) "
                  "for a painted contact sheet")
        ->required();
    f->add_option("--width", c->width, "Contact sheet width")->check(CLI::Range(16, 16384));
    f->add_option("--height", c->height, "Contact sheet height")->check(CLI::Range(16, 16384));
    f->add_option("--samples", c->samples,
                  "Contact sheet samples per pixel (1, 4 or 16; the feather is filtered)")
        ->check(CLI::IsMember({1, 4, 16}));
    f->add_option("--style", c->style,
                  "Contact sheet: paint the crowns in \"strokes\" (the default) or as a graftal "
                  "description's tufts (a name from presets/graftals or a JSON file)");
    f->add_option("--set", c->set, "Override a preset key: POINTER=VALUE");
    f->add_option("--save-preset", c->save_preset, "Write the fully resolved parameters to FILE");
    f->add_option("--format", c->format,
                  "Files in the tree folder besides tree.json: \"all\" (OBJ, PLY and tree.glb), "
                  "\"glb\" (tree.glb alone) or \"obj-ply\"")
        ->check(CLI::IsMember({"all", "glb", "obj-ply"}));

    return {f, [=] { return run_family(*c); }};
}

// The `render` command's options; returns what runs it once they are parsed.
Command add_render(CLI::App& app) {
    auto c = std::make_shared<RenderCommand>();
    CLI::App* r = app.add_subcommand("render", "Paint a scene into an image (PNG, TIFF or EXR)");
    r->add_option("scene", c->scene, "Scene name (presets/scenes) or JSON file")->required();
    r->add_option("-o,--out", c->out,
                  "Image to write: .png (8-bit sRGB), .tif, .exr (linear); needed unless an "
                  "--export option is given");
    r->add_option("--export", c->export_glb,
                  "Write the scene as glTF 2.0 (.glb): terrain, water, rocks and meshes, every "
                  "tree as an instance of its grown member, the sun, and the camera with its "
                  "track as an animation");
    r->add_option("--export-instancing", c->export_instancing,
                  "How trees of one member share its mesh in --export: \"gpu\" "
                  "(EXT_mesh_gpu_instancing, the default) or \"nodes\" (a node per tree, which "
                  "every client reads, Blender 3.4 among them)")
        ->check(CLI::IsMember({"gpu", "nodes"}));
    r->add_flag("--export-low-detail", c->export_low_detail,
                "Trees in --export at their low-detail level alone (about a quarter of the size)");
    r->add_option("--export-height-map", c->export_height_map,
                  "Write the terrain's heights at its grid's resolution: .png or .tif (16-bit, "
                  "the lowest height 0 and the highest 65535, both printed) or .exr (float "
                  "metres); /terrain/height_map reads it back");
    r->add_flag("--explain", c->explain,
                "Print the frame's plan: passes run or skipped and why, times, counts");
    r->add_flag("--aovs", c->aovs, "Add depth, object id, alpha, lightness channels (EXR)");
    r->add_flag("--preview", c->preview, "Half resolution, as animate --preview");
    r->add_flag("--draft", c->draft,
                "Paint lighter for a quick look (README, \"The draft\"); --set keeps its keys");
    r->add_flag("--progress", c->progress,
                "Report each stage and the paint's progress on stderr (always past 16 "
                "megapixels)");
    r->add_option("--set", c->set, "Override a scene key: POINTER=VALUE, e.g. /camera/fov=30");
    auto time = std::make_shared<double>(0);
    auto frame = std::make_shared<int>(0);
    CLI::Option* time_opt =
        r->add_option("--time", *time, "Seconds into an animated scene (its camera and sun tracks)")
            ->check(kFinite);
    CLI::Option* frame_opt =
        r->add_option("--frame", *frame, "Frame of an animated scene, from 1 at the scene's fps");

    return {r, [=] {
                if (*time_opt) c->time = *time;
                if (*frame_opt) c->frame = *frame;
                return run_render(*c);
            }};
}

// The `animate` command's options; returns what runs it once they are parsed.
Command add_animate(CLI::App& app) {
    auto c = std::make_shared<AnimateCommand>();
    CLI::App* a = app.add_subcommand(
        "animate", "Paint the frames of an animated scene: one shot, then each frame in turn");
    a->add_option("scene", c->scene, "Scene name (presets/scenes) or JSON file")->required();
    a->add_option("-o,--out", c->out,
                  "Frame files; a run of # (or %04d) is the frame number: out/frame_####.png")
        ->required();
    a->add_option("--frames", c->frames,
                  "Frames A-B or A-BxSTEP, from 1 (default: every frame of the track)");
    a->add_flag("--resume", c->resume,
                "Keep frames already complete; clear temporaries left by killed runs");
    a->add_option("--video", c->video, "Also encode the frames into FILE.mp4 (ffmpeg, H.264)");
    a->add_flag("--preview", c->preview, "Half resolution, for a quick look");
    a->add_flag("--draft", c->draft,
                "Paint lighter for a quick look (README, \"The draft\"); --set keeps its keys");
    a->add_flag("--aovs", c->aovs, "Add depth, object id, alpha, lightness channels (EXR)");
    a->add_flag("--explain", c->explain,
                "Print the shot's passes and the first frame's plan; after the frames, each "
                "pass's median time over the later frames");
    a->add_option("--set", c->set, "Override a scene key: POINTER=VALUE");
    auto progress = std::make_shared<std::string>("auto");
    a->add_option("--progress", *progress,
                  "auto: a bar on a terminal, else Progress/Saved lines; bar; log")
        ->check(CLI::IsMember({"auto", "bar", "log"}));

    return {a, [=] {
                c->progress = *progress == "bar"   ? AnimateCommand::Progress::kBar
                              : *progress == "log" ? AnimateCommand::Progress::kLog
                                                   : AnimateCommand::Progress::kAuto;
                return run_animate(*c);
            }};
}

// The `bench` command's options; returns what runs it once they are parsed.
Command add_bench(CLI::App& app) {
    auto c = std::make_shared<BenchCommand>();
    CLI::App* b = app.add_subcommand("bench", "Measure what accuracy costs in time");
    b->add_option("what", c->what,
                  "What to measure: accuracy (each quality setting's time and error), "
                  "coherence (flicker, pops, order swaps, silhouette of an animated shot), look "
                  "(brush texture of the sky against the trees, banding, water's mirror), trees "
                  "(each tree family's form from the side: crown proportions, clear trunk, "
                  "droop, clumps, sky in the crown)")
        ->required()
        ->check(CLI::IsMember({"accuracy", "coherence", "look", "trees"}));
    b->add_option("scene", c->scene,
                  "Scene name or JSON file; for trees, a tree preset or file, or all")
        ->required();
    b->add_option("--repeat", c->repeat, "Renders per setting (median time reported)")
        ->check(CLI::Range(1, 1000));
    b->add_option("--set", c->set, "Override a scene key (trees: a tree preset's): POINTER=VALUE");
    b->add_option("--frames", c->frames, "coherence: frames A-B[xSTEP] (default: the track's)");
    b->add_flag("--preview", c->preview, "coherence: half the resolution");
    b->add_flag("--draft", c->draft, "coherence: painted as render --draft paints");
    b->add_flag("--per-frame", c->per_frame,
                "coherence: also a row per frame (area and L* on and off, swaps)");
    b->add_option("--frame", c->frame,
                  "look: the frame of an animated scene to measure (default: its first, as "
                  "render paints)");
    b->add_option("--save", c->save,
                  "coherence: write each frame as planned (a pattern with #, as animate's -o); "
                  "look: write the frame measured (the pixels render and animate paint)");
    CLI::Option* members = b->add_option("--members", c->members, "trees: members per family")
                               ->check(CLI::Range(1, 64));
    CLI::Option* seed = b->add_option("--seed", c->seed, "trees: the first member's seed")
                            ->check(whole_number(UINT64_MAX));
    CLI::Option* width = b->add_option("--width", c->cell_width, "trees: the side view's width")
                             ->check(CLI::Range(64, 4096));
    CLI::Option* height = b->add_option("--height", c->cell_height, "trees: the side view's height")
                              ->check(CLI::Range(64, 4096));

    return {b, [=] {
                // Options another kind reads are refused, not silently dropped.
                if (c->what != "coherence")
                    for (const auto& [flag, given] :
                         {std::pair{"--preview", c->preview}, std::pair{"--draft", c->draft},
                          std::pair{"--per-frame", c->per_frame}})
                        if (given)
                            throw InputError(flag, "",
                                             std::string("only bench coherence reads ") + flag +
                                                 ", not bench " + c->what);
                if (c->what != "trees")
                    for (const CLI::Option* o : {members, seed, width, height})
                        if (o->count())
                            throw InputError(o->get_name(), "",
                                             "only bench trees reads " + o->get_name() +
                                                 ", not bench " + c->what);
                if (c->what == "trees")
                    for (const auto& [flag, given] : {std::pair{"--frames", !c->frames.empty()},
                                                      std::pair{"--frame", c->frame.has_value()},
                                                      std::pair{"--save", !c->save.empty()}})
                        if (given)
                            throw InputError(flag, "",
                                             std::string("bench trees does not read ") + flag);
                return c->what == "coherence" ? run_bench_coherence(*c)
                       : c->what == "look"    ? run_bench_look(*c)
                       : c->what == "trees"   ? run_bench_trees(*c)
                                              : run_bench_accuracy(*c);
            }};
}

// The `presets` command's options; returns what runs it once they are parsed.
Command add_presets(CLI::App& app) {
    auto c = std::make_shared<PresetsCommand>();
    CLI::App* p = app.add_subcommand("presets", "List the shipped presets, one line each");
    p->add_option("--reference", c->reference,
                  "Print the Markdown reference of every key of one kind of file, or of the "
                  "settings --draft eases")
        ->check(CLI::IsMember({"trees", "shaders", "scenes", "graftals", "imposters", "draft"}));

    return {p, [=] { return run_presets(*c); }};
}

// The `studio` command's options; returns what runs it once they are parsed.
Command add_studio(CLI::App& app) {
    auto c = std::make_shared<StudioCommand>();
    CLI::App* s = app.add_subcommand(
        "studio", "A local page that paints every change as you make it (Ctrl-C stops it)");
    s->add_option("scene", c->scene, "Scene name (presets/scenes) or JSON file");
    s->add_option("--preset", c->preset, "A tree preset (name or file), grown alone and framed");
    s->add_option("--set", c->set, "Override a scene key to start from: POINTER=VALUE");
    s->add_option("--host", c->host,
                  "Interface to listen on (default 127.0.0.1; another exposes the studio to "
                  "the network)");
    s->add_option("--port", c->port, "Port (default 8420; 0: any free port)")
        ->check(CLI::Range(0, 65535));
    s->add_option("--save-to", c->save_to,
                  "Folder where \"keep\" writes presets (default ./presets), the only place "
                  "the studio writes");

    return {s, [=] {
                if (c->scene.empty() == c->preset.empty())
                    throw InputError("studio", "",
                                     "give a SCENE or --preset TREE (one of them, not both)");
                return run_studio(*c);
            }};
}

// The `camera` command's options; returns what runs it once they are parsed.
Command add_camera(CLI::App& app) {
    auto c = std::make_shared<CameraCommand>();
    CLI::App* k = app.add_subcommand(
        "camera",
        "Print the camera at each frame as JSON lines (eye, forward, up, focal length in pixels) "
        "and where world points land in its image (x right, y down, in pixels; depth)");
    k->add_option("scene", c->scene, "Scene name (presets/scenes) or JSON file")->required();
    k->add_option("--frames", c->frames, "Frames: A-B or A-BxSTEP (default: the whole track)");
    k->add_option("--point", c->points, "A world point x,y,z to project (repeatable)")
        ->delimiter(',')
        ->check(kWorldCoordinate);
    k->add_option("--set", c->set, "Override a scene key: POINTER=VALUE");
    return {k, [=] { return run_camera(*c); }};
}

}  // namespace

int main(int argc, char** argv) {
    using namespace pleinair;
    CLI::App app{"pleinair: seeded trees and landscapes, painted like Corot."};
    app.require_subcommand(1);
    app.fallthrough();  // global options such as --threads may follow the command
    app.set_help_all_flag("--help-all", "Help for every command");
    int threads = 0;
    app.add_option("--threads", threads, "Worker threads (default: all cores)")
        ->check(CLI::Range(1, 1024));
    bool fast_rays = false;
    app.add_flag("--fast-rays", fast_rays,
                 "Let Embree trace with the widest instruction set this CPU has (AVX2, AVX-512) "
                 "instead of SSE2: shadow rays up to 1.5x faster, but the bytes then depend on "
                 "the CPU, so machines of a farm may paint a few values differently");
    std::vector<std::string> limit_settings;
    app.add_option("--limit", limit_settings,
                   "Raise (or lower) a limit checked before work starts: NAME=N, repeatable. "
                   "Limits and their defaults:\n" +
                       describe_limits())
        ->each([](const std::string& v) {
            if (std::string why = set_limit(v); !why.empty()) throw CLI::ValidationError(why);
        });
    const Command commands[] = {add_tree(app),  add_family(app),  add_render(app), add_animate(app),
                                add_bench(app), add_presets(app), add_studio(app), add_camera(app)};
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
    // From here on outputs are written; an interrupted run removes its temporaries.
    install_partial_cleanup();

    if (fast_rays) set_ray_device_config("");
    std::unique_ptr<tbb::global_control> limit;
    if (threads > 0)
        limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                      static_cast<size_t>(threads));
    try {
        for (const Command& c : commands)
            if (*c.app) return c.run();
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
