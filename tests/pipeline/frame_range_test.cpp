// Frame ranges and output patterns as farms write them, and the bad ones refused.
#include "pipeline/input/frame_range.h"

#include <gtest/gtest.h>

#include "pipeline/input/error.h"

namespace pleinair {
namespace {

TEST(FrameRange, ParsesFramesRangesAndSteps) {
    EXPECT_EQ(parse_frame_range("7").frames(), (std::vector<int>{7}));
    EXPECT_EQ(parse_frame_range("1-4").frames(), (std::vector<int>{1, 2, 3, 4}));
    EXPECT_EQ(parse_frame_range("1-10x4").frames(), (std::vector<int>{1, 5, 9}));
    EXPECT_EQ(parse_frame_range("0-0").frames(), (std::vector<int>{0}));
    const FrameRange big = parse_frame_range("999999990-999999999x5");
    EXPECT_EQ(big.frames(), (std::vector<int>{999999990, 999999995}));
}

TEST(FrameRange, RefusesWhatIsNotARange) {
    for (const char* bad : {"10-1", "x", "", "1-", "-3", "1-10x0", "1-10x", "a-b", "1.5", "1-2-3",
                            " 1-2", "1234567890"}) {
        SCOPED_TRACE(bad);
        try {
            parse_frame_range(bad);
            ADD_FAILURE() << "accepted";
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find("--frames"), std::string::npos) << e.what();
        }
    }
}

TEST(FramePattern, HashesAndPrintfBecomeTheFrameNumber) {
    EXPECT_EQ(parse_frame_pattern("out/walk/frame_####.png").path(42), "out/walk/frame_0042.png");
    EXPECT_EQ(parse_frame_pattern("f#.exr").path(123), "f123.exr");
    EXPECT_EQ(parse_frame_pattern("shot.%04d.tif").path(7), "shot.0007.tif");
    EXPECT_EQ(parse_frame_pattern("shot.%d.png").path(7), "shot.7.png");
    EXPECT_EQ(parse_frame_pattern("a/b_%3d.png").path(5), "a/b_005.png");
    EXPECT_EQ(parse_frame_pattern("f############.png").path(7), "f000000000007.png");
    EXPECT_EQ(parse_frame_pattern("f%012d.png").path(999999999), "f000999999999.png");
    EXPECT_EQ(parse_frame_pattern("f##.png").path(12345), "f12345.png");  // wider than its pad
    for (const char* bad : {"frame.png", "f##_##.png", "f%04d_#.png", "f#/x.png", "f%013d.png",
                            "f%0999999999999d.png", "f#############.png"}) {
        SCOPED_TRACE(bad);
        EXPECT_THROW(parse_frame_pattern(bad), InputError);
    }
}

}  // namespace
}  // namespace pleinair
