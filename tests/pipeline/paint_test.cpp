// The still painter: determinism across threads, finite buffers, the frame plan, and the hard
// cases of the issue (particles at or behind the camera, huge and zero-size sprites, a limb seen
// end-on, one-colour palettes, equal feather thresholds, an empty scene, a camera looking
// straight up or down).
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <glm/geometric.hpp>
#include <limits>

#include "pipeline/frame/background.h"
#include "pipeline/frame/composite.h"
#include "pipeline/frame/paint_frame.h"
#include "pipeline/frame/sprites.h"
#include "pipeline/output/image_io.h"
#include "test_util.h"

namespace pleinair {
namespace {

namespace fs = std::filesystem;

std::string scene_text(const std::string& camera, const std::string& trees,
                       const std::string& extra = "") {
    return R"({"camera": )" + camera + R"(,
        "atmosphere": {"near": 10, "far": 120},
        "render": {"samples": 4},
        "families": {"oak": {"preset": "oak"}, "birch": {"preset": "birch"}},
        "trees": )" +
           trees + extra + "}";
}

const char* kCamera =
    R"({"position": [0, 6, 40], "look_at": [0, 7, 0], "fov": 40, "width": 96, "height": 64})";
const char* kTrees =
    R"([{"family": "oak", "seed": 1, "position": [-6, 0, 0]},
        {"family": "birch", "seed": 2, "position": [8, 0, -20], "rotation": 90}])";

void expect_finite(const Frame& f) {
    for (float v : f.rgba) ASSERT_TRUE(std::isfinite(v));
    for (const auto* aov : {&f.depth, &f.object_id, &f.alpha, &f.lightness})
        for (float v : *aov) ASSERT_TRUE(std::isfinite(v));
}

Frame paint(const SceneDesc& s, bool aovs = false, FrameReport* rep = nullptr) {
    return paint_still(s, aovs, rep);
}

FramePlan plan_of(const SceneDesc& s) { return plan_frame(build_shot(s), scene_frame_settings(s)); }

TEST(Paint, SameBytesOnOneAndTwoThreads) {
    SceneDesc s = parse_scene(scene_text(kCamera, kTrees), "test");
    Frame one, two;
    tbb::task_arena(1).execute([&] { one = paint(s, true); });
    tbb::task_arena(2).execute([&] { two = paint(s, true); });
    ASSERT_EQ(one.rgba.size(), two.rgba.size());
    EXPECT_EQ(0, std::memcmp(one.rgba.data(), two.rgba.data(), one.rgba.size() * sizeof(float)));
    EXPECT_EQ(one.depth, two.depth);
    EXPECT_EQ(one.object_id, two.object_id);
    expect_finite(one);
}

// Pigment mixing and the canvas (issue 13 §3): the same bytes on one and two threads, finite,
// and each changes the picture (the plan says so).
TEST(Paint, PigmentMixingAndCanvasSameBytesOnOneAndTwoThreads) {
    SceneDesc s = parse_scene(scene_text(kCamera, kTrees), "test");
    const Frame plain = paint(s);
    s.render.pigment_mixing = true;
    const Frame pigment = paint(s);
    s.render.canvas_weave = 0.5f;
    Frame one, two;
    tbb::task_arena(1).execute([&] { one = paint(s, true); });
    tbb::task_arena(2).execute([&] { two = paint(s, true); });
    ASSERT_EQ(one.rgba.size(), two.rgba.size());
    EXPECT_EQ(0, std::memcmp(one.rgba.data(), two.rgba.data(), one.rgba.size() * sizeof(float)));
    expect_finite(one);
    for (float v : one.rgba) ASSERT_TRUE(v >= 0.0f && v <= 1.0f);
    EXPECT_NE(frame_srgb8(plain), frame_srgb8(pigment));
    EXPECT_NE(frame_srgb8(pigment), frame_srgb8(one));
    const FramePlan plan = plan_of(s);
    EXPECT_TRUE(plan.pigment);
    EXPECT_TRUE(plan.canvas);
}

// The instance transform the ray scenes use places a point exactly where the painter does.
// Pigment mixing in a painted frame, not only in pigment_over(): a field of yellow strokes
// laid over a field of blue ones on white canvas. Mixed as pigments (Kubelka-Munk), where
// they overlap the paint turns green, as yellow and blue paint do; mixed as linear RGB they
// make greys and no green. A renderer that composited plain RGB under pigment_mixing fails.
TEST(Paint, YellowOverBlueTurnsGreenUnderPigmentMixing) {
    const fs::path dir = test::temp_dir("pigment-frame");
    {
        std::ofstream ply(dir / "yb.ply");
        ply << "ply\nformat ascii 1.0\nelement vertex 120\nproperty float x\nproperty float "
               "y\nproperty float z\nproperty uchar red\nproperty uchar green\nproperty "
               "uchar blue\nproperty float pscale\nend_header\n";
        uint64_t state = 12345;  // a small LCG: the same strokes on every platform
        auto next = [&] {
            state = state * 6364136223846793005ull + 1442695040888963407ull;
            return double(state >> 11) / double(1ull << 53);
        };
        for (int i = 0; i < 120; ++i) {
            // Blue behind on the left, yellow in front on the right: they overlap in the middle.
            const bool yellow = i >= 60;
            const double u = next(), v = next();
            ply << (yellow ? -0.5 + 2 * u : -1.5 + 2 * u) << " " << (-1 + 2 * v) << " "
                << (yellow ? -9 : -10) << (yellow ? " 230 200 20" : " 30 60 200") << " 0.35\n";
        }
        std::ofstream(dir / "yb.json") << R"({
            "camera": {"position": [0, 0, 0], "look_at": [0, 0, -10], "fov": 20,
                       "width": 160, "height": 120},
            "sun": {"direction": [0, 0, 1]},
            "background": {"canvas": true, "canvas_color": "#ffffff"},
            "materials": {"paint": {"shader": "earth"}},
            "particles": [{"file": "yb.ply", "material": "paint", "color_amount": 1}]})";
    }
    // Pixels of the middle third that are green: G above both R and B by a tenth.
    auto green = [&](bool pigments) {
        const Frame f =
            paint_still(load_scene(dir / "yb.json", {std::string("/render/pigment_mixing=") +
                                                     (pigments ? "true" : "false")}));
        int n = 0;
        for (int y = 0; y < f.height; ++y)
            for (int x = f.width / 3; x < 2 * f.width / 3; ++x) {
                const float* p = &f.rgba[4 * (size_t(y) * f.width + x)];
                n += p[1] > p[0] + 0.1f && p[1] > p[2] + 0.1f;
            }
        return n;
    };
    const int mixed = green(true), plain = green(false);
    EXPECT_GT(mixed, 200) << "yellow over blue paint makes green";
    EXPECT_LT(plain, mixed / 4) << "linear RGB makes greys: " << plain << " vs " << mixed;
    fs::remove_all(dir);
}

TEST(Paint, TreePlacementsLinearPartMatchesPlace) {
    BuiltTree b;
    b.position = {1e4, 3, -2e4};
    b.rotation = 37;
    b.scale = 1.7;
    const TreePlacement pl = placement(b);
    for (const glm::vec3 p : {glm::vec3(1, 0, 0), glm::vec3(0.3f, 4, -2), glm::vec3(-5, 1, 7)}) {
        const glm::dvec3 want = pl.place(p), got = pl.position + pl.linear() * glm::dvec3(p);
        EXPECT_NEAR(glm::length(want - got), 0.0, 1e-9) << p.x;
    }
    // A turn of 37 degrees about +y and a scale of 1.7: +x goes to (cos, 0, -sin) * 1.7.
    const glm::dvec3 x = pl.linear() * glm::dvec3(1, 0, 0);
    EXPECT_NEAR(x.x, 1.7 * std::cos(37 * M_PI / 180), 1e-12);
    EXPECT_NEAR(x.z, -1.7 * std::sin(37 * M_PI / 180), 1e-12);
}

TEST(Paint, StrokesCoverTheTreesAndAovsNameThem) {
    SceneDesc s = parse_scene(scene_text(kCamera, kTrees), "test");
    FrameReport rep;
    Frame f = paint(s, true, &rep);
    EXPECT_GT(rep.leaf_sprites, 1000u);
    EXPECT_GT(rep.bark_sprites, 100u);
    EXPECT_GT(rep.fragments, 10000u);
    size_t oak = 0, birch = 0;
    for (size_t i = 0; i < f.object_id.size(); ++i) {
        oak += f.object_id[i] == 1.0f;
        birch += f.object_id[i] == 2.0f;
        if (f.object_id[i] > 0) {
            EXPECT_GT(f.depth[i], 0.0f);
            EXPECT_LT(f.depth[i], 1e4f);
            EXPECT_GT(f.alpha[i], 0.5f);
        } else if (f.alpha[i] == 0.0f) {
            EXPECT_EQ(f.depth[i], std::numeric_limits<float>::max());  // background: farthest
        }
        EXPECT_NEAR(f.rgba[4 * i + 3], 1.0f, 1e-5f);  // opaque over the background
    }
    EXPECT_GT(oak, 200u);
    EXPECT_GT(birch, 20u);
    EXPECT_GT(oak, birch);  // the oak is nearer and bigger
}

TEST(Paint, PlanSkipsWhatTheSceneDoesNotNeed) {
    SceneDesc s = parse_scene(scene_text(kCamera, kTrees), "test");
    FramePlan plan = plan_of(s);
    EXPECT_TRUE(plan.atmosphere);
    EXPECT_TRUE(plan.tint);  // corot-leaves has unique_tint_amt 0.02
    EXPECT_FALSE(plan.aovs);
    for (auto& f : s.families) f.leaf_shader.unique_tint_amt = f.bark_shader.unique_tint_amt = 0;
    s.has_atmosphere = false;
    s.build.bark_coverage = 0;
    plan = plan_of(s);
    EXPECT_FALSE(plan.tint);
    EXPECT_FALSE(plan.atmosphere);
    EXPECT_FALSE(plan.bark);
    int skipped = 0;
    for (const auto& d : plan.decisions) skipped += !d.ran;
    // bark, tint, atmosphere, cloud shadows, aovs, shadows, underpaint, occlusion maps, level of
    // detail, graftals, imposters, sky, reflections, pigment mixing, canvas, wind
    EXPECT_EQ(skipped, 16);
    EXPECT_FALSE(plan.occlusion_maps);
    EXPECT_FALSE(plan.wind);
    EXPECT_FALSE(plan.imposters);
    // Clouds' shadows only where the sun has clouds.
    s.clouds.cover = 0.5f;
    plan = plan_of(s);
    skipped = 0;
    for (const auto& d : plan.decisions) skipped += !d.ran;
    EXPECT_EQ(skipped, 15);
    s.clouds.cover = 0.0f;
    // With no tint and no atmosphere the picture changes (they did something before).
    SceneDesc full = parse_scene(scene_text(kCamera, kTrees), "test");
    EXPECT_NE(frame_srgb8(paint(full)), frame_srgb8(paint(s)));
}

// A scene with the families but no placed trees, for hand-made particles.
SceneDesc bare_scene(const std::string& camera = kCamera) {
    return parse_scene(scene_text(camera, "[]"), "test");
}

BuiltTree hand_tree(const std::vector<glm::vec3>& points, glm::vec3 normal = {0, 0, 1}) {
    BuiltTree b;
    LeafParticles& L = b.tree().leaves;
    for (size_t i = 0; i < points.size(); ++i) {
        L.position.push_back(points[i]);
        L.normal.push_back(normal);
        L.branch_distance.push_back(0.5f);
        L.center_distance.push_back(0.5f);
        L.label.push_back((i + 0.5f) / points.size());
        L.tree_id.push_back(0);
        L.fade_begin.push_back(2.0f);
        L.fade_end.push_back(3.0f);
    }
    return b;
}

Frame paint_hand(const SceneDesc& s, std::vector<BuiltTree> trees, FrameReport* rep = nullptr) {
    return paint_still(s, std::move(trees), true, rep);
}

// stroke_perspective: 1 is true perspective (size halves when depth doubles), 0 keeps the
// size a stroke has at the focus distance, 0.6 is between; min_stroke_px enlarges the far ones.
TEST(Paint, StrokesShrinkLessThanGeometry) {
    SceneDesc s = parse_scene(scene_text(kCamera, kTrees), "test");
    const Camera& cam = s.camera;
    RenderSettings r;
    const double f = cam.focus_distance;
    r.stroke_perspective = 1;
    EXPECT_NEAR(stroke_screen_px(cam, r, 1.0, 2 * f) / stroke_screen_px(cam, r, 1.0, f), 0.5, 1e-6);
    EXPECT_NEAR(stroke_screen_px(cam, r, 1.0, f), cam.focal_px / f, 1e-3);
    r.stroke_perspective = 0;
    EXPECT_NEAR(stroke_screen_px(cam, r, 1.0, 8 * f), stroke_screen_px(cam, r, 1.0, f), 1e-3);
    r.stroke_perspective = 0.6f;
    const double ratio = stroke_screen_px(cam, r, 1.0, 2 * f) / stroke_screen_px(cam, r, 1.0, f);
    EXPECT_NEAR(ratio, std::pow(0.5, 0.6), 1e-5);
    // In a frame: a particle far away is drawn no smaller than min_stroke_px.
    SceneDesc far = bare_scene();
    far.render.min_stroke_px = 6;
    far.render.samples = 16;
    BuiltTree t = hand_tree({{0, 7, -4000}});
    Frame fr = paint_still(far, {t});
    std::vector<uint8_t> bg = frame_srgb8(paint_still(far, std::vector<BuiltTree>{}));
    std::vector<uint8_t> px = frame_srgb8(fr);
    size_t changed = 0;
    for (size_t i = 0; i < px.size(); i += 3) changed += px[i] != bg[i] || px[i + 1] != bg[i + 1];
    EXPECT_GE(changed, 6u) << "a 6 px stroke covers more than a few pixels";
    EXPECT_LE(changed, 60u);
}

TEST(PaintHardCases, ParticlesAtAndBehindTheCameraAreCulled) {
    SceneDesc s = bare_scene();
    FrameReport rep;
    Frame f = paint_hand(s, {hand_tree({{0, 6, 40}, {0, 6, 45}, {0, 6, 39.99999f}})}, &rep);
    expect_finite(f);
    EXPECT_EQ(rep.culled, 3u);
    Frame empty = paint_hand(s, {});
    EXPECT_EQ(f.rgba, empty.rgba);
}

TEST(PaintHardCases, SpriteLargerThanTheScreenAndZeroSizeSprites) {
    SceneDesc s = bare_scene();
    s.families[0].leaf_shader.sprite_size = 500;  // a leaf 1 unit in front: far wider than the view
    FrameReport rep;
    Frame f = paint_hand(s, {hand_tree({{0, 6, 38}})}, &rep);
    expect_finite(f);
    EXPECT_EQ(rep.leaf_sprites, 1u);
    // Clipped to the screen, every pixel sampled, once: a stroke that large takes one sample.
    EXPECT_EQ(rep.fragments, 96u * 64u);
    s.render.one_sample_px = 0;  // and the scene's samples, 4 a pixel, otherwise
    rep = {};
    f = paint_hand(s, {hand_tree({{0, 6, 38}})}, &rep);
    EXPECT_EQ(rep.fragments, 4u * 96u * 64u);
    s.families[0].leaf_shader.sprite_size = 0;
    s.render.min_stroke_px = 0;
    rep = {};
    f = paint_hand(s, {hand_tree({{0, 6, 0}, {1, 6, 0}})}, &rep);
    expect_finite(f);
    EXPECT_EQ(rep.leaf_sprites, 0u);
    EXPECT_EQ(rep.culled, 2u);
}

TEST(PaintHardCases, NormalAlongTheViewAndLimbSeenEndOn) {
    // Camera straight above a vertical trunk: the bark tangent is parallel to the view.
    SceneDesc s = bare_scene(
        R"({"position": [0, 40, 0], "look_at": [0, 0, 0], "up": [0, 1, 0], "width": 64, "height": 64})");
    PlacedTree t;
    t.family = 1;  // birch: a straight trunk
    s.trees.push_back(t);
    FrameReport rep;
    Frame f = paint(s, true, &rep);
    expect_finite(f);
    EXPECT_GT(rep.bark_sprites, 0u);
    // Bark strokes of a trunk seen end-on still face the camera and paint its top.
    size_t bark = 0;
    for (size_t i = 0; i < f.object_id.size(); ++i) bark += f.object_id[i] > 0 && f.alpha[i] > 0.5f;
    EXPECT_GT(bark, 4u);
    // Leaves whose normal points at the camera: both painted, lit face-on, over the sky.
    FrameReport leaf_rep;
    Frame g = paint_hand(s, {hand_tree({{0, 10, 0}, {0.5f, 10, 0}}, {0, 1, 0})}, &leaf_rep);
    expect_finite(g);
    EXPECT_EQ(leaf_rep.leaf_sprites, 2u);
    EXPECT_GT(leaf_rep.fragments, 0u);
    EXPECT_NE(g.rgba, paint_hand(s, {}).rgba);
}

TEST(PaintHardCases, OneColourPaletteAndEqualFeatherThresholds) {
    SceneDesc s = parse_scene(scene_text(kCamera, kTrees), "test");
    const Color one(0.1f, 0.3f, 0.1f);
    for (auto& fam : s.families) {
        for (Palette* p : {&fam.leaf_palette, &fam.bark_palette})
            p->dark = p->mid = p->light = {{one}};
        for (StrokeShaderParams* p : {&fam.leaf_shader, &fam.bark_shader}) {
            p->stroke_feather_min = p->stroke_feather_max = 0.5f;
            p->sub_stroke_amt = 0;
            p->unique_tint_amt = 0;
        }
    }
    s.has_atmosphere = false;
    FrameReport rep;
    Frame f = paint(s, true, &rep);
    expect_finite(f);
    EXPECT_GT(rep.fragments, 0u);
    // Whatever a stroke's lightness or shadow, the palette has one colour: where the strokes
    // cover a pixel, it is that colour (to the coverage cutoff), and nowhere is a stroke more
    // than it over the sky.
    size_t covered = 0;
    for (size_t i = 0; i < f.alpha.size(); ++i) {
        if (!(f.alpha[i] > 0.9999f)) continue;
        ++covered;
        const float* px = &f.rgba[4 * i];
        ASSERT_NEAR(px[0], one.x, 2e-3f) << i;
        ASSERT_NEAR(px[1], one.y, 2e-3f) << i;
        ASSERT_NEAR(px[2], one.z, 2e-3f) << i;
    }
    EXPECT_GT(covered, 20u);  // 40 when written
}

TEST(PaintHardCases, EmptySceneIsTheBackground) {
    SceneDesc s = bare_scene();
    FrameReport rep;
    Frame f = paint_hand(s, {}, &rep);
    expect_finite(f);
    EXPECT_EQ(rep.fragments, 0u);
    // The frame is the background alone, bit for bit: what paint_background gives under a
    // stroke layer that lets all light through.
    StrokeLayer clear;
    clear.width = f.width, clear.height = f.height;
    clear.color.assign(3 * static_cast<size_t>(f.width) * f.height, 0.0f);
    clear.through.assign(static_cast<size_t>(f.width) * f.height, 1.0f);
    Frame bg = make_frame(s.camera, false);
    paint_background(s, s.camera, clear, bg);
    for (size_t i = 0; i < bg.rgba.size(); i += 4)
        for (int c = 0; c < 3; ++c) ASSERT_EQ(f.rgba[i + c], bg.rgba[i + c]) << i / 4;
    // The sky lightens from the top of the frame down to the horizon.
    auto lum = [&](int y) {
        const float* p = &f.rgba[4 * (y * f.width + f.width / 2)];
        return 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2];
    };
    const Projection horizon = project(s.camera, s.camera.eye + glm::dvec3(0, 0, -1e6));
    const int h = static_cast<int>(horizon.y);
    ASSERT_GT(h, 4);
    EXPECT_GT(lum(h - 2), lum(0) + 0.01f);
}

TEST(PaintHardCases, CameraLookingStraightUpOrDown) {
    for (
        const char* cam :
        {R"({"position": [-6, 1, 0], "look_at": [-6, 50, 0], "up": [0, 1, 0], "width": 48, "height": 48})",
         R"({"position": [0, 60, 0], "look_at": [0, 0, 0], "up": [0, 1, 0], "width": 48, "height": 48})"}) {
        SceneDesc s = parse_scene(scene_text(cam, kTrees), "test");
        EXPECT_NEAR(glm::length(s.camera.right), 1.0, 1e-9);
        EXPECT_NEAR(glm::dot(s.camera.right, s.camera.forward), 0.0, 1e-9);
        FrameReport rep;
        Frame f = paint(s, true, &rep);
        expect_finite(f);
        EXPECT_GT(rep.fragments, 0u) << cam;
    }
}

TEST(PaintHardCases, CameraInsideATree) {
    SceneDesc s = parse_scene(
        scene_text(
            R"({"position": [-6, 9, 0], "look_at": [-6, 9, -10], "width": 64, "height": 48})",
            kTrees),
        "test");
    FrameReport rep;
    Frame f = paint(s, true, &rep);
    expect_finite(f);
    EXPECT_GT(rep.culled, 0u);  // the leaves behind the eye
    // Inside a crown the leaves around the eye fill the view, none of them blown up past the
    // frame: the strokes cover most of it, with the sky still seen through gaps.
    size_t covered = 0, open = 0;
    for (float a : f.alpha) covered += a > 0.5f, open += a < 0.99f;
    EXPECT_GT(rep.leaf_sprites, 0u);
    EXPECT_GT(3 * covered, f.alpha.size());  // 1,850 of 3,072 pixels when written
    EXPECT_GT(open, f.alpha.size() / 10);    // 2,317
}

TEST(ImageOutput, EightBitEncodingEqualsTheTransferFunction) {
    Frame f;
    f.width = 1 << 16;
    f.height = 1;
    f.rgba.resize(4 * static_cast<size_t>(f.width));
    for (int i = 0; i < f.width; ++i) {
        float x = static_cast<float>(i) / (f.width - 1);
        f.rgba[4 * i] = x * x;  // dense near black, where the levels are closest
        f.rgba[4 * i + 1] = x;
        f.rgba[4 * i + 2] = i % 7 == 0 ? std::nanf("") : 1.5f * x - 0.25f;  // out of range
    }
    std::vector<uint8_t> bytes = frame_srgb8(f);
    for (int i = 0; i < f.width; ++i)
        for (int c = 0; c < 3; ++c) {
            float v = f.rgba[4 * i + c];
            if (!std::isfinite(v)) v = 0;
            ASSERT_EQ(bytes[3 * i + c], std::lround(255.0f * linear_to_srgb(v))) << v;
        }
}

}  // namespace
}  // namespace pleinair
