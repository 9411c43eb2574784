// Graftal sites and tufts for a fixed seed: counts by each placement rule, sites on the surface,
// tuft graftals where and as the description says, and each site's graftals independent of the
// others.
#include "pipeline/shot/graftal_instances.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>

#include "generators/rock.h"
#include "pipeline/input/graftal_io.h"

namespace pleinair {
namespace {

// A flat 10 x 10 grid of unit quads in the xz plane, facing up: area 100.
QuadMesh grid() {
    QuadMesh m;
    for (int z = 0; z <= 10; ++z)
        for (int x = 0; x <= 10; ++x) m.positions.push_back(glm::vec3(x, 0, z));
    for (unsigned z = 0; z < 10; ++z)
        for (unsigned x = 0; x < 10; ++x) {
            const unsigned a = z * 11 + x;
            m.quads.push_back({a, a + 11, a + 12, a + 1});  // counter-clockwise seen from +y
        }
    return m;
}

GraftalDesc placed(GraftalPlacement at) {
    GraftalDesc g = load_graftal("grass-tuft");
    g.placement = at;
    return g;
}

TEST(GraftalInstances, SitesByEachPlacementRule) {
    const QuadMesh m = grid();
    EXPECT_EQ(mesh_sites(placed(GraftalPlacement::kVertices), m, 1, 0).size(), 121u);
    const auto faces = mesh_sites(placed(GraftalPlacement::kFaces), m, 1, 0);
    ASSERT_EQ(faces.size(), 100u);
    EXPECT_EQ(faces[0].position, glm::dvec3(0.5, 0, 0.5));  // a face's centre
    EXPECT_NEAR(faces[0].normal.y, 1.0f, 1e-6f);            // facing up
    GraftalDesc k = placed(GraftalPlacement::kEveryKthFace);
    k.every_k = 4;
    const size_t kth = mesh_sites(k, m, 1, 0).size();
    EXPECT_GT(kth, 12u);  // about 25 of 100
    EXPECT_LT(kth, 40u);
    EXPECT_EQ(mesh_sites(k, m, 1, 0).size(), kth);  // the same faces again
    EXPECT_TRUE(mesh_sites(placed(GraftalPlacement::kLeafParticles), m, 1, 0).empty());
}

TEST(GraftalInstances, DensityGivesItsCountOnTheSurface) {
    GraftalDesc g = placed(GraftalPlacement::kDensity);
    g.per_area = 3;
    const auto sites = mesh_sites(g, grid(), 7, 5);
    EXPECT_NEAR(static_cast<double>(sites.size()), 300.0, 30.0);  // 3 a unit over 100 units
    for (const GraftalSite& s : sites) {
        EXPECT_EQ(s.position.y, 0.0);
        EXPECT_TRUE(s.position.x >= 0 && s.position.x <= 10 && s.position.z >= 0 &&
                    s.position.z <= 10);
        EXPECT_EQ(s.object, 5u);
    }
    // On a generated rock: every site within the rock's bounds.
    const QuadMesh rock = generate_rock(RockParams{}, 3, {0, 0, 0});
    const Bounds b = bounds_of(rock.positions);
    for (const GraftalSite& s : mesh_sites(g, rock, 7, 0)) {
        EXPECT_TRUE(s.position.x >= b.min.x - 1e-5 && s.position.x <= b.max.x + 1e-5);
        EXPECT_NEAR(glm::length(s.normal), 1.0f, 1e-5f);
    }
}

TEST(GraftalInstances, TuftsHoldEachLevelsGraftalsAroundTheirSite) {
    const GraftalDesc g = load_graftal("seuss-leaf-tuft");  // levels of 1, 3 and 6
    const std::vector<GraftalSite> sites = {{{0, 0, 0}, {0, 1, 0}, 1, 10},
                                            {{5, 2, 0}, {1, 0, 0}, 1, 11}};
    const auto all = grow_tufts(g, sites, 3);
    ASSERT_EQ(all.size(), 2u * (1 + 3 + 6));
    for (const GraftalInstance& i : all) {
        const GraftalSite& s = sites[i.tuft];
        const glm::dvec3 off = i.position - s.position;
        EXPECT_NEAR(glm::dot(off, glm::dvec3(s.normal)), 0.0, 1e-9);  // in the tangent plane
        EXPECT_LE(glm::length(off), g.tuft.spread * g.length + 1e-9);
        EXPECT_LE(std::abs(i.length / g.length - (i.level > 0 ? 0.85f : 1.0f)),
                  g.variation.length + 1e-5f);
        EXPECT_LE(std::abs(i.angle), g.variation.angle);
        EXPECT_TRUE(i.delay >= 0 && i.delay < 1);
        if (i.level == 1) {
            EXPECT_EQ(g.examples[i.example].name, "small-puff");
        } else if (i.level == 0) {
            EXPECT_EQ(g.examples[i.example].name, "puff");
        }
    }
    EXPECT_EQ(all[0].position, glm::dvec3(0, 0, 0));  // level 0's first stands on its site
    EXPECT_EQ(all[0].delay, 0.0f);
}

TEST(GraftalInstances, ASitesGraftalsDoNotDependOnTheOtherSites) {
    const GraftalDesc g = load_graftal("grass-tuft");
    const GraftalSite a{{1, 0, 1}, {0, 1, 0}, 0, 100}, b{{4, 0, 2}, {0, 1, 0}, 0, 200};
    const auto both = grow_tufts(g, {a, b}, 9);
    const auto alone = grow_tufts(g, {b}, 9);
    const size_t per = both.size() / 2;
    ASSERT_EQ(alone.size(), per);
    for (size_t i = 0; i < per; ++i) {
        EXPECT_EQ(both[per + i].position, alone[i].position);
        EXPECT_EQ(both[per + i].length, alone[i].length);
        EXPECT_EQ(both[per + i].key, alone[i].key);
    }
    // Another seed, other graftals; the same seed, the same ones.
    EXPECT_NE(grow_tufts(g, {a}, 10)[1].position, grow_tufts(g, {a}, 9)[1].position);
    EXPECT_EQ(grow_tufts(g, {a}, 9)[1].position, both[1].position);
}

}  // namespace
}  // namespace pleinair
