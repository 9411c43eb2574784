// Still water's mirror (pipeline/frame/reflection.h) and the look's measures
// (pipeline/bench/look_measures.h): the Fresnel curve, the measures on images made to have a known
// answer, and the small Mortefontaine's pond mirroring its far bank only with reflections on.
#include "pipeline/frame/reflection.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "pipeline/bench/look_measures.h"
#include "pipeline/frame/lod.h"
#include "pipeline/frame/mirror_memo.h"
#include "pipeline/frame/paint_frame.h"
#include "pipeline/shot/shot.h"
#include "test_util.h"

namespace pleinair {
namespace {

TEST(Reflection, WaterReflectsLittleLookingDownAndAllAtGrazing) {
    EXPECT_NEAR(water_reflectance(1.0f), 0.02f, 1e-6f);
    EXPECT_NEAR(water_reflectance(0.0f), 1.0f, 1e-6f);
    EXPECT_EQ(water_reflectance(-0.3f), water_reflectance(0.3f));  // either side of the plane
    float last = 2;
    for (float c = 0; c <= 1.0001f; c += 0.05f) {
        const float r = water_reflectance(c);
        EXPECT_LT(r, last);
        last = r;
    }
    EXPECT_TRUE(std::isfinite(water_reflectance(std::nanf(""))));
}

TEST(Look, TextureSeesEdgesInsideTheRegionOnly) {
    const int w = 40, h = 30;
    std::vector<float> flat(w * h, 50.0f), checker(w * h);
    std::vector<uint8_t> all(w * h, 1), left(w * h, 0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            checker[y * w + x] = ((x / 4 + y / 4) % 2) ? 60.0f : 40.0f;
            left[y * w + x] = x < w / 2;
        }
    EXPECT_EQ(brush_texture(flat, w, h, all, 2), 0.0);
    EXPECT_GT(brush_texture(checker, w, h, all, 2), 5.0);
    // A step at the region's edge is not texture: only whole windows inside count.
    std::vector<float> step(w * h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) step[y * w + x] = x < w / 2 ? 30.0f : 80.0f;
    uint64_t n = 0;
    EXPECT_EQ(brush_texture(step, w, h, left, 2, &n), 0.0);
    EXPECT_EQ(n, uint64_t((w / 2 - 4) * (h - 4)));
    EXPECT_EQ(brush_texture(step, w, h, std::vector<uint8_t>(w * h, 0), 8), 0.0);
}

TEST(Look, MirrorCorrelationOfAMirroredImageIsOne) {
    const int w = 32, h = 40, shore = 20;
    std::vector<float> l(w * h);
    std::vector<uint8_t> water(w * h, 0);
    for (int y = 0; y < shore; ++y)
        for (int x = 0; x < w; ++x) l[y * w + x] = 40.0f + 20.0f * std::sin(0.7f * x + 0.3f * y);
    for (int y = shore; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            l[y * w + x] = 0.5f * l[(2 * shore - 1 - y) * w + x] + 10.0f;  // dimmer, mirrored
            water[y * w + x] = 1;
        }
    uint64_t pairs = 0;
    EXPECT_NEAR(mirror_correlation(l, w, h, water, &pairs), 1.0, 1e-9);
    EXPECT_EQ(pairs, uint64_t(w * (h - shore)));
    for (int y = shore; y < h; ++y)
        for (int x = 0; x < w; ++x) l[y * w + x] = 30.0f + 5.0f * ((x * 7 + y * 13) % 5);
    EXPECT_LT(std::abs(mirror_correlation(l, w, h, water)), 0.2);
}

// A wall 50 m away stands on still water; the camera looks at it from 2 m above the water.
// Painted as a glass mirror (the water's L* a dimmed copy of the wall's at the mirrored point),
// the water matches what it mirrors at every scale; painted as noise, it does not. The mirror
// about the shore's row, with the wall set 10 m behind the shore, misses it.
TEST(Look, AGlassMirrorMatchesWhatItMirrorsWhereverTheBankStands) {
    CameraParams cp;
    cp.position = {0, 2, 0}, cp.look_at = {0, 2, -50}, cp.fov = 30;
    cp.width = 160, cp.height = 120;
    Camera cam;
    ASSERT_EQ(make_camera(cp, cam), "");
    const int w = cp.width, h = cp.height;
    const double shore = 40, wall = 50;
    auto pattern = [](const glm::dvec3& p) {  // the wall's L*: bands 3 m apart, faint stripes
        return float(40.0 + 30.0 * std::sin(p.y * 2.0) + 8.0 * std::sin(p.x * 1.3));
    };
    Frame f;
    f.width = w, f.height = h, f.has_aovs = true;
    f.rgba.assign(size_t(4) * w * h, 1.0f);
    f.depth.assign(size_t(w) * h, std::numeric_limits<float>::max());
    f.object_id.assign(size_t(w) * h, 7.0f);  // every pixel the water's strokes' id
    std::vector<float> l(size_t(w) * h, 90.0f), noise = l;
    std::vector<uint8_t> water(size_t(w) * h, 0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t i = size_t(y) * w + x;
            const glm::dvec3 d = ray_direction(cam, x + 0.5, y + 0.5);
            const double to_wall = wall / -d.z;
            glm::dvec3 p = cam.eye + d * to_wall;
            if (d.y < 0 && cam.eye.y / -d.y < to_wall) {  // the water, then the bank
                const double t = cam.eye.y / -d.y;
                const glm::dvec3 q = cam.eye + d * t;
                if (-q.z < shore) {
                    water[i] = 1;
                    // The glass mirror: the eye's ray reflected meets the wall at height -p.y.
                    glm::dvec3 m = p;
                    m.y = -m.y;
                    l[i] = 0.6f * pattern(m) + 8.0f;
                    noise[i] = float((x * 37 + y * 91) % 17) * 4.0f;
                    f.depth[i] = float(t * glm::dot(d, cam.forward));
                    continue;
                }
                p = q;  // the bank between the shore and the wall, flat at the water's level
            }
            if (p.y >= 0) {
                l[i] = noise[i] = pattern(p);
                f.depth[i] = float(glm::length(p - cam.eye) * glm::dot(d, cam.forward));
            }
        }
    const std::vector<uint32_t> src = mirror_sources(f, cam, 0.0, water, 7.0f);
    const MirrorMatch glass = mirror_match(f, l, src);
    EXPECT_GT(glass.pairs, 1000u);
    EXPECT_GT(glass.pixels, 0.95);
    EXPECT_GT(glass.forms, 0.95);
    EXPECT_LT(std::abs(mirror_match(f, noise, src).pixels), 0.15);
    EXPECT_LT(mirror_correlation(l, w, h, water), 0.5) << "the shore's row is not the wall's foot";
    for (size_t j = 0; j < src.size(); ++j)
        if (src[j]) {
            ASSERT_TRUE(water[j]) << j;
            ASSERT_FALSE(water[src[j] - 1]) << j;
        }
}

TEST(Look, FlatRunsAreLongOnAGradientAndShortOnNoise) {
    Frame f;
    f.width = 64, f.height = 4;
    f.rgba.assign(4 * 64 * 4, 1.0f);
    for (int x = 0; x < 64; ++x)
        for (int y = 0; y < 4; ++y)
            for (int c = 0; c < 3; ++c) f.rgba[4 * (y * 64 + x) + c] = 0.5f + 0.001f * x;
    const std::vector<uint8_t> all(64 * 4, 1);
    EXPECT_GT(mean_flat_run(f, all), 4.0);
    for (int i = 0; i < 64 * 4; ++i) f.rgba[4 * i] = (i % 2) ? 0.2f : 0.6f;
    EXPECT_EQ(mean_flat_run(f, all), 1.0);
}

TEST(Reflection, ThePondMirrorsItsFarBankOnlyWithReflections) {
    const auto file =
        test::source_dir() / "tests" / "golden" / "mortefontaine-small" / "scene.json";
    auto measure = [&](const std::vector<std::string>& set, FrameReport* rep) {
        const Shot shot = build_shot(load_scene(file, set));
        const FrameView view = still_view(shot.scene);
        const Frame f = paint_frame(shot, view, scene_frame_settings(shot.scene, true), rep);
        for (float v : f.rgba) EXPECT_TRUE(std::isfinite(v));
        const LookRegions r = look_regions(shot, view, f);
        uint64_t pairs = 0;
        const double c = mirror_correlation(frame_lightness(f), f.width, f.height, r.water, &pairs);
        EXPECT_GT(pairs, 300u);
        return c;
    };
    FrameReport on, off;
    const double with = measure({}, &on), without = measure({"/water/reflection=0"}, &off);
    EXPECT_GT(on.reflection_rays, 0u);
    EXPECT_EQ(off.reflection_rays, 0u);
    EXPECT_GT(with, without + 0.1) << with << " vs " << without;
}

// A known object: a dark post standing on the far bank of the small Mortefontaine's pond, seen
// low across the water. With reflections on, the water right under the post darkens over about
// the post's height, upside down (from the shore downwards); water beside it does not, and
// without reflections nothing does. A mirror showing only the sky passes the correlation test
// above; it fails this.
TEST(Reflection, APostOnTheFarBankStandsUpsideDownInThePond) {
    const auto file =
        test::source_dir() / "tests" / "golden" / "mortefontaine-small" / "scene.json";
    struct Painted {
        Frame f;
        std::vector<float> l;
        std::vector<uint8_t> water;
        float post_id = 0;
    };
    auto paint = [&](int reflection) {
        const Shot shot = build_shot(load_scene(
            file, {"/rocks/0/position=[-6,0,-45]", "/rocks/0/radius=5",
                   "/rocks/0/scale=[0.1,1.2,0.1]", "/families={}", "/trees=[]", "/groups=[]",
                   "/camera/position=[-4,2.5,10]", "/camera/look_at=[-6,0,-60]", "/camera/fov=30",
                   "/water/reflection=" + std::to_string(reflection)}));
        const FrameView view = still_view(shot.scene);
        Painted p;
        p.f = paint_frame(shot, view, scene_frame_settings(shot.scene, true));
        p.l = frame_lightness(p.f);
        p.water = look_regions(shot, view, p.f).water;
        p.post_id = float(0x10000u + shot.scene.rocks[0].material);
        return p;
    };
    const Painted on = paint(1), off = paint(0);
    const int w = on.f.width, h = on.f.height;
    // The post's columns and its top and bottom rows, from its strokes' ids.
    int x0 = w, x1 = -1, top = h, bottom = -1;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            if (on.f.object_id[size_t(y) * w + x] == on.post_id)
                x0 = std::min(x0, x), x1 = std::max(x1, x), top = std::min(top, y),
                bottom = std::max(bottom, y);
    ASSERT_GE(x1, x0) << "the post is in view";
    const int height = bottom - top + 1;
    ASSERT_GE(height, 10);
    ASSERT_LE(x1 - x0, 12) << "a post, not a wall";
    // Mean L* of the water in columns [a, b] over rows [r0, r1].
    auto mean = [&](const Painted& p, int a, int b, int r0, int r1) {
        double sum = 0;
        int n = 0;
        for (int y = std::max(r0, 0); y <= std::min(r1, h - 1); ++y)
            for (int x = std::max(a, 0); x <= std::min(b, w - 1); ++x)
                if (p.water[size_t(y) * w + x]) sum += p.l[size_t(y) * w + x], ++n;
        return n ? sum / n : -1.0;
    };
    // The first half of the mirrored post below the shore, and the same rows beside it.
    const int r0 = bottom + 1, r1 = bottom + height / 2;
    const int beside = x1 + 3 * (x1 - x0 + 1) + 6;
    const double under_on = mean(on, x0, x1, r0, r1), under_off = mean(off, x0, x1, r0, r1);
    const double beside_on = mean(on, beside, beside + (x1 - x0), r0, r1);
    const double beside_off = mean(off, beside, beside + (x1 - x0), r0, r1);
    ASSERT_GT(under_on, 0);
    ASSERT_GT(under_off, 0);
    ASSERT_GT(beside_on, 0);
    ASSERT_GT(beside_off, 0);
    // The mirror lightens the whole pond (it shows the sky); under the post it shows the post.
    const double dark_on = beside_on - under_on, dark_off = beside_off - under_off;
    EXPECT_GT(dark_on, dark_off + 6)
        << "the water under the post, against the water beside it: " << dark_on
        << " L* darker with reflections, " << dark_off << " without";
    // Upside down: the dark reaches down about the post's height, not far past it.
    const double far_on = mean(on, x0, x1, bottom + 2 * height, bottom + 3 * height);
    const double far_beside =
        mean(on, beside, beside + (x1 - x0), bottom + 2 * height, bottom + 3 * height);
    if (far_on > 0 && far_beside > 0) {
        EXPECT_LT(far_beside - far_on, 0.5 * dark_on) << "dark far below the post's reflection";
    }
}

// mortefontaine-walk small, for the mirrors of a moving camera (one occlusion ray a stroke:
// which strokes show does not matter here, and the tests run under the sanitizers too; 4
// mirror rays a stroke, not 16: the lattice and the memo are the same whatever the count).
Shot small_walk() {
    return build_shot(
        load_scene(test::source_dir() / "presets" / "scenes" / "mortefontaine-walk.json",
                   {"/camera/width=160", "/camera/height=90", "/render/occlusion_frames=1",
                    "/water/mirror_rays=4"}));
}

// A moving camera's mirrors on a lattice of 4 frames: each water stroke's colour is the line
// between what it mirrors from the eye at the lattice frames either side of the frame, those
// traced from exactly the eye the frame there has; the Fresnel share is the frame's own.
TEST(Reflection, AMovingCamerasMirrorIsLinearBetweenItsLatticeFrames) {
    const Shot shot = small_walk();
    const FrameSettings fs = scene_frame_settings(shot.scene);
    const double fps = shot.scene.fps;
    const int K = 4, f = 40;
    const FrameView view = view_at(shot.scene, frame_time(f, fps));
    ASSERT_GT(view.eye_speed, 0.0);
    const FramePlan plan = plan_frame(shot, fs);
    ASSERT_TRUE(plan.reflections);
    const FrameLod lod = level_of_detail(shot, view, fs.render);
    SpriteSet water = make_sprites({shot, view, plan, fs.render, lod, shot.sun_rays.get()});
    const MaterialId wm = shot.materials.surface(shot.scene.water.material);
    std::erase_if(water.sprites, [&](const Sprite& sp) {
        return !(sp.kind == SpriteKind::kSurface && sp.material == wm);
    });
    ASSERT_GT(water.sprites.size(), 100u);

    const MirrorLattice lattice = mirror_lattice(shot.scene, view, K);
    ASSERT_EQ(lattice.frames, K);
    EXPECT_EQ(lattice.base, f - 1);
    EXPECT_EQ(lattice.u, double(f - 1));
    EXPECT_EQ(mirror_lattice(shot.scene, still_view(shot.scene), K).frames, 1) << "a still";
    const MirrorContext c = mirror_context(shot, view, plan, fs.render, shot.sun_rays.get());
    SpriteSet on = water;
    const ReflectionReport rep = add_reflections(c, on, &lattice);
    EXPECT_EQ(rep.strokes, water.sprites.size());

    // Each lattice frame's own mirrors (frame g is lattice time g - 1), and what the frame's
    // Fresnel share makes of a colour.
    const size_t trees = shot.trees->size();
    auto particle = [&](const Sprite& sp) -> std::pair<const SurfaceParticles&, size_t> {
        return {shot.land->chunks[sp.item - trees], sp.particle};
    };
    std::vector<SpriteSet> exact;
    std::vector<FrameView> views;
    for (int g = f - K + 1; g <= f + K; ++g)
        views.push_back(view_at(shot.scene, frame_time(g, fps)));
    for (const FrameView& v : views) {
        SpriteSet e = water;
        add_reflections(mirror_context(shot, v, plan, fs.render, shot.sun_rays.get()), e);
        exact.push_back(std::move(e));
    }
    auto share = [&](const FrameView& v, const Sprite& sp) {
        const auto [S, j] = particle(sp);
        StrokeConstants k;
        set_mirror(c, Color(1.0f), S.normal(j),
                   glm::normalize(glm::dvec3(S.position[j]) - v.camera.eye), k);
        return k.mirror.x;
    };
    int phases[K] = {};
    for (size_t i = 0; i < water.sprites.size(); ++i) {
        const Sprite& sp = on.sprites[i];
        const auto [S, j] = particle(sp);
        const int64_t phase = mirror_phase(S.label[j], K);
        ASSERT_GE(phase, 0);
        ASSERT_LT(phase, K);
        ++phases[phase];
        const int64_t m0 = (f - 1) - (((f - 1 - phase) % K) + K) % K;
        const size_t a = size_t(m0 - (f - K)), b = a + K;  // their places in `views`
        const float w = float(f - 1 - m0) / K;
        if (w == 0.0f) {  // on its lattice: the frame's own mirror, to the bit
            EXPECT_EQ(sp.k.mirror, exact[a].sprites[i].k.mirror) << i;
            EXPECT_EQ(sp.k.mirror_keep, exact[a].sprites[i].k.mirror_keep) << i;
            continue;
        }
        const Color s0 = exact[a].sprites[i].k.mirror / share(views[a], sp);
        const Color s1 = exact[b].sprites[i].k.mirror / share(views[b], sp);
        const Color want = (s0 + w * (s1 - s0)) * share(view, sp);
        for (int ch = 0; ch < 3; ++ch)
            EXPECT_NEAR(sp.k.mirror[ch], want[ch], 1e-5f + 1e-4f * want[ch]) << i << " " << ch;
        EXPECT_EQ(sp.k.mirror_keep, exact[K - 1].sprites[i].k.mirror_keep) << "the frame's share";
    }
    for (int p = 0; p < K; ++p) EXPECT_GT(phases[p], int(water.sprites.size()) / (2 * K)) << p;
}

// What the water does with what it mirrors (set_mirror): the colour greyed to
// /water/mirror_saturation with its luminance kept, the water's own lightness lowered by the
// share the mirror takes (its dark body), and nothing more where it does not mirror. The share
// is /water/reflection times Fresnel's reflectance taken /water/silver of the way to 1: with
// silver 1 the water mirrors as much looking straight down as at a grazing angle.
TEST(Reflection, AMirrorIsGreyedAndTheWaterDarkensWhereItMirrors) {
    for (auto [saturation, silver] : {std::pair{1.0f, 0.0f}, {0.6f, 0.8f}, {0.0f, 1.0f}}) {
        const Shot shot = build_shot(
            load_scene(test::source_dir() / "presets" / "scenes" / "mortefontaine-walk.json",
                       {"/camera/width=160", "/camera/height=90",
                        "/water/mirror_saturation=" + std::to_string(saturation),
                        "/water/silver=" + std::to_string(silver)}));
        const FrameSettings fs = scene_frame_settings(shot.scene);
        const FrameView view = view_at(shot.scene, 0.0);
        const MirrorContext c =
            mirror_context(shot, view, plan_frame(shot, fs), fs.render, shot.sun_rays.get());
        const Color seen(0.05f, 0.4f, 0.1f);
        const glm::vec3 up(0, 1, 0);
        for (double down : {0.05, 0.5, 0.99}) {  // grazing, oblique, looking straight down
            StrokeConstants k;
            k.lightness = 0.8f;
            const glm::dvec3 dir = glm::normalize(glm::dvec3(1.0, -down, 0.0));
            set_mirror(c, seen, up, dir, k);
            const float fresnel = water_reflectance(float(glm::dot(dir, glm::dvec3(up))));
            const float amount =
                shot.scene.water.reflection * (fresnel + (1.0f - fresnel) * silver);
            EXPECT_NEAR(k.lightness, 0.8f * (1.0f - amount), 1e-6f) << silver << " " << down;
            if (silver == 1.0f) {
                EXPECT_NEAR(k.lightness, 0.8f * (1.0f - shot.scene.water.reflection), 1e-6f);
            }
            // The mirrored colour over its share: its luminance kept, its spread scaled.
            const float lum = luminance(k.mirror), want = luminance(seen);
            const float scale = lum / want;
            EXPECT_NEAR(k.mirror.x / scale, want + saturation * (seen.x - want), 1e-4f);
            EXPECT_NEAR(k.mirror.y / scale, want + saturation * (seen.y - want), 1e-4f);
        }
    }
}

// The leaves the water mirrors keep the haze of where they stand (mirror_context's foliage):
// near the atmosphere's start they are the families' leaf palettes in shade, far off they take
// the haze's colour as their own strokes do; without an atmosphere they are one colour.
TEST(Reflection, MirroredLeavesKeepTheHazeOfTheirDistance) {
    auto context_foliage = [](bool atmosphere) {
        const Shot shot =
            build_shot(load_scene(test::source_dir() / "presets" / "scenes" / "mortefontaine.json",
                                  {"/camera/width=160", "/camera/height=90"}));
        const FrameSettings fs = scene_frame_settings(shot.scene);
        const FrameView view = view_at(shot.scene, 0.0);
        FramePlan plan = plan_frame(shot, fs);
        EXPECT_TRUE(plan.atmosphere);
        plan.atmosphere = atmosphere;  // as a plan for a scene without one
        const MirrorContext c = mirror_context(shot, view, plan, fs.render, shot.sun_rays.get());
        const auto& a = shot.scene.atmosphere;
        std::vector<Color> out;
        for (float depth : {0.0f, a.near_distance, 0.5f * (a.near_distance + a.far_distance),
                            a.far_distance, 2.0f * a.far_distance})
            out.push_back(mirrored_foliage(c, depth));
        Color shade(0.0f);
        for (const Family& f : shot.scene.families) shade += palette_lookup(f.leaf_palette, 0.3f);
        out.push_back(shade / float(shot.scene.families.size()));
        return out;
    };
    const std::vector<Color> hazy = context_foliage(true), clear = context_foliage(false);
    const Color shade = hazy.back();
    for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(hazy[0][k], shade[k], 1e-5f) << "before the haze starts";
        EXPECT_NEAR(hazy[1][k], shade[k], 1e-5f);
        EXPECT_EQ(hazy[3][k], hazy[4][k]) << "the haze is full at its far distance";
        for (size_t i = 0; i + 1 < clear.size(); ++i) EXPECT_EQ(clear[i][k], shade[k]);
    }
    // Lighter and bluer with distance (the scene's haze is a light blue grey).
    EXPECT_GT(luminance(hazy[2]), luminance(shade) * 1.2f);
    EXPECT_GT(luminance(hazy[3]), luminance(hazy[2]));
    EXPECT_GT(hazy[3].z / hazy[3].y, shade.z / shade.y);
    for (const Color& c : hazy)
        for (int k = 0; k < 3; ++k) EXPECT_TRUE(std::isfinite(c[k]));
}

// Frames painted in order with the mirrors kept from the frames before are the frames painted
// alone, and trace a fraction of their mirrors; the lattice changes a still nothing.
TEST(Reflection, MirrorsKeptFromFrameToFramePaintTheFramesPaintedAlone) {
    const Shot shot = small_walk();
    MirrorMemo memo;
    uint64_t kept_rays = 0, alone_rays = 0;
    // Three frames show the memo kept and reused as five did (the first traces both lattice
    // times, the next two a quarter of one), at 60% of the time (CI's time, issue 51).
    for (int f = 30; f < 33; ++f) {
        SCOPED_TRACE(f);
        const FrameView view = view_at(shot.scene, frame_time(f, shot.scene.fps));
        FrameSettings fs = scene_frame_settings(shot.scene);
        FrameReport alone, kept;
        const Frame a = paint_frame(shot, view, fs, &alone);
        fs.mirror_memo = &memo;
        const Frame b = paint_frame(shot, view, fs, &kept);
        EXPECT_EQ(a.rgba, b.rgba);
        alone_rays += alone.reflection_rays, kept_rays += kept.reflection_rays;
    }
    EXPECT_GT(kept_rays, 0u);
    // Alone, a frame traces two lattice frames a stroke; in order, a quarter of one after the
    // first.
    EXPECT_LT(kept_rays * 2, alone_rays);

    FrameSettings fs = scene_frame_settings(shot.scene), one = fs;
    one.render.reflection_frames = 1;
    const FrameView still = still_view(shot.scene);
    EXPECT_EQ(paint_frame(shot, still, fs).rgba, paint_frame(shot, still, one).rgba);
}

}  // namespace
}  // namespace pleinair
