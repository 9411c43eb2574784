// The render command: scene file in, painted image out, with the shot's and the frame's plan
// on request.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <mutex>

#include "pipeline/cli/commands.h"
#include "pipeline/frame/paint_frame.h"
#include "pipeline/input/draft.h"
#include "pipeline/input/error.h"
#include "pipeline/input/limits.h"
#include "pipeline/input/presets.h"
#include "pipeline/output/gltf_scene.h"
#include "pipeline/output/height_map_writer.h"
#include "pipeline/output/image_io.h"
#include "pipeline/output/write_file.h"

namespace pleinair {

namespace fs = std::filesystem;

namespace {

void print_pass(const PassReport& p) {
    if (p.ran)
        std::printf("    %-18s %9.1f ms  %s%s%s\n", p.name.c_str(), p.ms, p.why.c_str(),
                    p.counts.empty() ? "" : "; ", p.counts.c_str());
    else
        std::printf("    %-18s   skipped     %s\n", p.name.c_str(), p.why.c_str());
}

std::string format_seconds(double t) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", t);
    return buf;
}

}  // namespace

double frame_time_of(std::optional<double> time, std::optional<int> frame, const SceneDesc& scene,
                     const std::string& file) {
    if (time && frame) throw InputError("--time", "", "give --time or --frame, not both");
    if ((time || frame) && !scene.animated())
        throw InputError(
            file, "/camera/track",
            "--time and --frame need a camera, sun or wind track; the scene is a still");
    const FrameRange frames = animation_frames(scene);
    if (frame) {
        if (*frame < frames.first || *frame > frames.last)
            throw InputError("--frame", "",
                             "frame " + std::to_string(*frame) +
                                 " lies outside the track, which has frames " +
                                 std::to_string(frames.first) + "-" + std::to_string(frames.last));
        return frame_time(*frame, scene.fps);
    }
    if (time) {
        const TimeSpan span = animation_span(scene);
        if (!(*time >= span.first && *time <= span.last))
            throw InputError("--time", "",
                             "must lie within the track, [" + format_seconds(span.first) + ", " +
                                 format_seconds(span.last) + "] s, got " + format_seconds(*time));
        return *time;
    }
    return frame_time(frames.first, scene.fps);
}

void print_explain(const Shot& shot, const FrameReport& report, const std::string& what,
                   double shot_ms) {
    std::printf("shot %s (%zu trees), built once in %.1f ms:\n", what.c_str(),
                shot.scene.trees.size(), shot_ms);
    for (const auto& p : shot.passes) print_pass(p);
    std::printf("  frame plan:\n");
    // Decisions about effects folded into other passes (tint, atmosphere, sub-stroke colour
    // are part of every stroke's paint; shadows and underpainting have passes below): no time
    // of their own.
    for (const auto& d : report.decisions) {
        if (d.ran)
            std::printf("    %-18s   on          %s\n", d.name.c_str(), d.why.c_str());
        else
            print_pass(d);
    }
    std::printf("  frame passes:\n");
    for (const auto& p : report.passes) print_pass(p);
}

void check_job_memory(const SceneDesc& scene, bool aovs, const std::string& out, int frames_at_once,
                      const std::string& file) {
    const Camera& cam = scene.camera;
    const double output = output_bytes_per_pixel(out, aovs);
    const uint64_t bytes =
        frame_buffer_bytes(cam.width, cam.height, aovs, scene.render.underpaint_scale, output) *
        static_cast<uint64_t>(frames_at_once);
    const uint64_t mb = (bytes + (1u << 20) - 1) >> 20;
    if (mb <= limits().memory_mb) return;
    char line[256];
    std::snprintf(
        line, sizeof line,
        "a %dx%d frame%s needs about %llu MB for its image buffers (%.0f bytes a pixel%s), "
        "over the limit of %llu MB; ",
        cam.width, cam.height, aovs ? " with AOVs" : "", static_cast<unsigned long long>(mb),
        static_cast<double>(bytes) / frames_at_once / cam.width / cam.height,
        frames_at_once > 1 ? ", two frames at once" : "",
        static_cast<unsigned long long>(limits().memory_mb));
    throw InputError(file, "/camera/width", line + how_to_raise("memory_mb"));
}

namespace {

// --export-height-map: the terrain's grid as a height map, its range printed for whoever reads
// it back (/terrain/height_map/low and high).
void export_height_map(const SceneDesc& scene, const std::string& source, const fs::path& path) {
    if (!scene.terrain.present)
        throw InputError(source, "/terrain", "--export-height-map needs a terrain to write");
    const GridSurface grid = generate_terrain(scene.terrain.params, scene.terrain.seed);
    double lo = 1e300, hi = -1e300;
    for (const glm::vec3& p : grid.positions)
        lo = std::min<double>(lo, p.y), hi = std::max<double>(hi, p.y);
    const bool exr = lower_ext(path) == ".exr";
    if (fs::path parent = path.parent_path(); !parent.empty()) fs::create_directories(parent);
    write_height_map(path, grid, lo, hi);
    std::printf(
        "wrote %s (%dx%d): /terrain/height_map {\"file\": \"%s\", \"low\": %.9g, "
        "\"high\": %.9g} over min [%.9g, %.9g], max [%.9g, %.9g], resolution %d\n",
        path.string().c_str(), grid.nu, grid.nv, path.filename().string().c_str(), exr ? 0.0 : lo,
        exr ? 1.0 : hi, scene.terrain.params.min.x, scene.terrain.params.min.y,
        scene.terrain.params.max.x, scene.terrain.params.max.y, grid.nu);
}

// --export: the scene as glTF, written whole or not at all.
void export_scene(const SceneDesc& scene, const RenderCommand& cmd) {
    SceneExport options;
    if (!parse_instancing(cmd.export_instancing, options.instancing))
        throw InputError("--export-instancing", "", "expected gpu or nodes");
    options.low_detail = cmd.export_low_detail;
    const BuiltLandscape land = build_landscape(scene);
    const std::vector<BuiltTree> trees = build_trees(scene, false);
    const std::string bytes = scene_glb(scene, land, trees, options);
    const fs::path path(cmd.export_glb);
    if (fs::path parent = path.parent_path(); !parent.empty()) fs::create_directories(parent);
    write_file_atomic(path, bytes);
    std::printf("wrote %s (%.1f MB): %zu trees, %zu surfaces\n", path.string().c_str(),
                double(bytes.size()) / 1e6, trees.size(),
                land.rocks.size() + (land.has_terrain ? 1 : 0) + (land.has_water ? 1 : 0));
}

}  // namespace

int run_render(const RenderCommand& cmd) {
    if (!cmd.export_glb.empty() && fs::path(cmd.export_glb).extension() != ".glb")
        throw InputError("--export", "",
                         "expected a path ending in .glb, got \"" + cmd.export_glb + "\"");
    if (cmd.out.empty() && cmd.export_height_map.empty() && cmd.export_glb.empty())
        throw InputError("-o", "", "give an image to paint (-o IMAGE) or an --export option");
    if (!cmd.export_height_map.empty() && !is_image_path(cmd.export_height_map))
        throw InputError("--export-height-map", "",
                         "expected a path ending in .png, .tif, .tiff or .exr, got \"" +
                             cmd.export_height_map + "\"");
    if (cmd.out.empty()) {
        fs::path file = resolve_preset("scenes", cmd.scene, "SCENE");
        const SceneDesc scene = load_scene(file, cmd.set);
        if (!cmd.export_height_map.empty())
            export_height_map(scene, file.string(), cmd.export_height_map);
        if (!cmd.export_glb.empty()) export_scene(scene, cmd);
        return 0;
    }
    if (!is_image_path(cmd.out))
        throw InputError(
            "-o", "",
            "expected an image path ending in .png, .tif, .tiff or .exr, got \"" + cmd.out + "\"");
    if (cmd.aovs && fs::path(cmd.out).extension() != ".exr")
        throw InputError("--aovs", "", "AOV channels need an .exr output, got \"" + cmd.out + "\"");
    PassTimer total;
    fs::path file = resolve_preset("scenes", cmd.scene, "SCENE");
    SceneDesc scene = load_scene(file, cmd.set);
    if (!cmd.export_height_map.empty())
        export_height_map(scene, file.string(), cmd.export_height_map);
    if (!cmd.export_glb.empty()) export_scene(scene, cmd);
    if (cmd.preview) halve_for_preview(scene, file.string());
    if (cmd.draft) apply_draft(scene.render, cmd.set);
    check_job_memory(scene, cmd.aovs, cmd.out, 1, file.string());
    const double t = frame_time_of(cmd.time, cmd.frame, scene, file.string());
    FrameView view;
    try {
        view = view_at(scene, t);
    } catch (const std::runtime_error& e) {
        throw InputError(file.string(), "/camera/track", e.what());
    }
    // A still traces the sun's light for the particles it shows, not for every particle.
    const Shot shot = build_shot(std::move(scene), ShotOptions{});
    const double shot_ms = total.ms();

    FrameReport report;
    PassTimer frame_timer;
    FrameSettings settings = scene_frame_settings(shot.scene, cmd.aovs);
    // Large frames (past 16 megapixels) say how far they have come, unasked.
    const bool report_progress =
        cmd.progress || static_cast<double>(view.camera.width) * view.camera.height > (1 << 24);
    std::mutex progress_mutex;
    if (report_progress) {
        std::fprintf(stderr, "pleinair: %s, %dx%d: shot built in %.1f s\n", file.string().c_str(),
                     view.camera.width, view.camera.height, shot_ms / 1000);
        settings.progress = [&](const char* stage, double done) {
            const std::lock_guard<std::mutex> lock(progress_mutex);
            // Stage starts, and the paint at every tenth.
            const int pct = static_cast<int>(std::floor(done * 100 + 1e-9));
            if (done == 0)
                std::fprintf(stderr, "pleinair: %s (%.1f s)\n", stage, frame_timer.ms() / 1000);
            else if (pct % 10 == 0)
                std::fprintf(stderr, "pleinair: %s %d%% (%.1f s)\n", stage, pct,
                             frame_timer.ms() / 1000);
        };
    }
    const Frame frame = paint_frame(shot, view, settings, &report);
    if (report_progress) std::fprintf(stderr, "pleinair: writing %s\n", cmd.out.c_str());
    const double frame_ms = frame_timer.ms();

    PassTimer out_timer;
    if (fs::path parent = fs::path(cmd.out).parent_path(); !parent.empty())
        fs::create_directories(parent);
    write_frame(cmd.out, frame);
    const double out_ms = out_timer.ms();

    if (cmd.explain) {
        print_explain(shot, report, file.string(), shot_ms);
        print_pass({"output", true, "written through OpenImageIO, renamed when complete", out_ms,
                    cmd.out});
        std::printf(
            "  %-20s %9.1f ms  frame %.1f ms; %llu leaf + %llu bark + %llu surface "
            "sprites, %llu fragments\n",
            "total", total.ms(), frame_ms, static_cast<unsigned long long>(report.leaf_sprites),
            static_cast<unsigned long long>(report.bark_sprites),
            static_cast<unsigned long long>(report.surface_sprites),
            static_cast<unsigned long long>(report.fragments));
    } else {
        std::printf("painted %s (%dx%d) in %.2f s\n", cmd.out.c_str(), frame.width, frame.height,
                    total.ms() / 1000.0);
    }
    return 0;
}

}  // namespace pleinair
