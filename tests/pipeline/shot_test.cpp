// The shot and the frame's stages: a shot's cached sun light paints the same bytes as rays
// traced per frame, frame settings never need a rebuild, a frame does not depend on the frames
// painted before it, and each stage (plan, materials, sprites, depth order, tiles) on its own.
#include "pipeline/shot/shot.h"

#include <gtest/gtest.h>
#include <hwy/targets.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <glm/geometric.hpp>
#include <set>
#include <unordered_set>

#include "pipeline/frame/background.h"
#include "pipeline/frame/composite.h"
#include "pipeline/frame/paint_frame.h"
#include "pipeline/frame/sprites.h"
#include "pipeline/frame/tile_bins.h"
#include "pipeline/frame/underpaint.h"
#include "pipeline/input/scene.h"
#include "pipeline/output/image_io.h"
#include "pipeline/shot/rays.h"
#include "test_util.h"

namespace pleinair {
namespace {

// Terrain, water, a rock and two trees under a sun that casts shadows.
SceneDesc lit_scene(const std::string& render = R"({"samples": 1})") {
    return parse_scene(R"({"camera": {"position": [0, 3, 40], "look_at": [0, 4, -10], "fov": 50,
                                      "width": 80, "height": 56},
        "sun": {"direction": [-0.5, 0.6, 0.4], "casts_shadows": true},
        "atmosphere": {"near": 10, "far": 150},
        "materials": {"grass": {"shader": "grass"}, "earth": {"shader": "earth"},
                      "water": {"shader": "water"}, "rock": {"shader": "rock"}},
        "terrain": {"seed": 2, "min": [-60, -80], "max": [60, 50], "resolution": 33,
                    "hills": [{"center": [15, 5], "radius": 15, "height": -2}],
                    "material": "grass", "bank_material": "earth",
                    "strokes": {"particle_spans_u": 30, "particle_spans_v": 30}},
        "water": {"level": 0.0, "strokes": {"particle_spans_u": 8, "particle_spans_v": 8}},
        "rocks": [{"seed": 1, "position": [-6, 0.2, 20]}],
        "families": {"birch": {"preset": "birch"}, "shrub": {"preset": "shrub"}},
        "trees": [{"family": "birch", "seed": 3, "position": [8, 0, 18]},
                  {"family": "shrub", "seed": 4, "position": [-3, 0, 25]}],
        "render": )" + render +
                           "}",
                       "test");
}

bool same_pixels(const Frame& a, const Frame& b) {
    return a.rgba.size() == b.rgba.size() &&
           std::memcmp(a.rgba.data(), b.rgba.data(), a.rgba.size() * sizeof(float)) == 0;
}

Frame paint(const Shot& shot, FrameReport* rep = nullptr) {
    return paint_frame(shot, still_view(shot.scene), scene_frame_settings(shot.scene), rep);
}

TEST(Shot, CachedSunLightPaintsTheSameBytesAsRaysPerFrame) {
    const Shot traced = build_shot(lit_scene());
    ShotOptions o;
    o.cache_sun_light = true;
    const Shot cached = build_shot(lit_scene(), o);
    ASSERT_FALSE(traced.plan.sun_light);
    ASSERT_TRUE(cached.plan.sun_light);
    ASSERT_EQ(cached.sun_light->items(), cached.item_count());
    // Nothing is traced before a frame asks.
    for (size_t i = 0; i < cached.item_count(); ++i)
        for (size_t j = 0; j < cached.sun_light->size(i); ++j)
            ASSERT_LT(cached.sun_light->known(i, j), 0.0f);
    FrameReport a, b, c;
    const Frame fa = paint(traced, &a), fb = paint(cached, &b), fc = paint(cached, &c);
    EXPECT_GT(a.shadow_rays, 0u);
    // The first frame traces the light of the particles it shows, as many rays as without the
    // cache; the next takes all of it from the shot.
    EXPECT_EQ(b.shadow_rays, a.shadow_rays);
    EXPECT_EQ(c.shadow_rays, 0u) << "the second frame takes every particle's light from the shot";
    EXPECT_TRUE(same_pixels(fa, fb));
    EXPECT_TRUE(same_pixels(fa, fc));
    // The light did something: some particle is in shadow; and only what was shown is known.
    float darkest = 1;
    size_t known = 0, slots = 0;
    for (size_t i = 0; i < cached.item_count(); ++i)
        for (size_t j = 0; j < cached.sun_light->size(i); ++j, ++slots) {
            const float l = cached.sun_light->known(i, j);
            if (l >= 0) darkest = std::min(darkest, l), ++known;
        }
    EXPECT_LT(darkest, 0.5f);
    EXPECT_EQ(known, size_t(a.shadow_rays));
    EXPECT_LE(known, slots);
}

TEST(Shot, FrameSettingsThatDifferFromTheCacheTraceInstead) {
    ShotOptions o;
    o.cache_sun_light = true;
    const Shot cached = build_shot(lit_scene(), o);  // transmissive light cached
    FrameSettings threshold = scene_frame_settings(cached.scene);
    threshold.render.shadows = ShadowMode::kThreshold;
    EXPECT_EQ(plan_frame(cached, threshold).sun_light, SunLightSource::kShotScene);
    const Frame a = paint_frame(cached, still_view(cached.scene), threshold);
    const Shot fresh = build_shot(lit_scene(R"({"samples": 1, "shadows": "threshold"})"));
    const Frame b = paint(fresh);
    EXPECT_TRUE(same_pixels(a, b));
    EXPECT_FALSE(same_pixels(a, paint(cached)));  // the mode changed the picture
}

TEST(Shot, AFrameDoesNotDependOnTheFramesPaintedBefore) {
    const Shot shot = build_shot(lit_scene());
    FrameView near = still_view(shot.scene), far = near;
    CameraParams p = shot.scene.camera_params;
    p.position = {10, 6, 60};
    ASSERT_EQ(make_camera(p, far.camera), "");
    const FrameSettings s = scene_frame_settings(shot.scene, true);
    const Frame first = paint_frame(shot, near, s);
    const Frame other = paint_frame(shot, far, s);
    const Frame again = paint_frame(shot, near, s);
    EXPECT_FALSE(same_pixels(first, other));
    EXPECT_TRUE(same_pixels(first, again));
    EXPECT_EQ(first.depth, again.depth);
    EXPECT_EQ(first.object_id, again.object_id);
    // And a shot built anew paints it the same, on one thread as on two.
    Frame one, two;
    tbb::task_arena(1).execute([&] { one = paint_frame(build_shot(lit_scene()), near, s); });
    tbb::task_arena(2).execute([&] { two = paint_frame(build_shot(lit_scene()), near, s); });
    EXPECT_TRUE(same_pixels(first, one));
    EXPECT_TRUE(same_pixels(first, two));
}

TEST(Shot, PlansOnlyWhatTheSceneNeeds) {
    SceneDesc s = lit_scene();
    s.sun_casts_shadows = false;
    const Shot unlit = build_shot(s);
    EXPECT_FALSE(unlit.plan.shadows);
    EXPECT_FALSE(unlit.sun_rays);
    EXPECT_TRUE(unlit.view_rays);
    EXPECT_EQ(plan_frame(unlit, scene_frame_settings(s)).sun_light, SunLightSource::kNone);
    s.build.bark_coverage = 0;
    const Shot bare = build_shot(s);
    EXPECT_FALSE(bare.plan.bark);
    for (const BuiltTree& t : *bare.trees) EXPECT_EQ(t.bark().size(), 0u);
    // The view scene knows what each of its geometries is painted with underneath.
    const Shot shot = build_shot(lit_scene());
    ASSERT_EQ(shot.view_surfaces.size(), 1u + 1u + 1u + 2u);  // terrain, water, rock, 2 trees
    EXPECT_TRUE(shot.view_surfaces[0].terrain);
    EXPECT_EQ(shot.view_surfaces[1].material, shot.materials.surface(shot.scene.water.material));
    EXPECT_EQ(shot.view_surfaces[4].material, shot.materials.bark((*shot.trees)[1].family));
}

TEST(Materials, LookupsByKindAndName) {
    // The table holds its own copies: it outlives the scene it was built from (a shot that
    // pointed into its scene painted garbage once moved, issue 24).
    auto scene = std::make_unique<SceneDesc>(lit_scene());
    const MaterialTable m(*scene);
    const SceneDesc s = *scene;
    scene.reset();
    ASSERT_EQ(m.size(), 2 * s.families.size() + s.materials.size());
    for (uint32_t f = 0; f < s.families.size(); ++f) {
        EXPECT_EQ(*m[m.leaf(f)].shader, s.families[f].leaf_shader);
        EXPECT_EQ(*m[m.leaf(f)].palette, s.families[f].leaf_palette);
        EXPECT_EQ(m[m.leaf(f)].kind, SpriteKind::kLeaf);
        EXPECT_EQ(*m[m.bark(f)].shader, s.families[f].bark_shader);
        EXPECT_EQ(*m[m.bark(f)].palette, s.families[f].bark_palette);
        EXPECT_EQ(m[m.bark(f)].kind, SpriteKind::kBark);
        EXPECT_EQ(m[m.bark(f)].surface, nullptr);
    }
    for (uint32_t i = 0; i < s.materials.size(); ++i) {
        EXPECT_EQ(*m[m.surface(i)].surface, s.materials[i].surface);
        EXPECT_EQ(*m[m.surface(i)].shader, s.materials[i].shader);
        EXPECT_EQ(m[m.surface(i)].kind, SpriteKind::kSurface);
        // The edge table is the shader's own.
        const EdgeTable e = make_edge_table(s.materials[i].shader.stroke_fullness);
        EXPECT_EQ(0, std::memcmp(&e, &m[m.surface(i)].edge, sizeof e));
    }
}

TEST(Sprites, EveryParticleIsASpriteOrCulled) {
    const Shot shot = build_shot(lit_scene());
    const FrameSettings settings = scene_frame_settings(shot.scene);
    const FramePlan plan = plan_frame(shot, settings);
    const FrameView view = still_view(shot.scene);
    const FrameLod lod = level_of_detail(shot, view, settings.render);  // no circles: off
    const SpriteSet set =
        make_sprites({shot, view, plan, settings.render, lod, shot.sun_rays.get()});
    size_t particles = shot.land->stroke_count();
    for (const BuiltTree& t : *shot.trees) particles += t.tree().leaves.size() + t.bark().size();
    EXPECT_EQ(set.sprites.size() + set.culled, particles);
    EXPECT_EQ(set.leaf + set.bark + set.surface, set.sprites.size());
    EXPECT_GT(set.hidden, 0u);
    for (const Sprite& sp : set.sprites) {
        ASSERT_TRUE(std::isfinite(sp.x) && std::isfinite(sp.y) && sp.depth > 0);
        ASSERT_GT(sp.half_w, 0.0f);
        ASSERT_NEAR(sp.ax * sp.ax + sp.ay * sp.ay, 1.0f, 1e-5f);
        ASSERT_EQ(sp.kind, shot.materials[sp.material].kind);
    }
    // Looking away from everything: nothing left, nothing traced for the sun.
    FrameView away = still_view(shot.scene);
    CameraParams p = shot.scene.camera_params;
    p.position = {0, 3, 300};  // beyond the terrain, looking away from it
    p.look_at = p.position + glm::dvec3(0, 0, 10);
    ASSERT_EQ(make_camera(p, away.camera), "");
    const FrameLod away_lod = level_of_detail(shot, away, settings.render);
    const SpriteSet none =
        make_sprites({shot, away, plan, settings.render, away_lod, shot.sun_rays.get()});
    EXPECT_EQ(none.sprites.size(), 0u);
}

// Leaf strokes that follow no limb lie at their shader's stroke_angle on screen, within its
// angle_jitter: corot-leaves lays them flat (90, within 25 degrees either way), so every one
// not on a falling twig has its axis within 25 degrees of horizontal. A leaf whose implied
// branch falls more steeply than hanging_slope (corot-leaves: 40 degrees) is painted down
// along it: a willow's curtains, whose strokes run mostly up and down the screen (their mean
// |axis y| measured 0.91). With stroke_angle 0 and no hanging slope every stroke stands upright.
TEST(Sprites, LeafStrokesLieAtTheirAngleAndFallingTwigsLeavesRunDownThem) {
    auto sprites = [&](const std::vector<std::string>& sets) {
        const SceneDesc scene = parse_scene(
            R"({"camera": {"position": [0, 5, 24], "look_at": [0, 5, 0], "fov": 45,
                           "width": 160, "height": 160},
                "families": {"willow": {"preset": "willow"}},
                "trees": [{"family": "willow", "seed": 2, "position": [0, 0, 0]}]})",
            "test", sets);
        auto shot = std::make_shared<const Shot>(build_shot(scene));
        const FrameSettings settings = scene_frame_settings(shot->scene);
        const FramePlan plan = plan_frame(*shot, settings);
        const FrameView view = still_view(shot->scene);
        const FrameLod lod = level_of_detail(*shot, view, settings.render);
        return std::pair{shot, make_sprites({*shot, view, plan, settings.render, lod, nullptr})};
    };
    const float kJitter = std::sin(25.5f * 0.017453292f);
    {
        const auto [shot, set] = sprites({});
        const float hang = std::sin(40.0f * 0.017453292f);
        size_t flat = 0, hanging = 0;
        double hanging_ay = 0;
        for (const Sprite& sp : set.sprites) {
            if (sp.kind != SpriteKind::kLeaf) continue;
            const BuiltTree& b = (*shot->trees)[sp.item];
            const glm::vec3 n = b.tree().leaves.normal[sp.particle];  // no turn: rotation 0
            if (-n.y > hang) {
                ++hanging;
                hanging_ay += std::abs(sp.ay);
            } else {
                ++flat;
                ASSERT_LE(std::abs(sp.ay), kJitter) << sp.ax << " " << sp.ay;
            }
        }
        EXPECT_GT(flat, 200u);  // measured 303 of the willow's 1,551 leaves seen
        ASSERT_GT(hanging, 1000u);
        EXPECT_GT(hanging_ay / double(hanging), 0.8);
    }
    const auto [shot, upright] =
        sprites({R"(/families/willow/leaf_shader_keys={"sprite": {"stroke_angle": 0,
                                                                   "hanging_slope": 91}})"});
    size_t leaves = 0;
    for (const Sprite& sp : upright.sprites) {
        if (sp.kind != SpriteKind::kLeaf) continue;
        ++leaves;
        ASSERT_LE(std::abs(sp.ax), kJitter) << sp.ax << " " << sp.ay;
    }
    EXPECT_GT(leaves, 600u);
}

TEST(Sprites, PartlyHiddenStrokesAreDrawnByTheShareSeen) {
    // Without circles a tree's strokes are whole, unless the camera sees only the top of them
    // past a crest or a trunk: then a third or two (of three rays), never culled outright.
    const Shot shot = build_shot(lit_scene());
    const FrameSettings settings = scene_frame_settings(shot.scene);
    const FramePlan plan = plan_frame(shot, settings);
    const FrameView view = still_view(shot.scene);
    const FrameLod lod = level_of_detail(shot, view, settings.render);
    const SpriteSet set =
        make_sprites({shot, view, plan, settings.render, lod, shot.sun_rays.get()});
    size_t partial = 0;
    for (const Sprite& sp : set.sprites) {
        if (sp.kind == SpriteKind::kSurface) continue;  // detail strokes fade with distance
        // A leaf towards its crown's edge keeps only part of its coverage (issue 13 §4).
        float fade = sp.fade;
        if (sp.kind == SpriteKind::kLeaf) {
            const BuiltTree& b = (*shot.trees)[sp.item];
            fade /= crown_edge_fade(shot.scene.families[b.family].leaf_shader,
                                    b.tree().leaves.center_distance[sp.particle]);
        }
        const bool third = std::abs(fade - 1.0f / 3.0f) < 1e-5f;
        const bool two = std::abs(fade - 2.0f / 3.0f) < 1e-5f;
        ASSERT_TRUE(std::abs(fade - 1.0f) < 1e-5f || third || two) << fade;
        partial += third || two;
    }
    EXPECT_GT(partial, 0u);
    EXPECT_GT(set.hidden, 0u);
}

// A moving camera's occlusion rays go to where the eye is over occlusion_frames frames, on a
// lattice fixed to the track's clock: the next frame casts all but one of them again, from the
// same heights, so the share seen changes by at most one ray's worth a frame.
TEST(Sprites, TheNextFrameCastsAllButOneOfTheSameOcclusionRays) {
    SceneDesc scene = lit_scene();
    EXPECT_TRUE(seen_window(scene, still_view(scene), scene.render).cameras.empty());
    scene.fps = 24;
    scene.camera_track = parse_scene(R"({"camera": {"track": [
        {"time": 0, "position": [0, 3, 40], "look_at": [0, 4, -10]},
        {"time": 1, "position": [5, 4, 30], "look_at": [0, 4, -10]},
        {"time": 2, "position": [9, 3, 24], "look_at": [2, 4, -10]}]}})",
                                     "track")
                             .camera_track;
    for (int n : {2, 3, 4, 7}) {
        scene.render.occlusion_frames = n;
        for (int f = 2; f < 45; ++f) {
            const SeenWindow a =
                seen_window(scene, view_at(scene, frame_time(f, 24)), scene.render);
            const SeenWindow b =
                seen_window(scene, view_at(scene, frame_time(f + 1, 24)), scene.render);
            ASSERT_EQ(a.cameras.size(), static_cast<size_t>(n));
            ASSERT_EQ(b.cameras.size(), static_cast<size_t>(n));
            for (int i = 1; i < n; ++i) {
                ASSERT_EQ(a.cameras[i].eye, b.cameras[i - 1].eye) << "n " << n << " frame " << f;
                ASSERT_EQ(a.cameras[i].up, b.cameras[i - 1].up);
                ASSERT_EQ(a.heights[i], b.heights[i - 1]);
            }
            ASSERT_NE(a.cameras[0].eye, b.cameras[n - 1].eye);
            // Centred on the frame: as many eyes before its time as after.
            const glm::dvec3 eye = view_at(scene, frame_time(f, 24)).camera.eye;
            if (n % 2 == 1) {
                EXPECT_EQ(a.cameras[n / 2].eye, eye);
            }
        }
    }
    // All three heights take turns; 1 frame, or a still camera, casts the frame's own rays.
    scene.render.occlusion_frames = 3;
    const SeenWindow w = seen_window(scene, view_at(scene, 0.5), scene.render);
    EXPECT_EQ(std::set<uint8_t>(w.heights.begin(), w.heights.end()).size(), 3u);
    scene.render.occlusion_frames = 1;
    EXPECT_TRUE(seen_window(scene, view_at(scene, 0.5), scene.render).cameras.empty());
}

// Highway picks the vector target at run time; the bytes must not depend on it. Every target
// this build holds and this CPU runs paints a still and three frames of a moving shot to the
// same bits as the first.
TEST(Shot, SameBytesOnEveryVectorTarget) {
    SceneDesc scene = lit_scene(R"({"samples": 4})");
    const Shot still = build_shot(scene);
    scene.camera_track = parse_scene(R"({"camera": {"track": [
        {"time": 0, "position": [0, 3, 40], "look_at": [0, 4, -10]},
        {"time": 1, "position": [5, 4, 30], "look_at": [0, 4, -10]}]}})",
                                     "track")
                             .camera_track;
    const Shot moving = build_shot(scene);
    auto paint_all = [&] {
        std::vector<Frame> frames{paint(still)};
        for (int f : {1, 7, 8})
            frames.push_back(paint_frame(moving, view_at(moving.scene, frame_time(f, 24)),
                                         scene_frame_settings(moving.scene)));
        return frames;
    };
    std::vector<Frame> first;
    int targets = 0;
    for (int64_t target : hwy::SupportedAndGeneratedTargets()) {
        SCOPED_TRACE(hwy::TargetName(target));
        hwy::SetSupportedTargetsForTest(target);
        std::vector<Frame> frames = paint_all();
        if (first.empty()) first = frames;
        for (size_t i = 0; i < frames.size(); ++i)
            EXPECT_TRUE(same_pixels(frames[i], first[i])) << i;
        ++targets;
    }
    hwy::SetSupportedTargetsForTest(0);
    EXPECT_GE(targets, 1);
    RecordProperty("targets", targets);
}

// Left to itself Embree picks the widest instruction set the CPU has, and its BVH and hit tests
// differ with it (4- or 8-wide nodes, FMA or not): on an AVX-512 machine, frames pinned to AVX2
// or to SSE differ from its own in a few hundred values. pleinair pins SSE2, which every x86-64
// CPU runs, so the bytes do not depend on the CPU: the default paints what SSE2 pinned by hand
// does, for frames of a moving camera and of a moving sun.
TEST(Shot, EmbreeIsPinnedToOneInstructionSetForEveryCpu) {
    SceneDesc scene = lit_scene(R"({"samples": 4})");
    scene.camera_track = parse_scene(R"({"camera": {"track": [
        {"time": 0, "position": [0, 3, 40], "look_at": [0, 4, -10]},
        {"time": 1, "position": [5, 4, 30], "look_at": [0, 4, -10]}]}})",
                                     "track")
                             .camera_track;
    SceneDesc sunset = lit_scene(R"({"samples": 4})");
    sunset.sun_track = {SunKey{0, glm::normalize(glm::dvec3(-0.5, 0.6, 0.4))},
                        SunKey{1, glm::normalize(glm::dvec3(0.6, 0.5, -0.3))}};
    auto paint_all = [&] {
        std::vector<Frame> frames;
        const Shot shot = build_shot(scene);
        for (int f : {1, 13, 24})
            frames.push_back(paint_frame(shot, view_at(shot.scene, frame_time(f, 24)),
                                         scene_frame_settings(shot.scene)));
        const Shot sun_shot = build_shot(sunset);
        frames.push_back(paint_frame(sun_shot, view_at(sun_shot.scene, 0.5),
                                     scene_frame_settings(sun_shot.scene)));
        return frames;
    };
    const std::vector<Frame> pinned = paint_all();
    set_ray_device_config("isa=sse2");
    const std::vector<Frame> sse2 = paint_all();
    int moved = 0;  // what the pin prevents, recorded: values that differ with the widest set
    set_ray_device_config("");
    const std::vector<Frame> widest = paint_all();
    set_ray_device_config(kPortableRayDevice);
    for (size_t i = 0; i < pinned.size(); ++i) {
        EXPECT_TRUE(same_pixels(pinned[i], sse2[i])) << i;
        for (size_t k = 0; k < pinned[i].rgba.size(); ++k)
            moved += pinned[i].rgba[k] != widest[i].rgba[k];
    }
    RecordProperty("values_that_differ_with_embree_widest_isa", moved);
}

TEST(DepthOrder, BackToFrontByDistanceFromTheEyeWithTiesByIndex) {
    std::vector<Sprite> s(5);
    const float range[] = {1, 3, 3, 2, 3};
    // The view depth does not decide: turning the camera changes it, not the order.
    const float depth[] = {3, 1, 2, 3, 1};
    for (size_t i = 0; i < s.size(); ++i) s[i].range = range[i], s[i].depth = depth[i];
    EXPECT_EQ(depth_order(s), (std::vector<uint32_t>{1, 2, 4, 3, 0}));
}

// The sorted keys give the order the rule defines (farther first, then by index), over many
// ties, zeros of both signs and ranges a last bit apart.
TEST(DepthOrder, KeysGiveTheOrderOfTheRule) {
    std::vector<Sprite> s(20000);
    uint32_t h = 12345;
    for (size_t i = 0; i < s.size(); ++i) {
        h = h * 1664525u + 1013904223u;
        const float r = static_cast<float>(h >> 24) * 0.25f;  // 256 values: many ties
        s[i].range = (h & 0x100u) ? std::nextafter(r, 1e9f) : r;
        if (r == 0.0f && (h & 0x200u)) s[i].range = -0.0f;
    }
    std::vector<uint32_t> expect(s.size());
    for (size_t i = 0; i < expect.size(); ++i) expect[i] = static_cast<uint32_t>(i);
    std::sort(expect.begin(), expect.end(), [&](uint32_t a, uint32_t b) {
        if (s[a].range != s[b].range) return s[a].range > s[b].range;
        return a < b;
    });
    EXPECT_EQ(depth_order(s), expect);
}

TEST(DepthOrder, TurningTheCameraSwapsNoSprites) {
    // Thesis V.3, Fig. 31: camera-facing sprites ordered by view depth swap as the view turns.
    // From one eye, the order of the sprites both views draw is the same.
    const Shot shot = build_shot(lit_scene());
    const FrameSettings settings = scene_frame_settings(shot.scene);
    const FramePlan plan = plan_frame(shot, settings);
    std::vector<std::vector<uint64_t>> orders;
    for (double turn : {0.0, 0.25}) {
        FrameView view = still_view(shot.scene);
        CameraParams p = shot.scene.camera_params;
        const glm::dvec3 d = p.look_at - p.position;
        p.look_at = p.position + glm::dvec3(d.x * std::cos(turn) - d.z * std::sin(turn), d.y,
                                            d.x * std::sin(turn) + d.z * std::cos(turn));
        ASSERT_EQ(make_camera(p, view.camera), "");
        const FrameLod lod = level_of_detail(shot, view, settings.render);
        const SpriteSet set =
            make_sprites({shot, view, plan, settings.render, lod, shot.sun_rays.get()});
        std::vector<uint64_t> keys;
        for (uint32_t i : depth_order(set.sprites)) keys.push_back(sprite_key(set.sprites[i]));
        orders.push_back(keys);
    }
    std::unordered_set<uint64_t> in_both(orders[1].begin(), orders[1].end());
    std::vector<uint64_t> a, b;
    for (uint64_t k : orders[0])
        if (in_both.count(k)) a.push_back(k);
    const std::unordered_set<uint64_t> in_a(a.begin(), a.end());
    for (uint64_t k : orders[1])
        if (in_a.count(k)) b.push_back(k);
    ASSERT_GT(a.size(), 100u);
    EXPECT_EQ(a, b);
}

TEST(Bins, EveryTileASpriteTouchesListsItInOrder) {
    std::vector<Sprite> s(3);
    s[0].x = 70, s[0].y = 10, s[0].half_w = 10, s[0].half_l = 10;  // tiles 0 and 1 of row 0
    s[1].x = 10, s[1].y = 10, s[1].half_w = 2, s[1].half_l = 2, s[1].range = 5;
    s[2].x = -500, s[2].y = 1e6f, s[2].half_w = 1, s[2].half_l = 1;  // clamped to a corner
    const std::vector<uint32_t> order = depth_order(s);
    const TileBins b = bin_sprites(s, order, 150, 100);
    ASSERT_EQ(b.tiles_x, 3);
    ASSERT_EQ(b.tiles_y, 2);
    EXPECT_EQ(b.bins[0], (std::vector<uint32_t>{1, 0}));  // the far one first
    EXPECT_EQ(b.bins[1], (std::vector<uint32_t>{0}));
    EXPECT_TRUE(b.bins[2].empty());
    EXPECT_EQ(b.bins[3], (std::vector<uint32_t>{2}));
}

// A keyed sun: its scene is built for each frame (its casters face it), nothing of it in the
// shot; frames at two times differ, and a frame does not depend on the one painted before.
TEST(Shot, AMovingSunCastsItsShadowsPerFrame) {
    SceneDesc s = lit_scene();
    s.sun_track = {SunKey{0, glm::normalize(glm::dvec3(-0.5, 0.6, 0.4))},
                   SunKey{1, glm::normalize(glm::dvec3(0.6, 0.5, -0.3))}};
    ShotOptions o;
    o.cache_sun_light = true;  // asked for, but a moving sun cannot be cached
    const Shot shot = build_shot(s, o);
    EXPECT_TRUE(shot.plan.sun_moves);
    EXPECT_FALSE(shot.plan.sun_light);
    EXPECT_FALSE(shot.sun_rays);
    EXPECT_TRUE(shot.view_rays);
    const FrameSettings settings = scene_frame_settings(shot.scene);
    EXPECT_EQ(plan_frame(shot, settings).sun_light, SunLightSource::kFrameScene);
    FrameReport rep;
    const Frame early = paint_frame(shot, view_at(shot.scene, 0.0), settings, &rep);
    EXPECT_GT(rep.shadow_rays, 0u);
    bool built = false;
    for (const auto& p : rep.passes) built |= p.name == "sun scene" && p.ran;
    EXPECT_TRUE(built);
    const Frame late = paint_frame(shot, view_at(shot.scene, 1.0), settings);
    EXPECT_FALSE(same_pixels(early, late)) << "the light moved";
    EXPECT_TRUE(same_pixels(early, paint_frame(shot, view_at(shot.scene, 0.0), settings)));
    // The sun's key at time 0 is the still sun: the same picture as without a track.
    SceneDesc still = lit_scene();
    still.sun_direction = s.sun_track[0].direction;
    EXPECT_TRUE(same_pixels(early, paint(build_shot(still))));
}

// A stroke layer without a stroke: every pixel lets all the light through to what lies under.
StrokeLayer open_layer(const Camera& cam) {
    const size_t npix = static_cast<size_t>(cam.width) * cam.height;
    StrokeLayer open;
    open.width = cam.width, open.height = cam.height, open.cutoff = 1.0f / 2048;
    open.color.assign(3 * npix, 0.0f);
    open.through.assign(npix, 1.0f);
    return open;
}

// The underpainting shades every other cell each way and gives a cell between them their mean
// where they see one surface in one light and colour: against shading every cell, on the small
// Mortefontaine (pond, trees, shadows) and the small forest's edge at 768x432 seen wholly open
// (no stroke over it), the same cells are covered, it shades under half the cells (measured
// 45%), and the colours stay within a mean of 0.001 and a 99.9th percentile of 0.02 (linear;
// measured 0.0001 and 0.005-0.007).
TEST(Composite, TheUnderpaintingsSharedShadingStaysNearShadingEveryCell) {
    for (const char* name : {"mortefontaine-small", "forest-edge-small"}) {
        const Shot shot =
            build_shot(load_scene(test::source_dir() / "tests/golden" / name / "scene.json",
                                  {"/camera/width=768", "/camera/height=432"}));
        const FrameView view = still_view(shot.scene);
        const Camera& cam = view.camera;
        FrameSettings settings = scene_frame_settings(shot.scene);
        const FramePlan plan = plan_frame(shot, settings);
        const StrokeLayer open = open_layer(cam);
        Frame shared = make_frame(cam, false), every = make_frame(cam, false);
        const UnderpaintRays a = paint_underpainting(shot, view, plan, settings.render,
                                                     shot.sun_rays.get(), open, shared);
        const UnderpaintRays b = paint_underpainting(shot, view, plan, settings.render,
                                                     shot.sun_rays.get(), open, every, true);
        EXPECT_EQ(a.camera, b.camera) << name;
        EXPECT_LT(a.shaded * 2, b.shaded) << name;
        std::vector<float> diff;
        double sum = 0;
        for (size_t i = 0; i < shared.rgba.size(); ++i) {
            if (i % 4 == 3) {
                ASSERT_EQ(shared.rgba[i], every.rgba[i]) << name << ": coverage at " << i / 4;
                continue;
            }
            ASSERT_TRUE(std::isfinite(shared.rgba[i]));
            diff.push_back(std::abs(shared.rgba[i] - every.rgba[i]));
            sum += diff.back();
        }
        std::sort(diff.begin(), diff.end());
        const float p999 = diff[diff.size() * 999 / 1000];
        EXPECT_LE(sum / diff.size(), 0.001) << name;
        EXPECT_LE(p999, 0.02f) << name;
    }
}

// The lay-in's tone (issue 52 section 3): render/underpaint_tone_amount takes every dry
// surface's flat colour towards render/underpaint_tone before the atmosphere, and leaves the
// still water its mirror. On the small Mortefontaine at 192x108, wholly open: at amount 1 with
// a red tone the near ground's bottom rows turn red (red over twice green; the ground's own red
// is under 1.5 times its green), the water's pixels (over 2.5% of the frame, measured 4%) keep
// their colour exactly, and amount 0 paints what the scene without the key paints.
TEST(Composite, TheUnderpaintsToneTakesTheDrySurfacesTowardsItAndLeavesTheWater) {
    auto underpaint = [&](const std::vector<std::string>& sets) {
        std::vector<std::string> all = {"/camera/width=192", "/camera/height=108"};
        all.insert(all.end(), sets.begin(), sets.end());
        const Shot shot = build_shot(
            load_scene(test::source_dir() / "tests/golden/mortefontaine-small/scene.json", all));
        const FrameView view = still_view(shot.scene);
        const Camera& cam = view.camera;
        FrameSettings settings = scene_frame_settings(shot.scene);
        const FramePlan plan = plan_frame(shot, settings);
        const StrokeLayer open = open_layer(cam);
        Frame f = make_frame(cam, false);
        paint_underpainting(shot, view, plan, settings.render, shot.sun_rays.get(), open, f, true);
        return f;
    };
    const Frame plain = underpaint({"/render/underpaint_tone_amount=0"});
    const Frame toned =
        underpaint({"/render/underpaint_tone_amount=1", R"(/render/underpaint_tone="#c04020")"});
    EXPECT_EQ(plain.rgba, underpaint({R"(/render/underpaint_tone="#c04020")"}).rgba);
    const int w = plain.width, h = plain.height;
    double r0 = 0, g0 = 0, r1 = 0, g1 = 0;
    for (int y = h - 4; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t i = 4 * (static_cast<size_t>(y) * w + x);
            r0 += plain.rgba[i], g0 += plain.rgba[i + 1];
            r1 += toned.rgba[i], g1 += toned.rgba[i + 1];
        }
    EXPECT_LT(r0, 1.5 * g0) << "the ground's own colour";
    EXPECT_GT(r1, 2 * g1) << "the tone's";
    size_t covered = 0, same = 0;
    for (size_t p = 0; p < plain.rgba.size(); p += 4) {
        if (!(plain.rgba[p] + plain.rgba[p + 1] + plain.rgba[p + 2] > 0.0f)) continue;
        ++covered;
        same += plain.rgba[p] == toned.rgba[p] && plain.rgba[p + 1] == toned.rgba[p + 1] &&
                plain.rgba[p + 2] == toned.rgba[p + 2];
    }
    EXPECT_GT(same, size_t(w) * h / 40) << covered;
    EXPECT_LT(same * 2, covered);
}

// Strokes at least render/one_sample_px wide (the narrower half-width) take one sample a pixel,
// the feather filtered: none in the golden oak's 256x256 frame (the same bytes), many when the
// frame is three times larger, with fewer samples then and a picture within 1.5 levels (RMS,
// 8-bit) of every stroke at 4 samples: 0.34 measured with corot-leaves' old wide feather, 1.21
// with its crisp one (issue 52 §2), whose edges one sample anti-aliases less finely; a threshold
// past every stroke changes nothing.
TEST(Composite, LargeStrokesTakeOneSample) {
    auto paint = [&](const std::vector<std::string>& sets, float px, FrameReport& report) {
        SceneDesc scene =
            load_scene(test::source_dir() / "tests/golden/oak-study/scene.json", sets);
        scene.render.one_sample_px = px;
        const Shot shot = build_shot(scene);
        return frame_srgb8(
            paint_frame(shot, still_view(shot.scene), scene_frame_settings(shot.scene), &report));
    };
    FrameReport a, b;
    EXPECT_EQ(paint({}, 16, a), paint({}, 0, b));
    EXPECT_EQ(a.fragments, b.fragments);
    const std::vector<std::string> large = {"/camera/width=768", "/camera/height=768"};
    const auto one = paint(large, 16, a), every = paint(large, 0, b);
    EXPECT_LT(a.fragments * 4, b.fragments * 3);
    EXPECT_EQ(paint(large, 1000, a), every);
    ASSERT_EQ(one.size(), every.size());
    const test::ByteDiff d = test::byte_diff(one, every);
    EXPECT_GT(d.differ, one.size() / 100);
    EXPECT_LE(d.rms, 1.5);
}

// The stages under the strokes on their own: the background and the underpainting only where a
// stroke layer lets light through (every underpainting cell when depth is asked for), and the
// composite C + T * what lies under.
TEST(Composite, UnderTheStrokesOnlyWhereLightGetsThrough) {
    const Shot shot = build_shot(lit_scene());
    const FrameView view = still_view(shot.scene);
    const Camera& cam = view.camera;
    FrameSettings settings = scene_frame_settings(shot.scene);
    const FramePlan plan = plan_frame(shot, settings);
    const size_t npix = static_cast<size_t>(cam.width) * cam.height;
    StrokeLayer open, covered;
    for (StrokeLayer* l : {&open, &covered}) {
        l->width = cam.width, l->height = cam.height, l->cutoff = 1.0f / 2048;
        l->color.assign(3 * npix, 0.0f);
    }
    open.through.assign(npix, 1.0f);
    covered.through.assign(npix, 0.0f);
    covered.color.assign(3 * npix, 0.25f);

    Frame a = make_frame(cam, false), b = make_frame(cam, false);
    paint_background(shot.scene, cam, open, a);
    paint_background(shot.scene, cam, covered, b);
    EXPECT_GT(a.rgba[3], 0.0f);
    for (float v : b.rgba) ASSERT_EQ(v, 0.0f) << "nothing painted under covered pixels";
    const uint64_t all =
        paint_underpainting(shot, view, plan, settings.render, shot.sun_rays.get(), open, a).camera;
    const uint64_t none =
        paint_underpainting(shot, view, plan, settings.render, shot.sun_rays.get(), covered, b)
            .camera;
    const uint64_t cells = static_cast<uint64_t>(std::ceil(cam.width * 0.5)) *
                           static_cast<uint64_t>(std::ceil(cam.height * 0.5));
    EXPECT_EQ(all, cells);
    EXPECT_EQ(none, 0u);
    FramePlan with_depth = plan;
    with_depth.aovs = true;
    Frame c = make_frame(cam, true);
    EXPECT_EQ(paint_underpainting(shot, view, with_depth, settings.render, shot.sun_rays.get(),
                                  covered, c)
                  .camera,
              cells);
    // One pixel half covered: C + T * under.
    Frame d = a;
    StrokeLayer half = open;
    half.through[0] = 0.5f;
    half.color[0] = 0.1f;
    composite_strokes(half, plan, RenderSettings{}, d);
    EXPECT_FLOAT_EQ(d.rgba[0], 0.1f + 0.5f * a.rgba[0]);
    EXPECT_FLOAT_EQ(d.rgba[4], a.rgba[4]);  // an open pixel keeps what lies under
    composite_strokes(covered, plan, RenderSettings{}, b);
    EXPECT_EQ(b.rgba[0], 0.25f);
    EXPECT_EQ(b.rgba[3], 1.0f);
}

// Strokes composited nearest first stop where less than coverage_cutoff of the light is left:
// the frame differs from painting every stroke by at most that (plus rounding), and far fewer
// fragments are shaded. A stack of 300 strokes on one spot is the hard case.
TEST(Composite, CoverageCutoffBoundsTheErrorOfSkippedStrokes) {
    SceneDesc s = parse_scene(R"({"camera": {"position": [0, 0, 10], "look_at": [0, 0, 0],
        "fov": 20, "width": 64, "height": 48},
        "families": {"oak": {"preset": "oak"}}, "trees": []})",
                              "test");
    BuiltTree t;
    LeafParticles& L = t.tree().leaves;
    for (int i = 0; i < 300; ++i) {
        L.position.push_back({0.01f * (i % 7), 0.01f * (i % 5), -0.01f * i});
        L.normal.push_back({0, 0, 1});
        L.branch_distance.push_back(0.5f);
        L.center_distance.push_back(0.5f);
        L.label.push_back((i + 0.5f) / 300);
        L.tree_id.push_back(0);
        L.fade_begin.push_back(2);
        L.fade_end.push_back(3);
    }
    s.families[0].leaf_shader.sprite_size = 3;
    s.families[0].leaf_shader.max_stroke_opacity = 0.97f;
    s.render.coverage_cutoff = 0;
    FrameReport all, cut;
    const Frame every = paint_still(s, {t}, true, &all);
    s.render.coverage_cutoff = 1.0f / 2048;
    const Frame skipped = paint_still(s, {t}, true, &cut);
    EXPECT_LT(cut.fragments * 2, all.fragments) << "the strokes behind were skipped";
    float worst = 0;
    for (size_t i = 0; i < every.rgba.size(); ++i)
        worst = std::max(worst, std::abs(every.rgba[i] - skipped.rgba[i]));
    EXPECT_GT(worst, 0.0f);
    EXPECT_LE(worst, 1.0f / 2048 + 1e-5f);
    EXPECT_EQ(every.depth, skipped.depth);  // the nearest stroke over half opaque, either way
    EXPECT_EQ(every.object_id, skipped.object_id);
    for (size_t i = 0; i < every.alpha.size(); ++i)
        EXPECT_NEAR(every.alpha[i], skipped.alpha[i], 1.0f / 2048 + 1e-6f);
}

// Soft depth order (V.3, Fig. 31): two overlapping strokes whose eye distances cross as the
// camera moves blend from one order to the other over order_blend_frames instead of swapping
// in one frame. A recedes and B nears at 0.01 a frame each; they cross at frame 0.
struct CrossingStrokes {
    Shot shot = build_shot(parse_scene(R"({"camera": {"position": [0, 0, 10],
        "look_at": [0, 0, 0], "fov": 20, "width": 64, "height": 48},
        "families": {"oak": {"preset": "oak"}}, "trees": []})",
                                       "test"));

    // The stroke layer at frame n (rates scaled by `moving`: 0 is a still camera).
    StrokeLayer at(float n, float blend_frames, float moving = 1) const {
        SpriteSet set;
        for (int i = 0; i < 2; ++i) {
            Sprite sp;
            sp.x = 32, sp.y = 24, sp.half_w = 14, sp.half_l = 14;
            sp.material = shot.materials.leaf(0);
            sp.k.lightness = i == 0 ? 0.15f : 0.9f;  // visibly different
            sp.k.offset_s = 0.3f * i;
            const float dir = i == 0 ? 1.0f : -1.0f;
            sp.range = 10 + 0.01f * dir * n;
            sp.swap_speed = 0.01f * moving;  // their ranges change by 0.02 a frame
            set.sprites.push_back(sp);
        }
        FrameSettings fs = scene_frame_settings(shot.scene);
        fs.render.order_blend_frames = blend_frames;
        const FramePlan plan = plan_frame(shot, fs);
        Frame frame = make_frame(still_view(shot.scene).camera, false);
        const TileBins bins = bin_sprites(set.sprites, depth_order(set.sprites), 64, 48);
        return paint_strokes(shot, set, bins, plan, fs.render, frame);
    }
};

double mean_difference(const StrokeLayer& a, const StrokeLayer& b) {
    double d = 0;
    for (size_t i = 0; i < a.color.size(); ++i) d += std::abs(a.color[i] - b.color[i]);
    return d / static_cast<double>(a.color.size());
}

TEST(Composite, StrokesWhoseDistancesCrossSwapOverFrames) {
    const CrossingStrokes c;
    // The two plain orders, and how far apart they are.
    const StrokeLayer a_front = c.at(-4, 0), b_front = c.at(4, 0);
    const double swap = mean_difference(a_front, b_front);
    ASSERT_GT(swap, 0.002);  // a mean over the frame: the strokes cover part of it
    // Beyond the window the order is plain, to the byte.
    for (float n : {-4.0f, -3.0f, 3.0f, 4.0f}) {
        const StrokeLayer soft = c.at(n, 5), hard = c.at(n, 0);
        EXPECT_EQ(soft.color, hard.color) << "frame " << n;
        EXPECT_EQ(soft.through, hard.through) << "frame " << n;
    }
    // Within it the picture moves from one order to the other by less than a third of the
    // swap in any one frame, and is the even mix of both at the crossing.
    double steepest = 0;
    for (float n = -4; n < 4; n += 1)
        steepest = std::max(steepest, mean_difference(c.at(n, 5), c.at(n + 1, 5)) / swap);
    EXPECT_LT(steepest, 1.0 / 3.0);
    EXPECT_GT(steepest, 0.2);  // it does swap, over about five frames
    const StrokeLayer mid = c.at(0, 5);
    for (size_t i = 0; i < mid.color.size(); ++i)
        ASSERT_NEAR(mid.color[i], 0.5f * (a_front.color[i] + b_front.color[i]), 1e-5f);
    // Without the blend the swap happens between two frames, whole.
    EXPECT_NEAR(mean_difference(c.at(-0.5f, 0), c.at(0.5f, 0)), swap, 1e-6);
    // Light let through does not depend on the order.
    for (size_t i = 0; i < mid.through.size(); ++i)
        ASSERT_NEAR(mid.through[i], a_front.through[i], 1e-6f);
}

TEST(Composite, AStillCameraKeepsThePlainOrder) {
    const CrossingStrokes c;
    for (float n : {-1.0f, -0.2f, 0.2f, 1.0f}) {
        const StrokeLayer soft = c.at(n, 5, 0), hard = c.at(n, 0, 0);
        EXPECT_EQ(soft.color, hard.color) << "frame " << n;
    }
}

}  // namespace
}  // namespace pleinair
