// Bark strokes: on the limbs' surface (at the scaled ring radius from the skeleton), oriented
// along their limb, as many as the coverage asks, keyed so a seed repeats them exactly.
#include "generators/bark.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>

#include "generators/tree.h"
#include "test_util.h"

namespace pleinair {
namespace {

TEST(Bark, StrokesLieOnTheLimbsAlongTheirAxis) {
    Tree t = generate_tree(test::preset("oak"), 2);
    BarkOptions o;
    BarkParticles b = emit_bark(t, o, 2);
    ASSERT_GT(b.size(), 500u);
    double expected = 0;  // strokes the coverage asks for over the emitting segments
    for (const BranchInfo& br : t.branches) {
        if (br.level > o.max_level) continue;
        for (size_t s = 0; s + 1 < br.ring_centers.size(); ++s) {
            const double len = glm::length(br.ring_centers[s + 1] - br.ring_centers[s]);
            const double r = o.surface_scale * (br.ring_radii[s] + br.ring_radii[s + 1]);
            expected += o.coverage * M_PI * r * len / (o.stroke_length * o.stroke_width);
        }
    }
    EXPECT_NEAR(double(b.size()), expected, 0.05 * expected + 20);
    for (size_t i = 0; i < b.size(); ++i) {
        ASSERT_NEAR(glm::length(b.normal[i]), 1.0f, 1e-4f);
        ASSERT_NEAR(glm::length(b.tangent[i]), 1.0f, 1e-4f);
        ASSERT_NEAR(glm::dot(b.normal[i], b.tangent[i]), 0.0f, 1e-4f);
        ASSERT_GT(b.label[i], 0.0f);
        ASSERT_LT(b.label[i], 1.0f);
        ASSERT_EQ(b.tree_id[i], t.id);
        // Some limb segment runs along the stroke's tangent, and the stroke sits at its radius
        // from that segment's axis.
        bool on_a_limb = false;
        for (const BranchInfo& br : t.branches) {
            for (size_t s = 0; s + 1 < br.ring_centers.size() && !on_a_limb; ++s) {
                const glm::vec3 c0 = br.ring_centers[s], axis = br.ring_centers[s + 1] - c0;
                const float len = glm::length(axis);
                if (!(len > 0) || glm::dot(axis / len, b.tangent[i]) < 0.9999f) continue;
                const glm::vec3 rel = b.position[i] - c0;
                const float along = glm::dot(rel, axis / len);
                if (along < -1e-4f || along > len + 1e-4f) continue;
                const float dist = glm::length(rel - axis / len * along);
                on_a_limb = std::abs(dist - b.radius[i]) < 1e-3f * std::max(1.0f, b.radius[i]);
            }
            if (on_a_limb) break;
        }
        ASSERT_TRUE(on_a_limb) << "stroke " << i;
    }
}

TEST(Bark, SeedRepeatsLevelsAndThicknessLimitStrokes) {
    Tree t = generate_tree(test::preset("willow"), 5);
    BarkOptions o;
    BarkParticles a = emit_bark(t, o, 5), again = emit_bark(t, o, 5), other = emit_bark(t, o, 6);
    EXPECT_EQ(a.position, again.position);
    EXPECT_EQ(a.label, again.label);
    EXPECT_NE(a.position, other.position);
    o.max_level = 0;  // the trunk alone
    BarkParticles trunk = emit_bark(t, o, 5);
    EXPECT_LT(trunk.size(), a.size());
    EXPECT_GT(trunk.size(), 0u);
    o.max_level = -1;
    EXPECT_EQ(emit_bark(t, o, 5).size(), 0u);
    o.max_level = 2;
    o.min_radius = 1e9f;  // every limb thinner than this: none
    EXPECT_EQ(emit_bark(t, o, 5).size(), 0u);
    o.min_radius = 0;
    o.coverage = 0;
    EXPECT_EQ(emit_bark(t, o, 5).size(), 0u);
}

}  // namespace
}  // namespace pleinair
