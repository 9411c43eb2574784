// Scanline coverage: exact areas for shapes inside the buffer and clipped by its sides, the
// nonzero rule for same-wound overlaps, and no harm from wild input.
#include "pipeline/shot/graftal_raster.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace pleinair {
namespace {

TEST(GraftalRaster, CoverageIsTheExactAreaInsideEachPixel) {
    CoverageRaster r(8, 8);
    // A square from (1.25, 2.5) to (5.75, 6): its corner pixels are partly covered.
    r.polygon({{1.25, 2.5}, {5.75, 2.5}, {5.75, 6}, {1.25, 6}});
    std::vector<float> c;
    r.coverage(c);
    EXPECT_NEAR(c[2 * 8 + 1], 0.75f * 0.5f, 1e-5);  // (1, 2): 0.75 wide, 0.5 high
    EXPECT_NEAR(c[4 * 8 + 3], 1.0f, 1e-5);
    EXPECT_NEAR(c[5 * 8 + 5], 0.75f, 1e-5);
    EXPECT_NEAR(c[6 * 8 + 3], 0.0f, 1e-5);
    double sum = 0;
    for (float v : c) sum += v;
    EXPECT_NEAR(sum, 4.5 * 3.5, 1e-4);
}

TEST(GraftalRaster, ShapesClippedByTheBufferKeepTheirCoverage) {
    // The triangle (-6, 0), (6, 0), (-6, 4): its slanted edge crosses x = 0 at y = 2. Under it,
    // x < 6 - 3y: pixel (0, 1) is covered over 1 - 1/6, pixel (1, 1) over a half.
    CoverageRaster r(4, 4);
    r.polygon({{-6, 0}, {6, 0}, {-6, 4}});
    std::vector<float> c;
    r.coverage(c);
    EXPECT_NEAR(c[0], 1.0f, 1e-5);
    EXPECT_NEAR(c[1 * 4 + 0], 1.0f - 1.0f / 6.0f, 1e-5);
    EXPECT_NEAR(c[1 * 4 + 1], 0.5f, 1e-5);
    EXPECT_NEAR(c[2 * 4 + 0], 0.0f, 1e-5);
    // The same past the right side: mirrored, x > 6 - 3y measured from x = 4.
    CoverageRaster m(4, 4);
    m.polygon({{10, 0}, {-2, 0}, {10, 4}});
    m.coverage(c);
    EXPECT_NEAR(c[1 * 4 + 3], 1.0f - 1.0f / 6.0f, 1e-5);
    EXPECT_NEAR(c[1 * 4 + 2], 0.5f, 1e-5);
}

TEST(GraftalRaster, SameWoundOverlapsCountOnceAndOppositeOnesCancel) {
    CoverageRaster r(6, 6);
    r.polygon({{1, 1}, {4, 1}, {4, 4}, {1, 4}});
    r.polygon({{2, 2}, {5, 2}, {5, 5}, {2, 5}});
    std::vector<float> c;
    r.coverage(c);
    EXPECT_NEAR(c[3 * 6 + 3], 1.0f, 1e-5);  // in both
    double sum = 0;
    for (float v : c) sum += v;
    EXPECT_NEAR(sum, 9 + 9 - 4, 1e-4);
}

TEST(GraftalRaster, WildInputLeavesTheBufferFinite) {
    CoverageRaster r(16, 16);
    const double inf = std::numeric_limits<double>::infinity();
    r.line({0, 0}, {inf, 5});
    r.line({std::nan(""), 1}, {3, 4});
    r.line({-1e308, 0.5}, {1e308, 0.5000000001});
    r.line({-1e300, -1e300}, {1e300, 1e300});
    r.polygon({{3, 1e-300}, {4, 2e-300}, {5, 0}});
    std::vector<float> c;
    r.coverage(c);
    for (float v : c) ASSERT_TRUE(std::isfinite(v) && v >= 0.0f && v <= 1.0f);
}

}  // namespace
}  // namespace pleinair
