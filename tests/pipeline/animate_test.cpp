// pleinair animate as a farm drives it: chunks, single frames and a whole run give the same
// bytes; a still camera gives identical frames; bad ranges and tracks write nothing; a run
// killed with SIGKILL resumes to the bytes of an uninterrupted one; the video has every frame.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include "pipeline/output/partial_files.h"
#include "test_util.h"

namespace pleinair {
namespace {

namespace fs = std::filesystem;
using test::read_file;
using test::run_pleinair;

// A small landscape under a shadow-casting sun, the camera walking past two trees.
std::string walk_scene(const std::string& track, int width = 96, int height = 64,
                       const std::string& camera = "", const std::string& extra = "") {
    return R"({"fps": 12, )" + extra + R"(
        "camera": {)" +
           camera + R"("width": )" + std::to_string(width) + R"(, "height": )" +
           std::to_string(height) + R"(, "fov": 50, "track": )" + track + R"(},
        "sun": {"direction": [-0.5, 0.6, 0.4], "casts_shadows": true},
        "atmosphere": {"near": 10, "far": 150},
        "materials": {"grass": {"shader": "grass"}},
        "terrain": {"seed": 2, "min": [-40, -60], "max": [40, 40], "resolution": 17,
                    "material": "grass",
                    "strokes": {"particle_spans_u": 16, "particle_spans_v": 16}},
        "families": {"birch": {"preset": "birch"}, "shrub": {"preset": "shrub"}},
        "trees": [{"family": "birch", "seed": 3, "position": [6, 0, 8]},
                  {"family": "shrub", "seed": 4, "position": [-3, 0, 14]}]})";
}

const char* kWalk = R"([{"time": 0, "position": [-6, 2.5, 34], "look_at": [2, 5, 0]},
                         {"time": 0.5, "position": [0, 2.5, 30], "look_at": [4, 5, 0]}])";

class Animate : public ::testing::Test {
  protected:
    void SetUp() override { dir_ = test::temp_dir("animate"); }
    void TearDown() override { fs::remove_all(dir_); }
    fs::path scene(const std::string& text, const std::string& name = "walk.json") {
        std::ofstream(dir_ / name) << text;
        return dir_ / name;
    }
    // Runs animate on `scene` into dir_/NAME/f_##.png with the extra arguments.
    test::RunResult animate(const fs::path& scene, const std::string& name,
                            const std::string& args) {
        return run_pleinair("animate " + scene.string() + " -o " + (dir_ / name).string() +
                            "/f_##.png --progress log " + args);
    }
    void chunks_single_frames_and_a_whole_run(const std::string& text);
    std::string frame(const std::string& name, int f) {
        char buf[16];
        std::snprintf(buf, sizeof buf, "/f_%02d.png", f);
        return read_file(dir_.string() + "/" + name + buf);
    }
    fs::path dir_;
};

// Distance circles near enough that the walk's trees fade, and a near field.
const char* kCircles =
    R"("leaf_near": 8, "leaf_far": 30, "trunk_near": 8, "trunk_far": 30, "near_field": 12, )";

// A gusty wind: the trees' poses are functions of time alone (generators/wind.h).
const char* kWind =
    R"("wind": {"strength": 9, "direction": [1, 0, 0.3], "gustiness": 0.8, "gust_period": 0.3}, )";

TEST_F(Animate, ChunksSingleFramesAndAWholeRunGiveTheSameBytes) {
    for (const char* extra : {"", kWind}) {
        SCOPED_TRACE(extra);
        chunks_single_frames_and_a_whole_run(walk_scene(kWalk, 96, 64, kCircles, extra));
    }
}

void Animate::chunks_single_frames_and_a_whole_run(const std::string& text) {
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    // With the level of detail on: nothing of it may depend on the frames painted before.
    const fs::path s = scene(text);
    auto whole = animate(s, "whole", "--threads 2");
    ASSERT_EQ(whole.exit_code, 0) << whole.err;
    ASSERT_EQ(animate(s, "chunks", "--frames 1-3 --threads 1").exit_code, 0);
    ASSERT_EQ(animate(s, "chunks", "--frames 4-7").exit_code, 0);
    ASSERT_EQ(animate(s, "alone", "--frames 5").exit_code, 0);
    // Frames 1..7 at 12 fps cover the half second of the track.
    EXPECT_FALSE(fs::exists(dir_ / "whole" / "f_08.png"));
    for (int f = 1; f <= 7; ++f) {
        SCOPED_TRACE(f);
        const std::string w = frame("whole", f);
        ASSERT_FALSE(w.empty());
        EXPECT_EQ(w, frame("chunks", f));
        if (f > 1) {
            EXPECT_NE(w, frame("whole", f - 1)) << "the camera moves";
        }
    }
    EXPECT_EQ(frame("whole", 5), frame("alone", 5));
    EXPECT_FALSE(fs::exists(dir_ / "alone" / "f_04.png"));
    // A still of the same frame (its light traced per particle, not cached by the shot).
    auto still =
        run_pleinair("render " + s.string() + " --frame 5 -o " + (dir_ / "still.png").string());
    ASSERT_EQ(still.exit_code, 0) << still.err;
    EXPECT_EQ(read_file(dir_ / "still.png"), frame("whole", 5));
    // Frame 5 is at 4/12 s.
    ASSERT_EQ(run_pleinair("render " + s.string() + " --time 0.3333333333333333 -o " +
                           (dir_ / "timed.png").string())
                  .exit_code,
              0);
    EXPECT_EQ(read_file(dir_ / "timed.png"), frame("whole", 5));
}

// --draft: lighter settings, the same frame from either command, and the user's own --set kept
// over the draft's (all five given back their defaults paint the full frame).
TEST_F(Animate, DraftFramesAreTheRenderDraftFramesAndYieldToTheUsersSets) {
    const fs::path s = scene(walk_scene(kWalk, 96, 64, kCircles));
    ASSERT_EQ(animate(s, "full", "--frames 2-3").exit_code, 0);
    auto draft = animate(s, "draft", "--frames 2-3 --draft");
    ASSERT_EQ(draft.exit_code, 0) << draft.err;
    EXPECT_NE(frame("draft", 3), frame("full", 3));
    auto still = run_pleinair("render " + s.string() + " --draft --frame 3 -o " +
                              (dir_ / "still.png").string());
    ASSERT_EQ(still.exit_code, 0) << still.err;
    EXPECT_EQ(read_file(dir_ / "still.png"), frame("draft", 3));
    const std::string defaults =
        " --set /render/samples=4 --set /render/thin_below_px=3 --set /render/thin_max_growth=2"
        " --set /render/coverage_cutoff=0.00048828125 --set /render/reflection_frames=4";
    ASSERT_EQ(animate(s, "undone", "--frames 2-3 --draft" + defaults).exit_code, 0);
    EXPECT_EQ(frame("undone", 3), frame("full", 3));
    // Only the coherence bench reads --draft among the bench kinds.
    auto bench = run_pleinair("bench look " + s.string() + " --draft");
    EXPECT_EQ(bench.exit_code, 2);
    EXPECT_NE(bench.err.find("--draft"), std::string::npos) << bench.err;
}

TEST_F(Animate, AStillCameraGivesIdenticalFrames) {
    const fs::path s =
        scene(walk_scene(R"([{"time": 0, "position": [0, 2.5, 30], "look_at": [4, 5, 0]},
                                           {"time": 0.25, "position": [0, 2.5, 30], "look_at": [4, 5, 0]}])"));
    ASSERT_EQ(animate(s, "still", "").exit_code, 0);
    for (int f = 2; f <= 4; ++f) EXPECT_EQ(frame("still", f), frame("still", 1)) << f;
}

// --explain: the first frame's plan and passes once, and after the frames each pass's median
// over the frames after the first (which reuse its occlusion answers and light).
TEST_F(Animate, ExplainAddsEachPassMedianOverTheLaterFrames) {
    const fs::path s = scene(walk_scene(kWalk));
    auto count = [](const std::string& text, const std::string& what) {
        size_t n = 0;
        for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1))
            ++n;
        return n;
    };
    auto four = animate(s, "four", "--frames 1-4 --explain");
    ASSERT_EQ(four.exit_code, 0) << four.err;
    EXPECT_EQ(count(four.out, "frame plan:"), 1u) << four.out;
    const size_t median = four.out.find("frame passes, median over the 3 frames after the first:");
    ASSERT_NE(median, std::string::npos) << four.out;
    EXPECT_NE(four.out.find("    sprites ", median), std::string::npos) << four.out;
    EXPECT_NE(four.out.find("  all passes ", median), std::string::npos) << four.out;
    auto one = animate(s, "one", "--frames 1-1 --explain");
    ASSERT_EQ(one.exit_code, 0) << one.err;
    EXPECT_EQ(count(one.out, "frame plan:"), 1u);
    EXPECT_EQ(one.out.find("median over"), std::string::npos) << one.out;
}

TEST_F(Animate, ProgressAndSavedLinesForFarms) {
    const fs::path s = scene(walk_scene(kWalk));
    auto r = animate(s, "log", "--frames 2-6x2");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    size_t saved = 0, progress = 0, pos = 0;
    while ((pos = r.out.find("Saved: ", pos)) != std::string::npos) ++saved, ++pos;
    pos = 0;
    while ((pos = r.out.find("Progress: ", pos)) != std::string::npos) ++progress, ++pos;
    EXPECT_EQ(saved, 3u);
    EXPECT_EQ(progress, 3u);
    EXPECT_NE(r.out.find("Progress: 33%\n"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("Progress: 100%\n"), std::string::npos);
    EXPECT_NE(r.out.find("Saved: " + (dir_ / "log" / "f_04.png").string() + "\n"),
              std::string::npos);
    EXPECT_FALSE(fs::exists(dir_ / "log" / "f_03.png"));
    // On a terminal: a bar with frames done and frames per second, no farm lines.
    auto bar = run_pleinair("animate " + s.string() + " -o " + (dir_ / "bar").string() +
                            "/f_##.png --frames 1-2 --progress bar");
    ASSERT_EQ(bar.exit_code, 0) << bar.err;
    EXPECT_NE(bar.out.find("2/2 frames"), std::string::npos) << bar.out;
    EXPECT_NE(bar.out.find("frames/s"), std::string::npos) << bar.out;
    EXPECT_EQ(bar.out.find("Progress: "), std::string::npos);
    EXPECT_EQ(bar.out.find("Saved: "), std::string::npos);
}

TEST_F(Animate, BadRangesAndTracksExitTwoAndWriteNothing) {
    const fs::path s = scene(walk_scene(kWalk));
    const fs::path still = scene(R"({"families": {"oak": {"preset": "oak"}},
        "trees": [{"family": "oak", "seed": 1}]})",
                                 "still.json");
    const fs::path one_key = scene(
        walk_scene(R"([{"time": 0, "position": [0, 2, 30], "look_at": [0, 3, 0]}])"), "one.json");
    const fs::path reversed = scene(walk_scene(R"([
        {"time": 1, "position": [0, 2, 30], "look_at": [0, 3, 0]},
        {"time": 0, "position": [0, 2, 20], "look_at": [0, 3, 0]}])"),
                                    "reversed.json");
    const fs::path eye_on_target = scene(walk_scene(R"([
        {"time": 0, "position": [0, 2, 30], "look_at": [0, 2, 30]},
        {"time": 1, "position": [0, 2, 20], "look_at": [0, 3, 0]}])"),
                                         "eye.json");
    struct Case {
        fs::path scene;
        std::string args, expect;
    };
    const std::vector<Case> cases = {
        {s, "--frames 10-1", "--frames"},
        {s, "--frames x", "--frames"},
        {s, "--frames 1-99", "outside the track"},
        {s, "--frames 0-2", "outside the track"},
        {s, "--video out.mkv", "--video"},
        {s, "--aovs", "--aovs"},
        {still, "", "/camera/track"},
        {one_key, "", "/camera/track"},
        {reversed, "", "/camera/track/1/time"},
        {eye_on_target, "", "/camera/track/0"},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.args + " " + c.scene.string());
        auto r = animate(c.scene, "out", c.args);
        EXPECT_EQ(r.exit_code, 2) << r.err;
        EXPECT_NE(r.err.find(c.expect), std::string::npos) << r.err;
        EXPECT_FALSE(fs::exists(dir_ / "out"));
    }
    auto no_number = run_pleinair("animate " + s.string() + " -o " + (dir_ / "x.png").string());
    EXPECT_EQ(no_number.exit_code, 2);
    EXPECT_NE(no_number.err.find("frame number"), std::string::npos) << no_number.err;
    auto outside =
        run_pleinair("render " + s.string() + " --frame 9 -o " + (dir_ / "r.png").string());
    EXPECT_EQ(outside.exit_code, 2);
    EXPECT_FALSE(fs::exists(dir_ / "r.png"));
}

// SIGKILL mid-run: what is on disk is complete frames only, and --resume finishes the shot with
// the bytes of an uninterrupted run.
TEST_F(Animate, AKilledRunResumesToTheSameBytes) {
    const fs::path s = scene(walk_scene(kWalk, 320, 200));
    const std::string out = (dir_ / "killed" / "f_##.png").string();
    const int pid = test::spawn_pleinair({"animate", s.string(), "-o", out, "--threads", "1"});
    ASSERT_GT(pid, 0);
    auto complete = [&] {
        size_t n = 0;
        if (fs::exists(dir_ / "killed"))
            for (const auto& e : fs::directory_iterator(dir_ / "killed"))
                n += !is_partial_name(e.path().filename().string());
        return n;
    };
    const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (complete() < 2 && std::chrono::steady_clock::now() < give_up)
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    ::kill(pid, SIGKILL);
    int status = 0;
    ::waitpid(pid, &status, 0);
    ASSERT_TRUE(WIFSIGNALED(status)) << "the run finished before it was killed";
    const size_t before = complete();
    ASSERT_GE(before, 2u);
    ASSERT_LT(before, 7u);
    // A temporary a killed writer of this machine left (the kill may or may not have caught one
    // mid-write): its PID is past any Linux pid_max.
    const std::string host = partial_host(partial_path("x").filename().string());
    std::ofstream(dir_ / "killed" / (".f_07.png.partial-999999999@" + host)) << "half a frame";

    ASSERT_EQ(animate(s, "clean", "--threads 2").exit_code, 0);
    for (int f = 1; f <= 7; ++f) {
        char name[16];
        std::snprintf(name, sizeof name, "f_%02d.png", f);
        if (fs::exists(dir_ / "killed" / name)) {
            EXPECT_EQ(read_file(dir_ / "killed" / name), read_file(dir_ / "clean" / name)) << f;
        }
    }
    auto resumed =
        run_pleinair("animate " + s.string() + " -o " + out + " --resume --progress log");
    ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
    size_t saved = 0, pos = 0;
    while ((pos = resumed.out.find("Saved: ", pos)) != std::string::npos) ++saved, ++pos;
    EXPECT_EQ(saved, 7 - before) << "complete frames are kept, not painted again";
    for (const auto& e : fs::directory_iterator(dir_ / "killed"))
        EXPECT_FALSE(is_partial_name(e.path().filename().string())) << e.path();
    // Once complete, a resumed run paints nothing and builds no shot.
    auto again = run_pleinair("animate " + s.string() + " -o " + out + " --resume --progress log");
    ASSERT_EQ(again.exit_code, 0) << again.err;
    EXPECT_EQ(again.out.find("Saved: "), std::string::npos);
    EXPECT_NE(again.out.find("every frame was already complete"), std::string::npos);
    for (int f = 1; f <= 7; ++f) {
        char name[16];
        std::snprintf(name, sizeof name, "f_%02d.png", f);
        EXPECT_EQ(read_file(dir_ / "killed" / name), read_file(dir_ / "clean" / name)) << f;
    }
}

TEST_F(Animate, VideoHoldsEveryFrame) {
    const fs::path s = scene(walk_scene(kWalk));
    auto r = animate(s, "video", "--video " + (dir_ / "walk.mp4").string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("Saved: " + (dir_ / "walk.mp4").string()), std::string::npos);
    const std::string probe = dir_.string() + "/probe.txt";
    const std::string cmd =
        "ffprobe -v error -count_frames -select_streams v:0 -show_entries "
        "stream=nb_read_frames,width,height,pix_fmt -of csv=p=0 '" +
        (dir_ / "walk.mp4").string() + "' > '" + probe + "'";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << "ffprobe (Debian package ffmpeg) must be installed";
    EXPECT_EQ(read_file(probe), "96,64,yuv420p,7\n");
}

// A frame that cannot be written (its name is taken by a folder) fails the run with exit 1,
// naming the frame; the frames before it are whole and no temporary is left.
TEST_F(Animate, AFailedFrameIsNamedAndTheEarlierOnesStay) {
    const fs::path s = scene(walk_scene(kWalk));
    fs::create_directories(dir_ / "fail" / "f_03.png" / "inside");
    auto r = animate(s, "fail", "--frames 1-5");
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_NE(r.err.find("frame 3: "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("f_03.png"), std::string::npos) << r.err;
    ASSERT_EQ(animate(s, "good", "--frames 1-2").exit_code, 0);
    EXPECT_EQ(frame("fail", 1), frame("good", 1));
    EXPECT_EQ(frame("fail", 2), frame("good", 2));
    for (const auto& e : fs::directory_iterator(dir_ / "fail"))
        EXPECT_FALSE(is_partial_name(e.path().filename().string())) << e.path();
}

// A camera that looks at its own position between two good keys: bad input, before any frame.
TEST_F(Animate, ATrackThatDegeneratesBetweenKeysIsBadInput) {
    // Linear: position and look-at meet at t = 1/4, frame 4 at 12 fps.
    const fs::path s = scene(walk_scene(R"([
        {"time": 0, "position": [0, 2, 30], "look_at": [0, 2, 20]},
        {"time": 1, "position": [0, 2, 10], "look_at": [0, 2, 40]}])",
                                        96, 64, R"("interpolation": "linear", )"));
    auto r = animate(s, "bad", "");
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("/camera/track: frame 4"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "bad"));
    auto still =
        run_pleinair("render " + s.string() + " --frame 4 -o " + (dir_ / "r.png").string());
    EXPECT_EQ(still.exit_code, 2) << still.err;
    EXPECT_FALSE(fs::exists(dir_ / "r.png"));
}

// Frames of a --preview run are not the full run's: --resume paints them again.
TEST_F(Animate, ResumeRepaintsFramesOfAnotherSize) {
    const fs::path s = scene(walk_scene(kWalk));
    ASSERT_EQ(animate(s, "mixed", "--frames 1-2 --preview").exit_code, 0);
    ASSERT_EQ(animate(s, "full", "--frames 1-2").exit_code, 0);
    auto r = animate(s, "mixed", "--frames 1-3 --resume");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    size_t saved = 0, pos = 0;
    while ((pos = r.out.find("Saved: ", pos)) != std::string::npos) ++saved, ++pos;
    EXPECT_EQ(saved, 3u);
    EXPECT_EQ(frame("mixed", 1), frame("full", 1));
    EXPECT_EQ(frame("mixed", 2), frame("full", 2));
}

}  // namespace
}  // namespace pleinair
