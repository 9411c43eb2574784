// bias, gain and smoothstep, value by value and at their edges.
#include "shading/curves.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace pleinair {
namespace {

TEST(Curves, BiasPassesThroughItsParameterAtOneHalf) {
    for (float b : {0.1f, 0.25f, 0.5f, 0.8f, 0.95f}) EXPECT_NEAR(bias(0.5f, b), b, 1e-6f);
    EXPECT_FLOAT_EQ(bias(0.0f, 0.3f), 0.0f);
    EXPECT_FLOAT_EQ(bias(1.0f, 0.3f), 1.0f);
    for (float x : {0.0f, 0.2f, 0.7f, 1.0f}) EXPECT_NEAR(bias(x, 0.5f), x, 1e-6f);
    EXPECT_NEAR(bias(0.25f, 0.8f), std::pow(0.25f, std::log(0.8f) / std::log(0.5f)), 1e-6f);
}

TEST(Curves, BiasIsFiniteAndMonotoneAtExtremeParameters) {
    for (float b : {0.0f, 1e-9f, 1.0f, -3.0f, 7.0f}) {
        float prev = -1;
        for (int i = 0; i <= 100; ++i) {
            float y = bias(i / 100.0f, b);
            ASSERT_TRUE(std::isfinite(y)) << b;
            ASSERT_GE(y, prev);
            ASSERT_GE(y, 0.0f);
            ASSERT_LE(y, 1.0f);
            prev = y;
        }
    }
    EXPECT_EQ(bias(std::numeric_limits<float>::quiet_NaN(), 0.3f), 0.0f);
}

TEST(Curves, GainIsSymmetricAboutTheMiddle) {
    for (float g : {0.2f, 0.5f, 0.8f}) {
        EXPECT_NEAR(gain(0.5f, g), 0.5f, 1e-6f);
        for (float x : {0.1f, 0.3f}) EXPECT_NEAR(gain(x, g) + gain(1.0f - x, g), 1.0f, 1e-6f);
    }
    EXPECT_NEAR(gain(0.3f, 0.5f), 0.3f, 1e-6f);
    EXPECT_LT(gain(0.25f, 0.8f), 0.25f);  // g > 0.5 steepens the middle
    EXPECT_GT(gain(0.25f, 0.2f), 0.25f);
    EXPECT_TRUE(std::isfinite(gain(0.0f, 0.0f)));
    EXPECT_TRUE(std::isfinite(gain(1.0f, 1.0f)));
}

TEST(Curves, SmoothstepMatchesHermiteAndHandlesEqualEdges) {
    EXPECT_FLOAT_EQ(smoothstep(0.2f, 0.6f, 0.1f), 0.0f);
    EXPECT_FLOAT_EQ(smoothstep(0.2f, 0.6f, 0.7f), 1.0f);
    EXPECT_FLOAT_EQ(smoothstep(0.2f, 0.6f, 0.4f), 0.5f);
    EXPECT_NEAR(smoothstep(0.0f, 1.0f, 0.25f), 0.15625f, 1e-7f);
    EXPECT_FLOAT_EQ(smoothstep(0.5f, 0.5f, 0.49f), 0.0f);
    EXPECT_FLOAT_EQ(smoothstep(0.5f, 0.5f, 0.5f), 1.0f);
    EXPECT_FLOAT_EQ(smoothstep(0.6f, 0.4f, 0.5f), 0.0f);  // crossed edges: a step at e0
    EXPECT_EQ(smoothstep(0.2f, 0.6f, std::numeric_limits<float>::quiet_NaN()), 0.0f);
}

}  // namespace
}  // namespace pleinair
