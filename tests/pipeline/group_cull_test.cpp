// Culling by group (group_cull.h) against culling particle by particle: the same sprites, in
// the same order, from random cameras over shipped shots, with and without the thinning of
// small strokes and with occlusion maps; the thinning's own rule (lod.h); the memo of occlusion
// maps and answers (seen_memo.h); and where the frame plan draws occlusion maps.
#include "pipeline/frame/group_cull.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>

#include "pipeline/frame/frame_plan.h"
#include "pipeline/frame/paint_frame.h"
#include "pipeline/frame/seen_memo.h"
#include "pipeline/frame/sprites.h"
#include "pipeline/input/scene.h"
#include "pipeline/shot/particle_input.h"
#include "pipeline/shot/shot.h"
#include "tests/test_util.h"

namespace pleinair {
namespace {

// The sprites of a view, culled by group or particle by particle.
SpriteSet sprites_of(const Shot& shot, const FrameView& view, const FrameSettings& fs,
                     bool group_culling) {
    // With occlusion maps whatever the shot's size, so clusters are also culled behind them.
    FramePlan plan = plan_frame(shot, fs);
    plan.occlusion_maps = plan.underpaint;
    const FrameLod lod = level_of_detail(shot, view, fs.render);
    const SeenWindow seen = seen_window(shot.scene, view, fs.render);
    const FrameWind wind = frame_wind(shot, view.time, lod);  // still air: off
    SpriteStageInput in{shot, view, plan, fs.render, lod, shot.sun_rays.get(), &seen};
    in.group_culling = group_culling;
    in.wind = &wind;
    return make_sprites(in);
}

void expect_same_sprites(const SpriteSet& a, const SpriteSet& b) {
    ASSERT_EQ(a.sprites.size(), b.sprites.size());
    EXPECT_EQ(a.culled, b.culled);
    EXPECT_EQ(a.hidden, b.hidden);
    for (size_t k = 0; k < a.sprites.size(); ++k) {
        const Sprite &p = a.sprites[k], &q = b.sprites[k];
        ASSERT_EQ(sprite_key(p), sprite_key(q)) << k;
        ASSERT_EQ(p.x, q.x);
        ASSERT_EQ(p.y, q.y);
        ASSERT_EQ(p.half_w, q.half_w);
        ASSERT_EQ(p.half_l, q.half_l);
        ASSERT_EQ(p.fade, q.fade);
        ASSERT_EQ(p.k.lightness, q.k.lightness);
    }
}

// A view of the shot's track at a random time, its eye moved and turned at random: within the
// scene, sometimes looking down, sometimes along the ground, sometimes away.
FrameView random_view(const Shot& shot, std::mt19937& rng) {
    const SceneDesc& s = shot.scene;
    const TimeSpan span = animation_span(s);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    FrameView view = view_at(s, span.first + u(rng) * (span.last - span.first));
    CameraParams p = s.camera_params;
    p.position = view.camera.eye + glm::dvec3(60 * (u(rng) - 0.5), 6 * u(rng), 60 * (u(rng) - 0.5));
    const double yaw = 2 * M_PI * u(rng), pitch = -0.6 * u(rng);
    p.look_at = p.position + glm::dvec3(std::cos(yaw) * std::cos(pitch), std::sin(pitch),
                                        std::sin(yaw) * std::cos(pitch));
    p.width = 160 + static_cast<int>(400 * u(rng));
    p.height = p.width * 9 / 16;
    EXPECT_EQ(make_camera(p, view.camera), "");
    return view;
}

TEST(GroupCulling, NeverDropsAStrokeThatParticleCullingDraws) {
    std::mt19937 rng(26);
    uint64_t grouped = 0, drawn = 0;
    // The gusts move the willow's strokes out of their clusters' bounds at rest: the bounds
    // widen by the wind's reach.
    for (const char* name :
         {"forest-edge-walk", "mortefontaine-walk", "truffula-walk", "willow-gust"}) {
        SCOPED_TRACE(name);
        ShotOptions options;
        options.cache_sun_light = true;  // as animate builds it
        const Shot shot = build_shot(
            load_scene(test::source_dir() / "presets" / "scenes" / (std::string(name) + ".json")),
            options);
        FrameSettings fs = scene_frame_settings(shot.scene);
        for (int n = 0; n < 6; ++n) {
            SCOPED_TRACE(n);
            const FrameView view = random_view(shot, rng);
            fs.render.thin_below_px = n % 2 ? 6.0f : 0.0f;
            const SpriteSet by_group = sprites_of(shot, view, fs, true);
            const SpriteSet each = sprites_of(shot, view, fs, false);
            expect_same_sprites(by_group, each);
            grouped += by_group.grouped, drawn += by_group.sprites.size();
        }
    }
    // The test means something: clusters were culled whole, and sprites were drawn.
    EXPECT_GT(grouped, 10000u);
    EXPECT_GT(drawn, 10000u);
}

// Where the frame's edge cuts a crown, a gust blows strokes into view from clusters that lie
// off screen at rest: their bounds widen by the wind's reach, or those strokes are lost. The
// willow in a strong wind, the camera turned step by step so the frame's edge sweeps the crown
// (at 480x270 a step moves the edge by a few pixels; at 160x90 no stroke crosses it).
TEST(GroupCulling, WindBlowsStrokesIntoViewFromClustersOffScreenAtRest) {
    const Shot shot =
        build_shot(load_scene(test::source_dir() / "presets" / "scenes" / "willow-gust.json",
                              {"/camera/width=480", "/camera/height=270",
                               R"(/wind/track=[{"time": 0, "strength": 20},
                                               {"time": 8, "strength": 20}])"}));
    ASSERT_TRUE(shot.plan.wind);
    ASSERT_EQ(shot.clusters.size(), 2u);  // the willow, then the ground touches at its foot
    const ItemClusters& ic = shot.clusters[0];
    std::map<uint64_t, size_t> cluster_of;  // particle key -> its cluster
    for (size_t k = 0; k < ic.clusters.size(); ++k)
        for (uint32_t i = ic.clusters[k].first; i < ic.clusters[k].first + ic.clusters[k].count;
             ++i)
            cluster_of[particle_key(0, ic.clusters[k].kind, ic.order[i])] = k;
    const FrameSettings fs = scene_frame_settings(shot.scene);
    uint64_t grouped = 0, blown_in = 0;
    // The willow's upwind side leaving the frame's left edge (the wind blows it back in), then a
    // view turned away from it.
    std::vector<glm::dvec3> looks;
    for (double x = 14.0; x <= 30.0; x += 0.25) looks.emplace_back(x, 5.8, 0.0);
    looks.emplace_back(0.0, 3.0, 60.0);
    for (const glm::dvec3& look : looks) {
        SCOPED_TRACE(look.x);
        FrameView view = view_at(shot.scene, 2.5);
        CameraParams p = shot.scene.camera_params;
        p.look_at = look;
        ASSERT_EQ(make_camera(p, view.camera), "");
        const SpriteSet by_group = sprites_of(shot, view, fs, true);
        const SpriteSet each = sprites_of(shot, view, fs, false);
        expect_same_sprites(by_group, each);
        grouped += by_group.grouped;
        // The strokes the case is about: drawn, from a cluster that lies off screen at rest.
        const FrameLod lod = level_of_detail(shot, view, fs.render);
        for (const Sprite& sp : each.sprites)
            if (sp.item == 0)  // the willow's (the touches at its foot do not blow)
                blown_in += cluster_fate(shot, lod, view.camera, fs.render, 0,
                                         ic.clusters[cluster_of.at(sprite_key(sp))],
                                         0.0) != ClusterFate::kShown;
    }
    // The test means something: clusters were culled whole (the view turned away), and strokes
    // did blow into view.
    EXPECT_GE(grouped, ic.order.size());
    EXPECT_GT(blown_in, 0u);
    RecordProperty("blown_in", static_cast<int>(blown_in));
}

TEST(GroupCulling, ClustersHoldEveryParticleOnce) {
    const Shot shot =
        build_shot(load_scene(test::source_dir() / "presets" / "scenes" / "forest-edge-walk.json"));
    ASSERT_EQ(shot.clusters.size(), shot.item_count());
    for (size_t i = 0; i < shot.item_count(); ++i) {
        size_t n = 0;
        for_each_particle(shot, i, [&](SpriteKind, size_t, const RayOrigin&) { ++n; });
        const ItemClusters& ic = shot.clusters[i];
        ASSERT_EQ(ic.order.size(), n);
        std::vector<int> seen(n, 0);
        size_t covered = 0;
        for (const ParticleCluster& c : ic.clusters) {
            ASSERT_LE(c.count, kClusterSize);
            ASSERT_EQ(c.first, covered);
            covered += c.count;
            for (uint32_t k = c.first; k < c.first + c.count; ++k) {
                const size_t j = ic.order[k];
                const size_t slot = particle_slot(shot, i, c.kind, j);
                ASSERT_LT(slot, n);
                ++seen[slot];
                // Inside its bounds.
                const glm::dvec3 w = particle_origin(shot, i, c.kind, j).world;
                ASSERT_TRUE(glm::all(glm::greaterThanEqual(w, c.lo)) &&
                            glm::all(glm::lessThanEqual(w, c.hi)));
            }
        }
        ASSERT_EQ(covered, n);
        for (int s : seen) ASSERT_EQ(s, 1);
    }
}

TEST(SeenMemo, FramesInOrderCastFewerRaysForTheSameSprites) {
    ShotOptions options;
    options.cache_sun_light = true;
    const Shot shot = build_shot(
        load_scene(test::source_dir() / "presets" / "scenes" / "forest-edge-walk.json"), options);
    FrameSettings fs = scene_frame_settings(shot.scene);
    SeenMemo memo;
    uint64_t with = 0, without = 0, maps_kept = 0, maps_alone = 0;
    for (int f : {20, 21, 22, 23, 25, 24, 40}) {  // in order, a step back, a jump
        SCOPED_TRACE(f);
        const FrameView view = view_at(shot.scene, frame_time(f, shot.scene.fps));
        FramePlan plan = plan_frame(shot, fs);
        plan.occlusion_maps = true;  // maps kept as well as answers
        const FrameLod lod = level_of_detail(shot, view, fs.render);
        const SeenWindow seen = seen_window(shot.scene, view, fs.render);
        ASSERT_EQ(seen.cameras.size(), 4u);
        SpriteStageInput in{shot, view, plan, fs.render, lod, shot.sun_rays.get(), &seen};
        const SpriteSet each = make_sprites(in);
        in.seen_memo = &memo;
        const SpriteSet remembered = make_sprites(in);
        expect_same_sprites(remembered, each);
        with += remembered.occlusion_rays, without += each.occlusion_rays;
        maps_kept += remembered.map_rays, maps_alone += each.map_rays;
    }
    // The maps too: a frame one after another builds one of its four.
    EXPECT_GT(maps_kept, 0u);
    EXPECT_LT(maps_kept, maps_alone * 0.55);
    // Frames one apart share three of four lattice times: about a quarter of the rays, and
    // the first frame and the jump cast them all.
    EXPECT_LT(with, without * 0.55);
    EXPECT_GT(with, without * 0.25);
}

TEST(Thinning, KeepsAboutTheAreaAndFadesIn) {
    // Whole at or above the thinning size, whatever the draw.
    for (float u : {0.0f, 0.5f, 0.999f}) EXPECT_EQ(thin_presence(1.0f, u), 1.0f);
    EXPECT_EQ(thin_presence(0.0f, 0.0f), 0.0f);
    EXPECT_EQ(thin_kept(1.0f), 1.0f);
    EXPECT_NEAR(thin_kept(0.9999f), 1.0f, 1e-3);  // no step where thinning starts
    for (float r : {0.05f, 0.2f, 0.5f, 0.8f, 0.99f}) {
        // The mean presence over draws is thin_kept(r^2), the share of area the survivors grow
        // by the inverse of: about r^2 (1 + kThinBand / 2), and 1 at r = 1.
        double mean = 0;
        constexpr int kDraws = 100000;
        float before = 1;
        for (int k = 0; k < kDraws; ++k) {
            const float p = thin_presence(r, (k + 0.5f) / kDraws);
            ASSERT_TRUE(p >= 0.0f && p <= 1.0f);
            ASSERT_LE(p, before + 1e-6f);  // a later draw is never kept more
            before = p;
            mean += p;
        }
        mean /= kDraws;
        const double q = double(r) * r;
        EXPECT_NEAR(mean, thin_kept(static_cast<float>(q)), 0.002 * q + 1e-4) << r;
        if (q * (1 + kThinBand) <= 1) {
            EXPECT_NEAR(thin_kept(static_cast<float>(q)), q * (1 + kThinBand / 2), 1e-6);
        }
        // No stroke appears at once: its presence grows by at most 1 / kThinBand of the
        // relative growth of r^2.
        for (int k = 0; k < 100; ++k) {
            const float u = (k + 0.5f) / 100;
            const float a = thin_presence(r, u), b = thin_presence(r * 1.01f, u);
            ASSERT_LE(b - a, 0.0201f / kThinBand * 1.5f + 1e-4f) << r << " " << u;
            ASSERT_GE(b, a);
        }
    }
    // Draws are the particle's own: spread over [0, 1), unlike for neighbours.
    double sum = 0;
    for (size_t j = 0; j < 10000; ++j) {
        const float u = thin_draw(3, SpriteKind::kLeaf, j);
        ASSERT_TRUE(u >= 0.0f && u < 1.0f);
        sum += u;
    }
    EXPECT_NEAR(sum / 10000, 0.5, 0.01);
    EXPECT_NE(thin_draw(3, SpriteKind::kLeaf, 7), thin_draw(4, SpriteKind::kLeaf, 7));
}

// Thinning is on by default (issue 53: a preview is the same painting seen smaller): a walk's
// small frame keeps fewer strokes than without it, and no survivor grows past
// render/thin_max_growth, even where the near field or a wide thinning size asks for more (the
// draft's 6 px would grow the smallest strokes 3.6x).
TEST(Thinning, OnByDefaultAndSurvivorsGrowAtMostTheCap) {
    const Shot shot =
        build_shot(load_scene(test::source_dir() / "presets" / "scenes" / "mortefontaine-walk.json",
                              {"/camera/width=160", "/camera/height=90"}));
    const FrameView view = view_at(shot.scene, 2.0);
    const FrameSettings defaults = scene_frame_settings(shot.scene);
    EXPECT_EQ(defaults.render.thin_below_px, 2.0f * defaults.render.min_stroke_px);
    EXPECT_EQ(defaults.render.thin_max_growth, 2.0f);
    FrameSettings none = defaults;
    none.render.thin_below_px = 0;
    const SpriteSet all = sprites_of(shot, view, none, false);
    std::map<uint64_t, float> width;
    for (const Sprite& sp : all.sprites) width[sprite_key(sp)] = sp.half_w;
    for (float thin_px : {3.0f, 6.0f}) {
        SCOPED_TRACE(thin_px);
        FrameSettings fs = defaults;
        fs.render.thin_below_px = thin_px;
        const SpriteSet thinned = sprites_of(shot, view, fs, false);
        EXPECT_LT(thinned.sprites.size(), all.sprites.size() * (thin_px > 3 ? 0.5 : 0.8));
        // (A grown survivor may reach past the frame's edge or a crest where the stroke at its
        // own size did not: it has no width to compare with.)
        float most = 0;
        size_t compared = 0;
        for (const Sprite& sp : thinned.sprites) {
            const auto it = width.find(sprite_key(sp));
            if (it == width.end()) continue;
            most = std::max(most, sp.half_w / it->second);
            ++compared;
        }
        EXPECT_GT(compared, thinned.sprites.size() * 0.95);
        EXPECT_LE(most, 2.0f * (1 + 1e-5f));
        EXPECT_GT(most, 1.5f) << "survivors grew";
    }
}

}  // namespace
}  // namespace pleinair

namespace pleinair {
namespace {

// The frame plan draws occlusion maps where the shot's strokes outnumber the maps' texels eight
// to one (a small frame of the open walk, the dense wood at any size), not where a map would
// cost more rays than its answers save (the open walk at full size: BENCHMARKS.md, "Occlusion
// maps").
TEST(OcclusionMaps, DrawnWhereTheStrokesOutnumberTheTexels) {
    auto plan_at = [](const char* scene, int w, int h) {
        const Shot shot = build_shot(load_scene(
            test::source_dir() / "presets" / "scenes" / scene,
            {"/camera/width=" + std::to_string(w), "/camera/height=" + std::to_string(h)}));
        return plan_frame(shot, scene_frame_settings(shot.scene)).occlusion_maps;
    };
    EXPECT_TRUE(plan_at("forest-edge-walk.json", 112, 64));
    EXPECT_FALSE(plan_at("forest-edge-walk.json", 1920, 1080));
    EXPECT_FALSE(plan_at("truffula-walk.json", 256, 144));
}

}  // namespace
}  // namespace pleinair
