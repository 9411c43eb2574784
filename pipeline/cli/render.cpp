// The render command: scene file in, painted image out, with the frame's plan on request.
#include <chrono>
#include <cstdio>
#include <filesystem>

#include "pipeline/cli/commands.h"
#include "pipeline/error.h"
#include "pipeline/image_io.h"
#include "pipeline/paint.h"
#include "pipeline/presets.h"

namespace pleinair {

namespace fs = std::filesystem;

int run_render(const RenderCommand& cmd) {
    using Clock = std::chrono::steady_clock;
    if (!is_image_path(cmd.out))
        throw InputError(
            "-o", "",
            "expected an image path ending in .png, .tif, .tiff or .exr, got \"" + cmd.out + "\"");
    if (cmd.aovs && fs::path(cmd.out).extension() != ".exr")
        throw InputError("--aovs", "", "AOV channels need an .exr output, got \"" + cmd.out + "\"");
    auto t_all = Clock::now();
    fs::path file = resolve_preset("scenes", cmd.scene, "SCENE");
    SceneDesc scene = load_scene(file, cmd.set);

    PaintOptions options;
    options.aovs = cmd.aovs;
    FramePlan plan = plan_frame(scene, options);
    FrameReport report;
    auto t0 = Clock::now();
    std::vector<BuiltTree> trees = build_trees(scene, plan.bark);
    BuiltLandscape land = build_landscape(scene);
    double gen_ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    size_t leaves = 0, bark = 0;
    for (const auto& t : trees) leaves += t.tree.leaves.size(), bark += t.bark.size();
    Frame frame = paint_frame(scene, trees, land, plan, &report);

    t0 = Clock::now();
    if (fs::path parent = fs::path(cmd.out).parent_path(); !parent.empty())
        fs::create_directories(parent);
    write_frame(cmd.out, frame);
    double out_ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    double total_ms = std::chrono::duration<double, std::milli>(Clock::now() - t_all).count();

    if (cmd.explain) {
        std::printf("plan for %s (%dx%d, %zu trees):\n", file.string().c_str(), frame.width,
                    frame.height, scene.trees.size());
        auto line = [](const std::string& name, bool ran, const std::string& why, double ms,
                       const std::string& counts) {
            if (ran)
                std::printf("  %-18s %9.1f ms  %s%s%s\n", name.c_str(), ms, why.c_str(),
                            counts.empty() ? "" : "; ", counts.c_str());
            else
                std::printf("  %-18s   skipped     %s\n", name.c_str(), why.c_str());
        };
        line("generate", true, "trees grown from their presets, surfaces turned into strokes",
             gen_ms,
             std::to_string(trees.size()) + " trees, " + std::to_string(leaves) + " leaves, " +
                 std::to_string(bark) + " bark strokes, " + std::to_string(land.stroke_count()) +
                 " surface strokes");
        // Decisions about effects folded into other passes (tint, atmosphere, sub-stroke colour
        // are part of every stroke's paint; shadows and underpainting have passes below): no
        // time of their own.
        for (const auto& d : plan.decisions) {
            if (d.ran)
                std::printf("  %-18s   on          %s\n", d.name.c_str(), d.why.c_str());
            else
                line(d.name, false, d.why, 0, "");
        }
        for (const auto& p : report.passes) line(p.name, p.ran, p.why, p.ms, p.counts);
        line("output", true, "written through OpenImageIO, renamed when complete", out_ms, cmd.out);
        std::printf(
            "  %-18s %9.1f ms  %llu leaf + %llu bark + %llu surface sprites, %llu fragments\n",
            "total", total_ms, static_cast<unsigned long long>(report.leaf_sprites),
            static_cast<unsigned long long>(report.bark_sprites),
            static_cast<unsigned long long>(report.surface_sprites),
            static_cast<unsigned long long>(report.fragments));
    } else {
        std::printf("painted %s (%dx%d) in %.2f s\n", cmd.out.c_str(), frame.width, frame.height,
                    total_ms / 1000.0);
    }
    return 0;
}

}  // namespace pleinair
