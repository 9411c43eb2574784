// Difference-image placement: the Pascal dot, filling that ends and fills where desire is,
// candidates tried in a fixed order (deterministic, coherent as the desire moves), hidden
// candidates refused by the ID image.
#include "pipeline/frame/graftal_placement.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <set>

#include "generators/rng.h"

namespace pleinair {
namespace {

DesireImage flat(int w, int h, float value) {
    DesireImage img;
    img.width = w, img.height = h;
    img.desire.assign(static_cast<size_t>(w) * h, value);
    return img;
}

TEST(GraftalPlacement, ThePascalDotIsTheBinomialOuterProductPeakingAtOne) {
    const std::vector<float> d = pascal_dot(4);  // 1 4 6 4 1
    ASSERT_EQ(d.size(), 25u);
    EXPECT_FLOAT_EQ(d[2 * 5 + 2], 1.0f);
    EXPECT_FLOAT_EQ(d[0], 1.0f / 36);
    EXPECT_FLOAT_EQ(d[2 * 5 + 1], 4.0f / 6);
    EXPECT_FLOAT_EQ(d[1 * 5 + 3], 16.0f / 36);
    for (int j = 0; j < 5; ++j)
        for (int i = 0; i < 5; ++i) EXPECT_EQ(d[j * 5 + i], d[i * 5 + j]);  // symmetric
    EXPECT_EQ(pascal_dot(0), std::vector<float>{1.0f});
    for (float x : pascal_dot(60)) EXPECT_TRUE(std::isfinite(x) && x >= 0 && x <= 1);
}

TEST(GraftalPlacement, FillingEndsAndLeavesNoDesireAboveTheThreshold) {
    DesireImage img = flat(64, 48, 1.0f);
    const DifferencePlacement p;  // a 7-pixel dot, threshold 0.5
    const auto placed = fill_by_difference(img, p);
    for (float d : img.desire) EXPECT_LT(d, p.threshold);
    // Spread out: each dot clears the desire next to it, so no two stand side by side.
    for (size_t a = 0; a < placed.size(); ++a)
        for (size_t b = a + 1; b < placed.size(); ++b)
            EXPECT_GE(std::abs(placed[a].x - placed[b].x) + std::abs(placed[a].y - placed[b].y), 2);
    EXPECT_GT(placed.size(), 64u * 48 / 49);  // at least one per dot's square
    EXPECT_LT(placed.size(), 64u * 48 / 4);   // far fewer than one per pixel
    DesireImage again = flat(64, 48, 1.0f);
    EXPECT_EQ(fill_by_difference(again, p), placed);  // one function of the image
}

TEST(GraftalPlacement, GraftalsGoWhereTheDesireIsAndNowhereElse) {
    DesireImage img = flat(80, 60, 0.0f);
    for (int y = 10; y < 30; ++y)
        for (int x = 40; x < 70; ++x) img.desire[static_cast<size_t>(y) * 80 + x] = 1.0f;
    const auto placed = fill_by_difference(img, {});
    ASSERT_FALSE(placed.empty());
    for (const glm::ivec2& q : placed) {
        EXPECT_TRUE(q.x >= 40 && q.x < 70 && q.y >= 10 && q.y < 30) << q.x << ", " << q.y;
    }
    DesireImage none = flat(80, 60, 0.49f);
    EXPECT_TRUE(fill_by_difference(none, {}).empty());  // under the threshold everywhere
    DesireImage broken;
    broken.width = 3, broken.height = 3;  // no pixels behind it
    EXPECT_TRUE(fill_by_difference(broken, {}).empty());
}

std::vector<GraftalCandidate> scattered(size_t n, uint64_t seed, float w, float h) {
    Rng rng = make_rng(seed, Purpose::kSurface);
    std::vector<GraftalCandidate> c(n);
    for (size_t i = 0; i < n; ++i)
        c[i] = {glm::vec2(rand_range(rng, 0, w), rand_range(rng, 0, h)), 0, 1000 + i};
    return c;
}

TEST(GraftalPlacement, CandidatesAreTriedInTheSameOrderWhateverTheirListOrder) {
    auto c = scattered(3000, 4, 100, 80);
    DesireImage a = flat(100, 80, 1.0f);
    std::set<uint64_t> first;
    for (uint32_t i : place_candidates(a, c, {})) first.insert(c[i].key);
    std::reverse(c.begin(), c.end());
    DesireImage b = flat(100, 80, 1.0f);
    std::set<uint64_t> second;
    for (uint32_t i : place_candidates(b, c, {})) second.insert(c[i].key);
    EXPECT_EQ(first, second);
    EXPECT_GT(first.size(), 100u);
    EXPECT_LT(first.size(), 3000u);
    EXPECT_EQ(a.desire, b.desire);
}

// A camera move shifts every candidate by a pixel and changes the desire a little: most of the
// graftals placed are the same ones (what the eye sees as graftals that stay put).
TEST(GraftalPlacement, ASmallChangeOfViewKeepsMostOfTheSameGraftals) {
    auto c = scattered(4000, 7, 120, 90);
    auto keys = [](DesireImage img, const std::vector<GraftalCandidate>& cs) {
        std::set<uint64_t> k;
        for (uint32_t i : place_candidates(img, cs, {})) k.insert(cs[i].key);
        return k;
    };
    DesireImage before = flat(120, 90, 0.0f), after = flat(120, 90, 0.0f);
    for (int y = 0; y < 90; ++y)
        for (int x = 0; x < 120; ++x) {
            before.desire[static_cast<size_t>(y) * 120 + x] = 0.6f + 0.4f * std::sin(x * 0.05f);
            after.desire[static_cast<size_t>(y) * 120 + x] =
                0.6f + 0.4f * std::sin(x * 0.05f + 0.05f);
        }
    const auto k0 = keys(before, c);
    for (auto& g : c) g.pixel.x += 1.0f;
    const auto k1 = keys(after, c);
    size_t common = 0;
    for (uint64_t k : k0) common += k1.count(k);
    const double jaccard = static_cast<double>(common) / (k0.size() + k1.size() - common);
    EXPECT_GT(jaccard, 0.8);
    RecordProperty("jaccard", std::to_string(jaccard));
}

TEST(GraftalPlacement, ACandidateHiddenByAnotherObjectIsNotPlaced) {
    DesireImage img = flat(20, 20, 1.0f);
    img.id.assign(400, 1);
    for (int x = 0; x < 10; ++x)
        for (int y = 0; y < 20; ++y) img.id[static_cast<size_t>(y) * 20 + x] = 2;  // left half: 2
    const std::vector<GraftalCandidate> c = {
        {{5, 5}, 1, 1}, {{15, 5}, 1, 2}, {{5, 15}, 2, 3}, {{-1, 4}, 1, 4}, {{15, 25}, 1, 5}};
    std::vector<uint64_t> keys;
    for (uint32_t i : place_candidates(img, c, {})) keys.push_back(c[i].key);
    std::sort(keys.begin(), keys.end());
    EXPECT_EQ(keys, (std::vector<uint64_t>{2, 3}));  // 1 is behind object 2; 4 and 5 are off
}

}  // namespace
}  // namespace pleinair

namespace pleinair {
namespace {

TEST(GraftalPlacement, ACandidateCarryingItsOwnDesireIsJudgedByIt) {
    // The image wants graftals everywhere; the candidates' own desire decides instead, less
    // the dots of those placed before them.
    DesireImage img{32, 32, std::vector<float>(32 * 32, 1.0f), {}};
    std::vector<GraftalCandidate> cands;
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x)
            cands.push_back({glm::vec2(x + 0.5f, y + 0.5f), 0, uint64_t(y * 32 + x),
                             x < 16 ? 0.2f : 1.0f});  // the left half does not want any
    DifferencePlacement p;
    p.dot_row = 4, p.threshold = 0.5f;
    const std::vector<uint32_t> placed = place_candidates(img, cands, p);
    ASSERT_FALSE(placed.empty());
    for (uint32_t c : placed) EXPECT_GE(cands[c].pixel.x, 16.0f) << c;
    // Spaced by their dots: no two placed side by side (a neighbour's dot takes 2/3 of 1).
    for (uint32_t a : placed)
        for (uint32_t b : placed)
            if (a != b) {
                const glm::vec2 d = cands[a].pixel - cands[b].pixel;
                EXPECT_GT(std::abs(d.x) + std::abs(d.y), 1.5f);
            }
    // Moved by a tenth of a pixel, nearly all the same candidates win: what each leaves to the
    // next changes by a tenth of a dot, not by a whole one.
    for (auto& c : cands) c.pixel.x += 0.1f;
    DesireImage again{32, 32, std::vector<float>(32 * 32, 1.0f), {}};
    std::vector<uint32_t> a = placed, b = place_candidates(again, cands, p), both;
    std::sort(a.begin(), a.end()), std::sort(b.begin(), b.end());
    std::set_intersection(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(both));
    EXPECT_GT(double(both.size()) / double(a.size() + b.size() - both.size()), 0.9)
        << both.size() << " of " << a.size() << " and " << b.size();
}

}  // namespace
}  // namespace pleinair
