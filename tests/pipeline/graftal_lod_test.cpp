// σ, ρ, τ and λ at known values; the tuft level filter's hysteresis, its timed transitions and
// its replay; the local frame at its degenerate cases.
#include "pipeline/shot/graftal_lod.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>

#include "generators/rng.h"

namespace pleinair {
namespace {

TEST(GraftalLod, SigmaIsWorldLengthOverTheDiameterOfThePreferredScreenSize) {
    // 25 px at 40 units through a 1000 px focal length spans 1 world unit.
    EXPECT_FLOAT_EQ(graftal_sigma(1.0, 25, 40, 1000), 1.0f);
    EXPECT_FLOAT_EQ(graftal_sigma(1.0, 25, 20, 1000), 2.0f);  // twice as near: twice the size
    EXPECT_FLOAT_EQ(graftal_sigma(0.5, 25, 40, 1000), 0.5f);
    EXPECT_FLOAT_EQ(graftal_sigma(1.0, 50, 40, 1000), 0.5f);  // prefers to be larger
    EXPECT_EQ(graftal_sigma(1.0, 25, 0, 1000), 0.0f);         // at the eye
    EXPECT_EQ(graftal_sigma(1.0, 25, -3, 1000), 0.0f);        // behind it
    EXPECT_EQ(graftal_sigma(1.0, 25, NAN, 1000), 0.0f);
    EXPECT_TRUE(std::isfinite(graftal_sigma(1.0, 25, 1e-300, 1000)));
}

TEST(GraftalLod, RhoByEachRuleAndLambdaFromTheThree) {
    const glm::vec3 n(0, 1, 0);
    const glm::vec3 v60 = glm::normalize(glm::vec3(std::sqrt(3.0f), 1, 0));  // n.v = 1/2
    EXPECT_NEAR(graftal_rho(GraftalRho::kSilhouette, n, v60), 0.5f, 1e-6f);
    EXPECT_NEAR(graftal_rho(GraftalRho::kFrontFacing, n, v60), 0.5f, 1e-6f);
    EXPECT_EQ(graftal_rho(GraftalRho::kSilhouette, n, n), 0.0f);          // seen face on
    EXPECT_EQ(graftal_rho(GraftalRho::kSilhouette, n, {1, 0, 0}), 1.0f);  // on the silhouette
    EXPECT_EQ(graftal_rho(GraftalRho::kFrontFacing, n, -n), 1.0f);        // |n.v|: back faces too
    EXPECT_EQ(graftal_rho(GraftalRho::kNone, n, v60), 1.0f);
    EXPECT_EQ(graftal_rho(GraftalRho::kSilhouette, n, n * 1.001f), 0.0f);  // never below 0
    EXPECT_EQ(graftal_rho(GraftalRho::kSilhouette, {NAN, 0, 0}, n), 0.0f);

    EXPECT_FLOAT_EQ(graftal_lambda(GraftalLambda::kRhoSigma, 3, 0.5f, 0.2f), 1.5f);
    EXPECT_FLOAT_EQ(graftal_lambda(GraftalLambda::kTauRhoSigma, 3, 0.5f, 0.2f), 0.3f);
    EXPECT_FLOAT_EQ(graftal_lambda(GraftalLambda::kSigma, 3, 0.5f, 0.2f), 3.0f);
    EXPECT_EQ(graftal_lambda(GraftalLambda::kRhoSigma, INFINITY, 0.5f, 1), 0.0f);
    EXPECT_EQ(graftal_lambda(GraftalLambda::kRhoSigma, -2, 0.5f, 1), 0.0f);
}

TEST(GraftalLod, RampsInterpolateOverTheirLambdaRange) {
    const LodRamp r{1, 3, 0.0f, 1.0f};
    EXPECT_EQ(lod_ramp(r, 0), 0.0f);
    EXPECT_EQ(lod_ramp(r, 1), 0.0f);
    EXPECT_FLOAT_EQ(lod_ramp(r, 2), 0.5f);
    EXPECT_EQ(lod_ramp(r, 3), 1.0f);
    EXPECT_EQ(lod_ramp(r, 50), 1.0f);
    EXPECT_EQ(lod_ramp(LodRamp{}, 7), 1.0f);  // no ramp: its end value
    EXPECT_EQ(lod_ramp(r, NAN), 0.0f);
}

TEST(GraftalLod, TheLevelIsTheHighestWhoseThresholdIsReached) {
    const std::vector<TuftLevel> levels = {{0, 1, {}}, {1.5f, 3, {}}, {3, 6, {}}};
    EXPECT_EQ(tuft_level(levels, 0), 0);
    EXPECT_EQ(tuft_level(levels, 1.49f), 0);
    EXPECT_EQ(tuft_level(levels, 1.5f), 1);
    EXPECT_EQ(tuft_level(levels, 2.9f), 1);
    EXPECT_EQ(tuft_level(levels, 3), 2);
    EXPECT_EQ(tuft_level(levels, 1e9f), 2);
}

TuftRules four_levels(int queue, float hysteresis, float seconds = 0.5f) {
    TuftRules r;
    r.levels = {{0, 1, {}}, {1, 1, {}}, {2, 1, {}}, {3, 1, {}}};
    r.queue = queue;
    r.hysteresis = hysteresis;
    r.transition_seconds = seconds;
    return r;
}

// The paper's example: from level 2, u = 2.6 stays, 2.8 goes up to 3; from 3, u = 2.3 stays
// and 2.2 comes back down to 2.
TEST(GraftalLod, HysteresisAsThePaperDescribesIt) {
    const TuftRules rules = four_levels(10, 0.25f);
    TuftState s;
    step_tuft(s, rules, 2, 0.04);
    ASSERT_EQ(s.level, 2);
    // Ten choices whose mean is the u wanted: the queue holds the last ten.
    auto feed = [&](int threes) {
        for (int i = 0; i < 10; ++i) step_tuft(s, rules, i < threes ? 3 : 2, 0.04);
    };
    feed(6);
    EXPECT_FLOAT_EQ(s.average, 2.6f);
    EXPECT_EQ(s.level, 2);
    feed(8);
    EXPECT_FLOAT_EQ(s.average, 2.8f);
    EXPECT_EQ(s.level, 3);
    feed(3);
    EXPECT_FLOAT_EQ(s.average, 2.3f);
    EXPECT_EQ(s.level, 3);
    feed(2);
    EXPECT_FLOAT_EQ(s.average, 2.2f);
    EXPECT_EQ(s.level, 2);
}

int switches(const TuftRules& rules, const std::function<float(int)>& lambda, int frames) {
    TuftState s;
    int n = 0, last = -1;
    for (int f = 0; f < frames; ++f) {
        step_tuft(s, rules, tuft_level(rules.levels, lambda(f)), 1.0 / 24);
        n += last >= 0 && s.level != last;
        last = s.level;
    }
    return n;
}

TEST(GraftalLod, ALambdaWobblingAroundAThresholdDoesNotSwitchBackAndForth) {
    // λ jitters at random by up to 0.3 for ten seconds at 24 fps: around level 2's threshold
    // (the worst case: each frame's choice is a coin toss), and a little above it.
    Rng rng = make_rng(5, Purpose::kSurface);
    std::vector<float> jitter(240);
    for (float& j : jitter) j = static_cast<float>(rand_range(rng, -0.3, 0.3));
    auto at = [&](float mean) {
        return [&jitter, mean](int f) { return mean + jitter[static_cast<size_t>(f)]; };
    };
    const int raw = switches(four_levels(1, 0.0f), at(2.0f), 240);
    EXPECT_GT(raw, 60);  // unfiltered it flickers every few frames: what is being prevented
    // The paper's settings hold a level whose threshold λ only grazes...
    EXPECT_EQ(switches(four_levels(8, 0.25f), at(2.4f), 240), 0);
    // ...and a longer queue with wider hysteresis holds even the coin toss.
    const int held = switches(four_levels(12, 0.4f), at(2.0f), 240);
    EXPECT_LE(held, 2);
    RecordProperty("switches_raw", raw);
    RecordProperty("switches_held", held);
}

TEST(GraftalLod, LevelsGrowInAndFadeOutOverTheirTransitionTime) {
    const TuftRules rules = four_levels(1, 0.25f, 0.5f);  // 12 frames at 24 fps
    TuftState s;
    step_tuft(s, rules, 0, 1.0 / 24);
    EXPECT_EQ(s.tau, (std::vector<float>{1, 0, 0, 0}));  // the shot opens settled
    int frames_to_full = 0;
    float last = 0;
    for (int f = 0; f < 40 && s.tau[1] < 1.0f; ++f) {
        step_tuft(s, rules, 1, 1.0 / 24);
        EXPECT_LE(s.tau[1] - last, 1.0f / 12 + 1e-6f);  // no jump: a twelfth per frame at most
        EXPECT_GE(s.tau[1], last);
        last = s.tau[1];
        ++frames_to_full;
    }
    EXPECT_EQ(frames_to_full, 12);
    EXPECT_EQ(s.tau[2], 0.0f);
    // Back down: level 1 fades over the same time, still drawn while it does.
    int fading = 0;
    while (s.tau[1] > 0.0f && fading < 40) {
        step_tuft(s, rules, 0, 1.0 / 24);
        ++fading;
        EXPECT_EQ(s.level, 0);
    }
    EXPECT_EQ(fading, 12);
}

TEST(GraftalLod, AFrameAloneEqualsTheSameFrameInSequence) {
    const TuftRules rules = four_levels(6, 0.25f, 0.3f);
    // A camera moving in and out: λ rises and falls through every level.
    auto lambda = [](int f) { return 1.6f + 1.8f * static_cast<float>(std::sin(f * 0.07)); };
    std::vector<TuftState> sequence;
    TuftState s;
    for (int f = 0; f < 120; ++f) {
        step_tuft(s, rules, tuft_level(rules.levels, lambda(f)), 1.0 / 24);
        sequence.push_back(s);
    }
    for (int f : {119, 0, 57, 33, 90, 1}) {
        const TuftState alone = replay_tuft(rules, lambda, f, 24);
        EXPECT_EQ(alone.level, sequence[f].level) << f;
        EXPECT_EQ(alone.tau, sequence[f].tau) << f;
        EXPECT_EQ(alone.recent, sequence[f].recent) << f;
    }
    int distinct = 0;
    for (int f = 1; f < 120; ++f) distinct += sequence[f].level != sequence[f - 1].level;
    EXPECT_GE(distinct, 4);  // the track does move through the levels
}

TEST(GraftalLod, ATuftThatNeverChangesLevelReplaysToWhatSteppingGives) {
    // replay_tuft starts a tuft that chose one level at every frame where the first frame
    // leaves it; it must be exactly where stepping every frame ends, at each level.
    const TuftRules rules = four_levels(6, 0.25f, 0.3f);
    for (float lambda : {0.2f, 1.1f, 2.5f, 3.7f}) {
        TuftState stepped;
        for (int f = 0; f <= 80; ++f)
            step_tuft(stepped, rules, tuft_level(rules.levels, lambda), 1.0 / 24);
        const TuftState alone = replay_tuft(
            rules, [&](int) { return lambda; }, 80, 24);
        EXPECT_EQ(alone.level, stepped.level) << lambda;
        EXPECT_EQ(alone.tau, stepped.tau) << lambda;
        EXPECT_EQ(alone.recent, stepped.recent) << lambda;
        EXPECT_EQ(alone.average, stepped.average) << lambda;
        EXPECT_EQ(alone.started, stepped.started) << lambda;
    }
}

TEST(GraftalLod, LocalFramesAreOrthonormalEvenWhereTheRuleDegenerates) {
    Rng rng = make_rng(9, Purpose::kSurface, 2);
    auto unit = [&] {
        return glm::normalize(
            glm::vec3(rand_range(rng, -1, 1), rand_range(rng, -1, 1), rand_range(rng, -1, 1)) +
            glm::vec3(1e-3f));
    };
    auto check = [](const GraftalAxes& a, const glm::vec3& n) {
        for (const glm::vec3& e : {a.x, a.y, a.z}) {
            ASSERT_TRUE(std::isfinite(e.x) && std::isfinite(e.y) && std::isfinite(e.z));
            EXPECT_NEAR(glm::length(e), 1.0f, 1e-5f);
        }
        EXPECT_NEAR(glm::dot(a.x, a.y), 0.0f, 1e-5f);
        EXPECT_NEAR(glm::dot(a.y, a.z), 0.0f, 1e-5f);
        EXPECT_NEAR(glm::dot(a.x, a.z), 0.0f, 1e-5f);
        EXPECT_NEAR(glm::dot(a.y, n), 1.0f, 1e-5f);
    };
    for (int i = 0; i < 200; ++i) {
        const glm::vec3 n = unit(), v = unit(), t = unit();
        for (GraftalFrame rule :
             {GraftalFrame::kView, GraftalFrame::kUpright, GraftalFrame::kSurface})
            check(graftal_axes(rule, n, v, t), n);
        // kView: x = n x v is perpendicular to the view.
        EXPECT_NEAR(glm::dot(graftal_axes(GraftalFrame::kView, n, v, t).x, v), 0.0f, 1e-5f);
    }
    const glm::vec3 up(0, 1, 0);
    check(graftal_axes(GraftalFrame::kView, up, up, up), up);      // eye straight above
    check(graftal_axes(GraftalFrame::kUpright, up, up, up), up);   // a level surface
    check(graftal_axes(GraftalFrame::kSurface, up, -up, {}), up);  // no tangent given
    const GraftalAxes bad = graftal_axes(GraftalFrame::kView, {0, 0, 0}, {NAN, 0, 0}, {});
    check(bad, up);  // no normal: upright, and still a frame
}

}  // namespace
}  // namespace pleinair
