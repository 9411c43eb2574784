// The level of detail: distance values from the circles, fades, the survivors' growth and
// spread, and hard cases (the camera inside a crown, at a tree's centre).
#include "pipeline/frame/lod.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <glm/geometric.hpp>
#include <unordered_map>

#include "pipeline/frame/paint_frame.h"
#include "pipeline/frame/sprites.h"
#include "pipeline/input/scene.h"
#include "pipeline/shot/shot.h"
#include "test_util.h"

namespace pleinair {
namespace {

TEST(DistanceCircles, ValueAtTheCirclesAndBetween) {
    EXPECT_EQ(circle_value(0, 10, 50), 0.0f);
    EXPECT_EQ(circle_value(10, 10, 50), 0.0f);
    EXPECT_FLOAT_EQ(circle_value(30, 10, 50), 0.5f);
    EXPECT_FLOAT_EQ(circle_value(20, 10, 50), 0.25f);
    EXPECT_EQ(circle_value(50, 10, 50), 1.0f);
    EXPECT_EQ(circle_value(1e9, 10, 50), 1.0f);
    EXPECT_EQ(circle_value(-5, 10, 50), 0.0f);  // behind the camera: foreground
    // Swapped circles are taken in order; equal ones step at their distance.
    for (double d : {0.0, 12.0, 30.0, 49.0, 80.0})
        EXPECT_EQ(circle_value(d, 50, 10), circle_value(d, 10, 50)) << d;
    EXPECT_EQ(circle_value(19.999, 20, 20), 0.0f);
    EXPECT_EQ(circle_value(20, 20, 20), 0.0f);
    EXPECT_EQ(circle_value(20.001, 20, 20), 1.0f);
    EXPECT_EQ(circle_value(std::nan(""), 10, 50), 1.0f);
    // Monotonic in depth.
    float last = 0;
    for (double d = 0; d < 60; d += 0.37) {
        const float v = circle_value(d, 10, 50);
        EXPECT_GE(v, last);
        last = v;
    }
    EXPECT_EQ(near_field_value(0, 5), 1.0f);
    EXPECT_FLOAT_EQ(near_field_value(2.5, 5), 0.5f);
    EXPECT_EQ(near_field_value(5, 5), 0.0f);
    EXPECT_EQ(near_field_value(1, 0), 0.0f);  // no near field
}

TEST(DistanceCircles, DepthIsAlongTheViewAxisAtAnyOrientation) {
    // A point's depth is its distance from the plane through the eye perpendicular to the
    // view, whatever way the camera looks: points in one such plane share a distance value.
    for (int i = 0; i < 40; ++i) {
        const double a = 0.61 * i, b = 0.37 * i - 7;
        CameraParams p;
        p.position = {3 * std::sin(a), 2 + b * 0.1, 5 * std::cos(0.7 * a)};
        p.look_at = p.position +
                    glm::dvec3(std::cos(a) * std::cos(b), std::sin(b), std::sin(a) * std::cos(b));
        p.up = {std::sin(0.3 * i), 1, 0.2};
        Camera cam;
        ASSERT_EQ(make_camera(p, cam), "");
        for (double d : {0.5, 7.0, 42.0}) {
            const glm::dvec3 w = cam.eye + cam.forward * d + cam.right * (3.0 * b) - cam.up * a;
            EXPECT_NEAR(view_depth(cam, w), d, 1e-9 * (1 + std::abs(b) + a));
        }
    }
}

TEST(DistanceCircles, BadCirclesAreNamed) {
    DistanceCircles c;
    c.leaf_near = 30, c.leaf_far = 10;
    auto p = validate_circles(c, "/camera");
    ASSERT_EQ(p.size(), 1u);
    EXPECT_EQ(p[0].pointer, "/camera/leaf_far");
    EXPECT_NE(p[0].message.find(">= leaf_near (30)"), std::string::npos) << p[0].message;
    c = {};
    c.trunk_near = 5;  // a near circle without its far one
    p = validate_circles(c, "/camera");
    ASSERT_EQ(p.size(), 1u);
    EXPECT_EQ(p[0].pointer, "/camera/trunk_far");
    c = {};
    c.near_field = -1;
    EXPECT_EQ(validate_circles(c, "/k").at(0).pointer, "/k/near_field");
    c = {};
    c.leaf_far = INFINITY;
    EXPECT_EQ(validate_circles(c, "/k").size(), 1u);
    c = {};
    c.leaf_near = c.leaf_far = 20;  // equal circles: a step, allowed
    EXPECT_TRUE(validate_circles(c, "/k").empty());
}

TEST(Fades, MonotonicAndBounded) {
    for (float g : {0.2f, 0.4f, 0.5f, 0.8f}) {
        float last = 1;
        for (float v = -0.2f; v <= 1.2f; v += 0.01f) {
            const float f = leaf_fade(v, 0.3f, 0.6f, g);
            ASSERT_TRUE(f >= 0 && f <= 1) << v;
            ASSERT_LE(f, last) << v;
            if (v <= 0.3f) {
                ASSERT_EQ(f, 1.0f);
            }
            if (v >= 0.6f) {
                ASSERT_EQ(f, 0.0f);
            }
            last = f;
        }
        // The gain eases: half way, half gone.
        EXPECT_NEAR(leaf_fade(0.45f, 0.3f, 0.6f, g), 0.5f, 1e-5f);
    }
    // A fade of no length is a step.
    EXPECT_EQ(leaf_fade(0.49f, 0.5f, 0.5f, 0.4f), 1.0f);
    EXPECT_EQ(leaf_fade(0.5f, 0.5f, 0.5f, 0.4f), 0.0f);
    // The trunk, first branches and twigs bearing a kept leaf never fade; other twigs' strokes
    // are gone at the far circle, each over a span of 0.4.
    BranchInfo limb;
    for (int level : {0, 1, 2, 3})
        for (bool keeps : {false, true}) {
            limb.level = level, limb.keeps_leaves = keeps;
            EXPECT_EQ(twig_bark_fades(limb), level >= 2 && !keeps) << level << " " << keeps;
        }
    for (float label : {0.01f, 0.3f, 0.77f, 0.999f}) {
        EXPECT_EQ(bark_fade(1.0f, false, label, 0.4f), 1.0f);
        EXPECT_EQ(bark_fade(0.0f, true, label, 0.4f), 1.0f);
        EXPECT_EQ(bark_fade(1.0f, true, label, 0.4f), 0.0f);
        float last = 1;
        for (float v = 0; v <= 1; v += 0.05f) {
            const float f = bark_fade(v, true, label, 0.4f);
            ASSERT_LE(f, last);
            last = f;
        }
    }
    // The near field: interior leaves thin first; nothing thins outside it.
    EXPECT_EQ(near_field_fade(0.0f, 0.0f, 0.5f, 0.4f), 1.0f);
    EXPECT_LT(near_field_fade(0.9f, 0.05f, 0.5f, 0.4f), near_field_fade(0.9f, 0.95f, 0.5f, 0.4f));
}

// One oak seen from `distance` along +z, with circles.
SceneDesc oak_scene(double distance, const std::string& camera_extra = "") {
    return parse_scene(R"({"camera": {"position": [0, 7, )" + std::to_string(distance) +
                           R"(], "look_at": [0, 7, 0], "fov": 40, "width": 96, "height": 64,
                                     "leaf_near": 20, "leaf_far": 120,
                                     "trunk_near": 20, "trunk_far": 100)" +
                           camera_extra + R"(},
        "families": {"oak": {"preset": "oak"}},
        "trees": [{"family": "oak", "seed": 1, "position": [0, 0, 0]}]})",
                       "oak");
}

TEST(LevelOfDetail, TreesLoseLeavesAsTheyRecedeAndSurvivorsGrow) {
    const Shot shot = build_shot(oak_scene(10));
    const RenderSettings rs;
    float last_kept = 2, last_value = -1;
    for (double d : {10.0, 30.0, 60.0, 90.0, 120.0, 200.0}) {
        FrameView view = still_view(shot.scene);
        CameraParams p = shot.scene.camera_params;
        p.position.z = d;
        ASSERT_EQ(make_camera(p, view.camera), "");
        const FrameLod lod = level_of_detail(shot, view, rs);
        ASSERT_TRUE(lod.leaves && lod.trunks);
        ASSERT_EQ(lod.trees.size(), 1u);
        const TreeLod& t = lod.trees[0];
        // The tree's value, at its centre locator's depth.
        const glm::dvec3 c = shot.placements[0].place((*shot.trees)[0].tree().center);
        EXPECT_FLOAT_EQ(t.leaf, circle_value(view_depth(view.camera, c), 20, 120));
        EXPECT_GE(t.leaf, last_value);
        EXPECT_LE(t.kept, last_kept);
        // The survivors' area makes up for the leaves gone (Cook et al.): growth =
        // u^-kGrowthPower while the growth is within its bound.
        if (t.growth < rs.max_leaf_growth) {
            EXPECT_NEAR(std::pow(t.kept, kGrowthPower) * t.growth, 1.0f, 1e-4f);
            EXPECT_GT(t.growth, 1.0f / std::sqrt(t.kept) - 0.5f);  // about Cook's 1 / sqrt(u)
        }
        EXPECT_GE(t.growth, 1.0f);
        EXPECT_LE(t.growth, rs.max_leaf_growth);
        for (glm::vec2 r : t.radial) EXPECT_TRUE(r.x > 0.0f && r.x <= 1.0f && r.y > 0.0f);
        last_kept = t.kept, last_value = t.leaf;
    }
    // Beyond the far circle the innermost share the preset keeps remains (the oak's 40%).
    EXPECT_NEAR(last_kept, test::preset("oak").leaves.fade.keep, 0.01f);
}

TEST(LevelOfDetail, SurvivorsFillTheCrownsExtent) {
    // Beyond the far circle, the survivors' RMS distance from the centre comes back to (within
    // the growth bound) that of the whole crown.
    const Shot shot = build_shot(oak_scene(500));
    const FrameLod lod = level_of_detail(shot, still_view(shot.scene), RenderSettings{});
    const TreeLod& t = lod.trees.at(0);
    const LeafParticles& L = (*shot.trees)[0].tree().leaves;
    const glm::vec3 c = (*shot.trees)[0].tree().center;
    // The crown's spread along each axis: the fade ranks leaves in units of it.
    glm::dvec3 spread(0.0);
    for (const glm::vec3& p : L.position) spread += glm::dvec3(p - c) * glm::dvec3(p - c);
    spread = glm::sqrt(spread / double(L.size()));
    double all = 0, kept = 0, all_n = 0, kept_n = 0, moved = 0, w = 0;
    for (size_t j = 0; j < L.size(); ++j) {
        const double a =
            leaf_fade(t.leaf, L.fade_begin[j], L.fade_end[j], RenderSettings{}.fade_gain);
        const double r = glm::length(L.position[j] - c);
        const double rn = glm::length(glm::dvec3(L.position[j] - c) / spread);
        all += r * r, all_n += rn * rn;
        kept += a * r * r, kept_n += a * rn * rn;
        const double m = glm::length(spread_leaf(t, L.position[j]) - c);
        moved += a * m * m;
        w += a;
    }
    const double rms_all = std::sqrt(all / L.size()), rms_kept = std::sqrt(kept / w),
                 rms_moved = std::sqrt(moved / w);
    // The inner leaves alone, in the crown's own proportions: a smaller crown (0.69 of the
    // whole's RMS for the oak, which keeps 40%; 0.49 when it kept 20%).
    EXPECT_LT(std::sqrt(kept_n / w), 0.8 * std::sqrt(all_n / L.size()));
    EXPECT_NEAR(rms_moved, rms_all, 0.1 * rms_all) << rms_kept;
}

// Where sprites are painted, not only in the tree's LOD record: each far survivor's stroke is
// larger by its tree's growth than the same leaf's stroke with the level of detail off (its
// place moves a little towards the crown's edge, so its depth and size move by a few per cent).
TEST(LevelOfDetail, FarSurvivorsArePaintedGrownByTheirTreesGrowth) {
    const Shot shot = build_shot(oak_scene(150));
    const FrameView view = still_view(shot.scene);
    FrameSettings on = scene_frame_settings(shot.scene), off = on;
    off.render.level_of_detail = false;
    on.render.thin_below_px = 0;  // the circles' growth alone; thinning's is Thinning.*'s
    auto sprites = [&](const FrameSettings& fs) {
        const FramePlan plan = plan_frame(shot, fs);
        const FrameLod lod = level_of_detail(shot, view, fs.render);
        return make_sprites({shot, view, plan, fs.render, lod, shot.sun_rays.get()});
    };
    const SpriteSet a = sprites(on), b = sprites(off);
    const float growth = level_of_detail(shot, view, on.render).trees.at(0).growth;
    ASSERT_GT(growth, 1.3f) << "far enough for the survivors to grow";
    std::unordered_map<uint64_t, const Sprite*> plain;
    for (const Sprite& sp : b.sprites)
        if (sp.kind == SpriteKind::kLeaf) plain[sprite_key(sp)] = &sp;
    std::vector<double> ratios;
    for (const Sprite& sp : a.sprites) {
        if (sp.kind != SpriteKind::kLeaf) continue;
        const auto it = plain.find(sprite_key(sp));
        if (it == plain.end()) continue;
        ratios.push_back(std::sqrt(double(sp.half_w) * sp.half_l /
                                   (double(it->second->half_w) * it->second->half_l)));
    }
    ASSERT_GT(ratios.size(), 50u);
    std::sort(ratios.begin(), ratios.end());
    EXPECT_NEAR(ratios[ratios.size() / 2], growth, 0.1 * growth)
        << "the median survivor's linear size against its ungrown stroke";
}

// The shot keeps what no frame changes of each member's leaves (LeafBasis); a frame that
// computes it itself (a shot built with the level of detail off) gets the same bits, for the
// tree's record, every leaf's spread place and the frame's sprites.
TEST(LevelOfDetail, LeafBasisKeptInTheShotGivesTheSameBits) {
    Shot shot = build_shot(oak_scene(70));
    ASSERT_EQ(shot.leaf_basis.size(), shot.trees->size());
    const FrameView view = still_view(shot.scene);
    const FrameSettings fs = scene_frame_settings(shot.scene);
    const FramePlan plan = plan_frame(shot, fs);
    const FrameLod kept = level_of_detail(shot, view, fs.render);
    const SpriteSet kept_sprites =
        make_sprites({shot, view, plan, fs.render, kept, shot.sun_rays.get()});
    shot.leaf_basis.clear();
    const FrameLod own = level_of_detail(shot, view, fs.render);
    const SpriteSet own_sprites =
        make_sprites({shot, view, plan, fs.render, own, shot.sun_rays.get()});
    const TreeLod &a = kept.trees.at(0), &b = own.trees.at(0);
    ASSERT_GT(a.leaf, 0.3f) << "far enough for leaves to fade and survivors to spread";
    ASSERT_FALSE(a.radial.empty());
    EXPECT_EQ(0, std::memcmp(&a, &b, offsetof(TreeLod, center) + sizeof a.center));
    ASSERT_EQ(a.radial.size(), b.radial.size());
    EXPECT_EQ(0,
              std::memcmp(a.radial.data(), b.radial.data(), a.radial.size() * sizeof a.radial[0]));
    const Tree& tree = (*shot.trees)[0].tree();
    const LeafBasis basis = leaf_basis(tree, shot.scene.families[0].leaf_shader);
    size_t moved = 0;
    for (size_t j = 0; j < tree.leaves.size(); ++j) {
        const glm::vec3 p = tree.leaves.position[j];
        const glm::vec3 x = spread_leaf(a, p),
                        y = spread_leaf(a, p, basis.r[j], basis.e[j], basis.a[j]);
        ASSERT_EQ(0, std::memcmp(&x, &y, sizeof x)) << "leaf " << j;
        moved += x != p;
    }
    EXPECT_GT(moved, tree.leaves.size() / 2);
    ASSERT_EQ(kept_sprites.sprites.size(), own_sprites.sprites.size());
    ASSERT_GT(kept_sprites.sprites.size(), 100u);
    for (size_t k = 0; k < kept_sprites.sprites.size(); ++k) {
        const Sprite &p = kept_sprites.sprites[k], &q = own_sprites.sprites[k];
        ASSERT_EQ(sprite_key(p), sprite_key(q)) << k;
        ASSERT_EQ(p.x, q.x) << k;
        ASSERT_EQ(p.y, q.y) << k;
        ASSERT_EQ(p.depth, q.depth) << k;
        ASSERT_EQ(p.half_w, q.half_w) << k;
        ASSERT_EQ(p.half_l, q.half_l) << k;
        ASSERT_EQ(p.fade, q.fade) << k;
        ASSERT_EQ(p.k.lightness, q.k.lightness) << k;
    }
}

TEST(LevelOfDetail, OffWithoutCirclesOrWhenTurnedOff) {
    const Shot plain = build_shot(parse_scene(R"({"families": {"oak": {"preset": "oak"}},
        "trees": [{"family": "oak", "seed": 1, "position": [0, 0, 0]}]})",
                                              "plain"));
    FrameSettings fs = scene_frame_settings(plain.scene);
    EXPECT_FALSE(plan_frame(plain, fs).lod);
    const Shot shot = build_shot(oak_scene(60));
    fs = scene_frame_settings(shot.scene);
    EXPECT_TRUE(plan_frame(shot, fs).lod);
    fs.render.level_of_detail = false;
    EXPECT_FALSE(plan_frame(shot, fs).lod);
    const FrameLod off = level_of_detail(shot, still_view(shot.scene), fs.render);
    EXPECT_FALSE(off.leaves || off.trunks || off.surfaces || off.near_field);
}

TEST(LevelOfDetail, FewerSpritesFarAwayAndTheSameFromAnyThreadCount) {
    const Shot shot = build_shot(oak_scene(150));
    FrameSettings on = scene_frame_settings(shot.scene), off = on;
    off.render.level_of_detail = false;
    FrameReport a, b;
    const Frame fa = paint_frame(shot, still_view(shot.scene), on, &a);
    paint_frame(shot, still_view(shot.scene), off, &b);
    // Beyond the far circle, the share of its leaves the preset keeps (the oak's 40%).
    const double keep = test::preset("oak").leaves.fade.keep;
    EXPECT_LT(a.leaf_sprites, b.leaf_sprites * (keep + 0.1));
    EXPECT_GT(a.leaf_sprites, b.leaf_sprites * (keep - 0.1));
    EXPECT_LT(a.bark_sprites, b.bark_sprites);
    for (float v : fa.rgba) ASSERT_TRUE(std::isfinite(v));
    // The per-tree sums run in index order: one thread gives the same bytes.
    Frame one;
    {
        tbb::global_control single(tbb::global_control::max_allowed_parallelism, 1);
        one = paint_frame(shot, still_view(shot.scene), on);
    }
    ASSERT_EQ(one.rgba.size(), fa.rgba.size());
    EXPECT_EQ(0, std::memcmp(one.rgba.data(), fa.rgba.data(), fa.rgba.size() * sizeof(float)));
}

TEST(LevelOfDetail, NoNaNWithTheCameraInsideACrownOrAtATreesCentre) {
    const Shot shot = build_shot(oak_scene(10, R"(, "near_field": 8)"));
    const glm::dvec3 c = shot.placements[0].place((*shot.trees)[0].tree().center);
    const FrameSettings fs = scene_frame_settings(shot.scene);
    for (glm::dvec3 eye : {c, c + glm::dvec3(0.5, 0.2, 0.1), c + glm::dvec3(0, -2, 1)}) {
        size_t painted = 0;  // leaves, over the three directions
        for (glm::dvec3 dir : {glm::dvec3(0, 0, -1), glm::dvec3(0, 1, 0.01), glm::dvec3(1, 0, 0)}) {
            CameraParams p = shot.scene.camera_params;
            p.position = eye;
            p.look_at = eye + dir;
            FrameView view = still_view(shot.scene);
            ASSERT_EQ(make_camera(p, view.camera), "");
            const FrameLod lod = level_of_detail(shot, view, fs.render);
            for (const TreeLod& t : lod.trees) {
                ASSERT_TRUE(std::isfinite(t.leaf) && std::isfinite(t.kept) &&
                            std::isfinite(t.growth));
                for (glm::vec2 r : t.radial) ASSERT_TRUE(std::isfinite(r.x) && std::isfinite(r.y));
            }
            FrameReport rep;
            const Frame f = paint_frame(shot, view, fs, &rep);
            for (float v : f.rgba) ASSERT_TRUE(std::isfinite(v) && v >= 0);
            painted += rep.leaf_sprites;
        }
        // Some leaves are painted from each place (straight up from the centre, the open
        // crown of the oak shows the sky).
        EXPECT_GT(painted, 0u) << eye.x << " " << eye.y << " " << eye.z;
    }
    // At the centre locator itself, a leaf exactly there stays where it is.
    TreeLod t;
    t.center = glm::vec3(1, 2, 3);
    t.radial.assign(kElevationBins * kAzimuthBins, glm::vec2(0.5f, 4.0f));
    t.max_spread = 3;
    EXPECT_EQ(spread_leaf(t, t.center), t.center);
    // r = 1 of R = 4 with gamma 1/2: to 4 * (1/4)^(1/2) = 2. At or beyond R: unmoved.
    EXPECT_NEAR(glm::length(spread_leaf(t, glm::vec3(1, 3, 3)) - t.center), 2.0f, 1e-5f);
    EXPECT_EQ(spread_leaf(t, glm::vec3(1, 6, 3)), glm::vec3(1, 6, 3));
    // Near the centre the move is bounded.
    EXPECT_NEAR(glm::length(spread_leaf(t, glm::vec3(1, 2.001f, 3)) - t.center), 0.003f, 1e-4f);
}

}  // namespace
}  // namespace pleinair
