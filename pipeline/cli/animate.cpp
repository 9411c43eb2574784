// The animate command: one shot built once, then a range of frames, each written whole under
// its final name (so --resume trusts what exists), with the progress lines render farms parse,
// and an optional video encoded by ffmpeg.
#include <spawn.h>
#include <sys/wait.h>
#include <tbb/global_control.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <future>
#include <memory>
#include <stdexcept>

#include "pipeline/cli/commands.h"
#include "pipeline/frame/buffer_pool.h"
#include "pipeline/frame/mirror_memo.h"
#include "pipeline/frame/paint_frame.h"
#include "pipeline/frame/seen_memo.h"
#include "pipeline/input/draft.h"
#include "pipeline/input/error.h"
#include "pipeline/input/frame_range.h"
#include "pipeline/input/presets.h"
#include "pipeline/output/image_io.h"
#include "pipeline/output/partial_files.h"

extern char** environ;

namespace pleinair {

namespace fs = std::filesystem;

void print_explain(const Shot& shot, const FrameReport& report, const std::string& what,
                   double shot_ms);

namespace {

// Frames done, frames per second and time left: a bar redrawn in place on a terminal; in a log,
// one "Progress: N%" line per frame and one "Saved: PATH" line per file (OpenCue, Deadline and
// Flamenco parse these).
class ProgressReport {
  public:
    ProgressReport(size_t total, bool bar) : total_(total), bar_(bar) {}

    void frame_done(const std::string& path, bool painted, double ms) {
        ++done_;
        if (painted) ++painted_, painted_ms_ += ms;
        const int percent = static_cast<int>(100 * done_ / std::max<size_t>(total_, 1));
        if (!bar_) {
            if (painted) std::printf("Saved: %s\n", path.c_str());
            std::printf("Progress: %d%%\n", percent);
            std::fflush(stdout);
            return;
        }
        const double fps = painted_ms_ > 0 ? 1000.0 * painted_ / painted_ms_ : 0;
        const int left = fps > 0 ? static_cast<int>((total_ - done_) / fps + 0.5) : 0;
        constexpr size_t kWidth = 30;
        const size_t filled = kWidth * done_ / std::max<size_t>(total_, 1);
        std::printf("\r  [%s%s] %zu/%zu frames  %.2f frames/s  %d:%02d left ",
                    std::string(filled, '=').c_str(), std::string(kWidth - filled, ' ').c_str(),
                    done_, total_, fps, left / 60, left % 60);
        std::fflush(stdout);
    }
    void finish() {
        if (bar_) std::printf("\n");
    }

  private:
    size_t total_, done_ = 0, painted_ = 0;
    bool bar_;
    double painted_ms_ = 0;
};

// --explain after the frames: each pass's median time over the frames painted after the one
// explained. The first frame builds every occlusion map and traces the light of every particle
// it shows; the frames after it reuse most of both, so their cost is what a run pays a frame.
void print_later_passes(const std::vector<std::vector<PassReport>>& later) {
    if (later.empty()) return;
    std::printf("  frame passes, median over the %zu frames after the first:\n", later.size());
    auto median = [](std::vector<double> v) {
        std::sort(v.begin(), v.end());
        const size_t n = v.size();
        return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
    };
    std::vector<double> totals;
    for (const auto& frame : later) {
        double t = 0;
        for (const PassReport& p : frame) t += p.ms;
        totals.push_back(t);
    }
    for (size_t k = 0; k < later.front().size(); ++k) {
        std::vector<double> ms;
        for (const auto& frame : later)
            if (k < frame.size() && frame[k].name == later.front()[k].name)
                ms.push_back(frame[k].ms);
        if (ms.size() == later.size())
            std::printf("    %-18s %9.1f ms\n", later.front()[k].name.c_str(), median(ms));
    }
    std::printf("  %-20s %9.1f ms\n", "all passes", median(totals));
}

// The frames asked for, each within the track; bad input before any work.
}  // namespace

std::vector<int> frames_to_paint(const SceneDesc& scene, const std::string& text) {
    const FrameRange all = animation_frames(scene);
    if (all.last < all.first)
        throw InputError("--frames", "",
                         "the track holds no frame at " + std::to_string(scene.fps) + " fps");
    if (text.empty()) return all.frames();
    const FrameRange r = parse_frame_range(text);
    if (r.first < all.first || r.last > all.last)
        throw InputError("--frames", "",
                         "frames " + text + " lie outside the track, which has frames " +
                             std::to_string(all.first) + "-" + std::to_string(all.last));
    return r.frames();
}

void halve_for_preview(SceneDesc& scene, const std::string& file) {
    scene.camera_params.width = std::max(1, scene.camera_params.width / 2);
    scene.camera_params.height = std::max(1, scene.camera_params.height / 2);
    if (std::string why = make_camera(scene.camera_params, scene.camera); !why.empty())
        throw InputError(file, "/camera", why);
}

namespace {

// "%" doubled, for a literal part of an ffmpeg image pattern.
std::string escape_percent(const std::string& s) {
    std::string out;
    for (char c : s) out += c == '%' ? "%%" : std::string(1, c);
    return out;
}

// H.264 in yuv420p at the scene's fps through ffmpeg, into a temporary renamed when complete.
void encode_video(const std::string& video, const FramePattern& pattern, int first, size_t count,
                  double fps) {
    PartialOutput out{fs::path(video)};
    char rate[32], start[16], frames[32], width[8];
    std::snprintf(rate, sizeof rate, "%.17g", fps);
    std::snprintf(start, sizeof start, "%d", first);
    std::snprintf(frames, sizeof frames, "%zu", count);
    std::snprintf(width, sizeof width, "%02d", pattern.width);
    const std::string input =
        escape_percent(pattern.head) + "%" + width + "d" + escape_percent(pattern.tail);
    const std::string tmp = out.path().string();
    // yuv420p needs even sizes; bitexact keeps the encoder's version out of the file.
    std::vector<std::string> args = {"ffmpeg",
                                     "-nostdin",
                                     "-loglevel",
                                     "error",
                                     "-y",
                                     "-framerate",
                                     rate,
                                     "-start_number",
                                     start,
                                     "-i",
                                     input,
                                     "-frames:v",
                                     frames,
                                     "-vf",
                                     "pad=ceil(iw/2)*2:ceil(ih/2)*2",
                                     "-c:v",
                                     "libx264",
                                     "-pix_fmt",
                                     "yuv420p",
                                     "-r",
                                     rate,
                                     "-fflags",
                                     "+bitexact",
                                     "-flags:v",
                                     "+bitexact",
                                     "-map_metadata",
                                     "-1",
                                     "-f",
                                     "mp4",
                                     tmp};
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    pid_t pid;
    if (int e = posix_spawnp(&pid, "ffmpeg", nullptr, nullptr, argv.data(), environ); e != 0)
        throw std::runtime_error("cannot run ffmpeg for " + video + ": " + std::strerror(e) +
                                 " (install the Debian package ffmpeg; make does)");
    int status = 0;
    pid_t waited;
    while ((waited = waitpid(pid, &status, 0)) < 0 && errno == EINTR) {
    }
    if (waited != pid || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
        throw std::runtime_error("ffmpeg failed to encode " + video);
    out.commit();
}

}  // namespace

// A track whose camera degenerates between its keys (its look-at passing through its position)
// is bad input, found before any frame is painted.

void check_views(const SceneDesc& scene, const std::vector<int>& frames, const std::string& file) {
    for (int f : frames) try {
            view_at(scene, frame_time(f, scene.fps));
        } catch (const std::runtime_error& e) {
            throw InputError(file, "/camera/track", "frame " + std::to_string(f) + ": " + e.what());
        }
}

namespace {

void check_outputs(const AnimateCommand& cmd, const FramePattern& pattern) {
    const std::string first = pattern.path(1);
    if (!is_image_path(first))
        throw InputError(
            "-o", "",
            "expected frame images ending in .png, .tif, .tiff or .exr, got \"" + cmd.out + "\"");
    const std::string ext = fs::path(first).extension().string();
    if (cmd.aovs && ext != ".exr")
        throw InputError("--aovs", "", "AOV channels need .exr frames, got \"" + cmd.out + "\"");
    if (!cmd.video.empty()) {
        if (fs::path(cmd.video).extension() != ".mp4")
            throw InputError("--video", "",
                             "expected a file ending in .mp4, got \"" + cmd.video + "\"");
        if (ext == ".exr")
            throw InputError(
                "--video", "",
                "needs PNG or TIFF frames (EXR frames are linear), got \"" + cmd.out + "\"");
    }
}

// Paints the frames of `todo` (those of `frames` not on disk), each written while the next is
// painted (the write's PNG compression is serial); returns each frame's time from the previous
// frame done to its own.
std::vector<std::pair<double, int>> paint_frames(const Shot& shot, const std::vector<int>& frames,
                                                 const std::vector<int>& todo,
                                                 const FramePattern& pattern,
                                                 const AnimateCommand& cmd,
                                                 ProgressReport& progress, const std::string& what,
                                                 double shot_ms) {
    std::vector<std::pair<double, int>> times;  // ms between frames completed, frame
    struct PendingWrite {
        std::future<double> done;  // when the file was complete, on `clock`
        int frame = 0;
        std::string path;
    };
    // The memory of the frames' image and stroke layers, kept from one to the next
    // (buffer_pool.h); declared before the pending write, which hands its frame's image back
    // once on disk, so it outlives it.
    BufferPool buffers;
    std::unique_ptr<PendingWrite> pending;
    std::vector<std::vector<PassReport>> later;  // --explain: the passes of frames after the first
    // Frames painted in order share most of their occlusion maps (seen_memo.h).
    SeenMemo memo;
    // And their water strokes' mirrors (mirror_memo.h).
    MirrorMemo mirrors;
    const PassTimer clock;
    double last_done = 0;
    auto in_frame = [](int f, auto&& fn) {
        try {
            fn();
        } catch (const InputError&) {
            throw;
        } catch (const std::exception& e) {
            throw std::runtime_error("frame " + std::to_string(f) + ": " + e.what());
        }
    };
    auto settle = [&] {
        if (!pending) return;
        double done = 0;
        in_frame(pending->frame, [&] { done = pending->done.get(); });
        times.push_back({done - last_done, pending->frame});
        last_done = done;
        progress.frame_done(pending->path, true, times.back().first);
        pending.reset();
    };
    for (int f : frames) {
        const std::string path = pattern.path(f);
        if (!std::binary_search(todo.begin(), todo.end(), f)) {
            progress.frame_done(path, false, 0);
            continue;
        }
        FrameSettings settings = scene_frame_settings(shot.scene, cmd.aovs);
        settings.seen_memo = &memo;
        settings.mirror_memo = &mirrors;
        settings.buffers = &buffers;
        if (!pending) last_done = clock.ms();
        FrameReport report;
        auto frame = std::make_shared<Frame>();
        in_frame(f, [&] {
            *frame = paint_frame(shot, view_at(shot.scene, frame_time(f, shot.scene.fps)), settings,
                                 &report);
        });
        if (cmd.explain && times.empty() && !pending)
            print_explain(shot, report, what, shot_ms);
        else if (cmd.explain)
            later.push_back(report.passes);
        settle();
        auto write = [path, frame, clock, pool = &buffers] {
            write_frame(path, *frame);
            pool->give(std::move(frame->rgba));
            return clock.ms();
        };
        // With one thread asked for, the write runs in turn (deferred to its settle).
        const bool overlap =
            tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism) > 1;
        pending.reset(new PendingWrite{
            std::async(overlap ? std::launch::async : std::launch::deferred, write), f, path});
    }
    settle();
    print_later_passes(later);
    return times;
}

}  // namespace

int run_animate(const AnimateCommand& cmd) {
    const FramePattern pattern = parse_frame_pattern(cmd.out);
    check_outputs(cmd, pattern);
    PassTimer total;
    const fs::path file = resolve_preset("scenes", cmd.scene, "SCENE");
    SceneDesc scene = load_scene(file, cmd.set);
    if (!scene.animated())
        throw InputError(file.string(), "/camera/track",
                         "the scene has no camera, sun or wind track: paint it with "
                         "`pleinair render`");
    const std::vector<int> frames = frames_to_paint(scene, cmd.frames);
    check_views(scene, frames, file.string());
    if (!cmd.video.empty() && frames.size() > 1 && frames[1] - frames[0] != 1)
        throw InputError("--video", "", "a video needs every frame of its range (no xSTEP)");
    if (cmd.preview) halve_for_preview(scene, file.string());
    if (cmd.draft) apply_draft(scene.render, cmd.set);
    // One frame painted while the one before is written.
    check_job_memory(scene, cmd.aovs, pattern.path(1), 2, file.string());
    const fs::path dir = fs::path(pattern.path(0)).parent_path();
    if (!dir.empty()) fs::create_directories(dir);
    if (cmd.resume) clear_partials(dir.empty() ? fs::path(".") : dir);

    // A frame on disk is complete (written whole, then renamed); one of another size (a
    // --preview run's) is not this run's.
    std::vector<int> todo;
    for (int f : frames)
        if (!cmd.resume ||
            !image_has_size(pattern.path(f), scene.camera_params.width, scene.camera_params.height))
            todo.push_back(f);
    const double fps = scene.fps;
    // Every frame of an animation takes the still sun's light from the shot, so a chunk and a
    // whole run share one way of computing it. Nothing to paint (a resumed shot that is
    // complete, an encode job): no shot.
    ShotOptions options;
    options.cache_sun_light = true;
    const std::unique_ptr<const Shot> shot =
        todo.empty() ? nullptr
                     : std::make_unique<const Shot>(build_shot(std::move(scene), options));
    const double shot_ms = total.ms();
    const bool bar = cmd.progress == AnimateCommand::Progress::kBar ||
                     (cmd.progress == AnimateCommand::Progress::kAuto && isatty(STDOUT_FILENO));
    ProgressReport progress(frames.size(), bar);
    std::vector<std::pair<double, int>> times;
    if (shot)
        times = paint_frames(*shot, frames, todo, pattern, cmd, progress, file.string(), shot_ms);
    else
        for (int f : frames) progress.frame_done(pattern.path(f), false, 0);
    progress.finish();
    if (!cmd.video.empty()) {
        encode_video(cmd.video, pattern, frames.front(), frames.size(), fps);
        if (!bar) std::printf("Saved: %s\n", cmd.video.c_str());
    }
    if (!times.empty()) {
        std::vector<std::pair<double, int>> sorted = times;
        std::sort(sorted.begin(), sorted.end());
        std::printf(
            "shot built in %.0f ms; %zu frames painted: median %.0f ms, worst %.0f ms "
            "(frame %d) from one frame done to the next; %.2f s in all\n",
            shot_ms, times.size(), sorted[sorted.size() / 2].first, sorted.back().first,
            sorted.back().second, total.ms() / 1000.0);
    } else {
        std::printf("every frame was already complete\n");
    }
    return 0;
}

}  // namespace pleinair
