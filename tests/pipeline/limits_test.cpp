// Limits: each checked before the work it bounds, refused with exit 2 and a line that gives
// the limit and how to raise it, nothing written; raised, the same job runs.
#include "pipeline/input/limits.h"

#include <gtest/gtest.h>

#include <fstream>

#include "pipeline/output/image_io.h"
#include "pipeline/frame/paint_frame.h"
#include "test_util.h"

namespace pleinair {
namespace {

using test::run_pleinair;

TEST(Limits, EachIsCheckedBeforeTheWorkAndSaysHowToRaiseIt) {
    const auto dir = test::temp_dir("limits");
    const std::string out = (dir / "out.png").string();
    struct Case {
        std::string args, expect;
    };
    // A 16384 x 16384 still: its image buffers alone are some 10 GB.
    const Case cases[] = {
        {"render grove -o " + out +
             " --set /camera/width=16384 --set /camera/height=16384 --limit memory_mb=4000",
         "/camera/width: a 16384x16384 frame needs about 10240 MB for its image buffers (40 "
         "bytes a pixel), over the limit of 4000 MB; raise it with --limit memory_mb=N"},
        {"render mortefontaine -o " + out + " --limit trees=10",
         "/groups: the scene places 134 trees (3 listed, the rest scattered), over the limit of "
         "10; raise it with --limit trees=N"},
        {"family --preset oak --count 20000 -o " + (dir / "fam").string(),
         "--count: 20000 members, over the limit of 10000; raise it with --limit members=N"},
        {"render grove -o " + out + " --limit input_mb=0", "--limit input_mb expects a whole"},
        {"render grove -o " + out + " --limit bogus=3", "no limit \"bogus\" (have: input_mb"},
    };
    for (const Case& c : cases) {
        const auto r = run_pleinair(c.args);
        EXPECT_EQ(r.exit_code, 2) << c.args << "\n" << r.err;
        EXPECT_NE(r.err.find(c.expect), std::string::npos) << c.args << "\n" << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    }
    EXPECT_FALSE(std::filesystem::exists(out));
    EXPECT_FALSE(std::filesystem::exists(dir / "fam"));

    // An input file past its limit is refused once that many bytes are read (a 2 MB scene).
    {
        std::ofstream f(dir / "big.json");
        f << "{\"description\": \"" << std::string(2 << 20, 'x') << "\"}";
    }
    auto r = run_pleinair("render " + (dir / "big.json").string() + " -o " + out +
                          " --limit input_mb=1");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("big.json: larger than the limit of 1 MB for an input file; raise it "
                         "with --limit input_mb=N"),
              std::string::npos)
        << r.err;
    r = run_pleinair("render grove -o " + out + " --limit trees=8");
    EXPECT_NE(r.err.find("grove.json: /trees: the scene lists 9 trees, over the limit of 8"),
              std::string::npos)
        << r.err;
    // Raised, the same job runs: the grove's nine trees under a limit of nine.
    r = run_pleinair("render grove -o " + out + " --limit trees=9 --set /camera/width=64 " +
                     "--set /camera/height=36");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(image_has_size(out, 64, 36));
}

TEST(Limits, TheFrameEstimateCountsEveryBuffer) {
    // 16 RGBA + 16 stroke layer + 20 x 0.5^2 underpainting + 3 PNG = 40 bytes a pixel.
    EXPECT_EQ(frame_buffer_bytes(1000, 1000, false, 0.5f, output_bytes_per_pixel("a.png", false)),
              40'000'000u);
    // AOVs add four float channels to the frame and to the EXR's copies (8 x 6).
    EXPECT_EQ(frame_buffer_bytes(1000, 1000, true, 0.5f, output_bytes_per_pixel("a.exr", true)),
              (32 + 16 + 5 + 48) * 1'000'000u);
    EXPECT_EQ(output_bytes_per_pixel("a.tif", false), 6.0);
}

TEST(Limits, ALongFrameSaysHowFarItHasCome) {
    const auto dir = test::temp_dir("progress");
    const auto r = run_pleinair("render grove --progress -o " + (dir / "p.png").string() +
                                " --set /camera/width=256 --set /camera/height=144");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    for (const char* line :
         {"256x144: shot built in", "pleinair: sprites (", "pleinair: paint (",
          "pleinair: paint 50% (", "pleinair: paint 100% (", "pleinair: writing "})
        EXPECT_NE(r.err.find(line), std::string::npos) << line << " in:\n" << r.err;
}

}  // namespace
}  // namespace pleinair
