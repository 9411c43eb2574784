// Figures (issue 52 §6, generators/figure.h and pipeline/shot/figures.h): staffage posed and
// painted in touches of its own colours, standing on the ground, refused with its key when
// written wrong.
#include "generators/figure.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

#include "pipeline/frame/frame_plan.h"
#include "pipeline/frame/paint_frame.h"
#include "pipeline/input/error.h"
#include "pipeline/input/scene.h"
#include "pipeline/shot/figures.h"
#include "pipeline/shot/shot.h"

namespace pleinair {
namespace {

// The touches' highest point and farthest reach from the foot's vertical, over the height.
void extent(const FigureTouches& t, const glm::dvec3& foot, double h, double& top, double& reach,
            double& bottom) {
    top = -1e9, reach = 0, bottom = 1e9;
    for (const glm::vec3& q : t.position) {
        const glm::dvec3 d = (glm::dvec3(q) - foot) / h;
        top = std::max(top, d.y), bottom = std::min(bottom, d.y);
        reach = std::max(reach, std::hypot(d.x, d.z));
    }
}

TEST(Figure, EachPoseStandsWithinItsFrame) {
    const glm::dvec3 foot(3, 1.5, -2);
    struct Case {
        FigurePose pose;
        double top_lo, top_hi;  // the highest touch, in heights
    };
    for (const Case& c :
         {Case{FigurePose::kStanding, 0.98, 1.03}, Case{FigurePose::kReaching, 1.15, 1.25},
          Case{FigurePose::kBending, 0.65, 0.85}, Case{FigurePose::kSeated, 0.5, 0.6}}) {
        for (bool dress : {true, false}) {
            FigureParams p;
            p.pose = c.pose, p.height = 1.6, p.dress = dress;
            const FigureTouches t = generate_figure(p, 7, foot);
            // About a hundred touches each side, not a cloud of thousands.
            EXPECT_GT(t.size(), 80u);
            EXPECT_LT(t.size(), 600u);
            double top, reach, bottom;
            extent(t, foot, p.height, top, reach, bottom);
            EXPECT_GE(top, c.top_lo) << static_cast<int>(c.pose);
            EXPECT_LE(top, c.top_hi) << static_cast<int>(c.pose);
            EXPECT_GT(bottom, -0.01);  // nothing below the feet
            EXPECT_LT(bottom, 0.05);   // and down to them
            EXPECT_LT(reach, 0.6);
            for (size_t i = 0; i < t.size(); ++i) {
                EXPECT_NEAR(glm::length(t.normal[i]), 1.0f, 1e-4f);
                EXPECT_FLOAT_EQ(t.width[i], static_cast<float>(p.stroke_size * p.height));
            }
        }
    }
}

TEST(Figure, TheSameSeedGivesTheSameTouchesAndFacingTurnsThem) {
    FigureParams p;
    p.pose = FigurePose::kBending;
    const FigureTouches a = generate_figure(p, 3, glm::dvec3(0));
    const FigureTouches b = generate_figure(p, 3, glm::dvec3(0));
    const FigureTouches c = generate_figure(p, 4, glm::dvec3(0));
    ASSERT_EQ(a.size(), b.size());
    EXPECT_TRUE(std::equal(a.position.begin(), a.position.end(), b.position.begin()));
    ASSERT_EQ(a.size(), c.size());  // the seed moves touches, not their number
    EXPECT_FALSE(std::equal(a.position.begin(), a.position.end(), c.position.begin()));
    // Bent forward: the touches' mean lies ahead, +z at facing 0 and +x at facing 90.
    p.facing = 90;
    const FigureTouches d = generate_figure(p, 3, glm::dvec3(0));
    glm::dvec3 ma(0), md(0);
    for (size_t i = 0; i < a.size(); ++i)
        ma += glm::dvec3(a.position[i]), md += glm::dvec3(d.position[i]);
    ma /= static_cast<double>(a.size()), md /= static_cast<double>(d.size());
    EXPECT_GT(ma.z, 0.08);
    EXPECT_NEAR(ma.x, 0, 0.02);
    EXPECT_GT(md.x, 0.08);
    EXPECT_NEAR(md.z, 0, 0.02);
    EXPECT_NEAR(ma.y, md.y, 1e-6);
}

TEST(Figure, TheHeadsTopAndBackTakeTheHairsColour) {
    FigureParams p;
    const FigureTouches t = generate_figure(p, 1, glm::dvec3(0));
    size_t hair = 0, face = 0;
    for (size_t i = 0; i < t.size(); ++i) {
        if (t.part[i] == FigurePart::kHair) {
            ++hair;
            EXPECT_GT(t.position[i].y, 0.85 * p.height);
            EXPECT_TRUE(t.normal[i].y > 0.3f || t.normal[i].z < -0.25f);
        }
        // The face: skin high up facing forward (the hands hang below the waist).
        if (t.part[i] == FigurePart::kSkin && t.position[i].y > 0.85 * p.height) ++face;
    }
    EXPECT_GT(hair, 3u);
    EXPECT_GT(face, 3u);
    EXPECT_EQ(figure_color(p, FigurePart::kHair), p.hair);
    EXPECT_EQ(figure_color(p, FigurePart::kBottom), p.bottom);
}

const char* kScene = R"({"camera": {"position": [0, 1.2, 8], "look_at": [0, 0.9, 0], "fov": 30,
                                    "width": 160, "height": 90},
                         "sun": {"direction": [-0.5, 0.7, 0.4]})";

TEST(Figure, AScenesFiguresStandOnTheGroundInTheFigureMaterial) {
    const SceneDesc s = parse_scene(std::string(kScene) + R"(,
        "figures": [{"position": [1, 0, 0], "pose": "seated", "top": "#b8442c"},
                    {"position": [-1, 0.5, 0], "height": 1.1}]})",
                                    "t");
    ASSERT_EQ(s.figures.size(), 2u);
    EXPECT_EQ(s.figures[0].params.pose, FigurePose::kSeated);
    EXPECT_NEAR(s.figures[0].top.x, 0xb8 / 255.0f, 1e-6f);
    ASSERT_GE(s.figures[1].material, 0);
    EXPECT_EQ(s.figures[0].material, s.figures[1].material);
    EXPECT_EQ(s.materials[s.figures[0].material].name, "figure");
    // In the strokes: the file's shape, each in its part's colour (linear), none fading.
    const ImportedParticles in = figure_particles(s.figures[1], glm::vec3(0, 1, 0));
    ASSERT_GT(in.strokes.size(), 0u);
    ASSERT_EQ(in.color.size(), in.strokes.size());
    ASSERT_EQ(in.width.size(), in.strokes.size());
    float low = 1e9f;
    for (size_t i = 0; i < in.strokes.size(); ++i) {
        low = std::min(low, in.strokes.position[i].y);
        EXPECT_GT(in.strokes.fade_begin(i), 1.0f);
        EXPECT_EQ(in.strokes.material[i], s.figures[1].material);
        EXPECT_GT(in.strokes.label[i], 0.0f);
        EXPECT_LT(in.strokes.label[i], 1.0f);
    }
    EXPECT_NEAR(low, 0.5f, 0.05f);
    // On a terrain, y is the height above it.
    const SceneDesc hills = parse_scene(std::string(kScene) + R"(,
        "materials": {"grass": {"shader": "grass"}},
        "terrain": {"seed": 1, "min": [-20, -20], "max": [20, 20], "resolution": 17,
                    "base_height": 2, "noise_amplitude": 1, "material": "grass"},
        "figures": [{"position": [1, 0, 0]}]})",
                                        "t");
    EXPECT_NEAR(hills.figures[0].position.y,
                terrain_height(hills.terrain.params, hills.terrain.seed, 1, 0), 1e-9);
}

TEST(Figure, AFigureWrittenWrongIsRefusedWithItsKey) {
    auto refused = [](const std::string& figure, const std::string& key) {
        try {
            parse_scene(std::string(kScene) + R"(, "figures": [)" + figure + "]}", "t");
            ADD_FAILURE() << "taken: " << figure;
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
        }
    };
    refused(R"({"position": [0, 0, 0], "pose": "dancing"})", "/figures/0/pose");
    refused(R"({"pose": "standing"})", "/figures/0/position");
    refused(R"({"position": [0, 0, 0], "height": 0})", "/figures/0/height");
    refused(R"({"position": [0, 0, 0], "top": "red"})", "/figures/0/top");
    refused(R"({"position": [0, 0, 0], "material": "felt"})", "/figures/0/material");
    refused(R"({"position": [0, 0, 0], "hat": true})", "/figures/0/hat");
    refused(R"({"position": [2e5, 0, 0]})", "/figures/0/position");
}

// Pixels of the box whose red stands well above their green and blue: the figure's red top
// (the skin's warm light has green at over half its red).
int red_pixels(const Frame& f, int x0, int y0, int x1, int y1) {
    int n = 0;
    for (int y = std::max(y0, 0); y < std::min(y1, f.height); ++y)
        for (int x = std::max(x0, 0); x < std::min(x1, f.width); ++x) {
            const size_t i = 4 * (static_cast<size_t>(y) * f.width + x);
            if (f.rgba[i] > 2.5f * f.rgba[i + 1] && f.rgba[i] > 2.5f * f.rgba[i + 2]) ++n;
        }
    return n;
}

TEST(Figure, IsPaintedInItsOwnColoursWhereItStands) {
    auto paint = [](const std::string& figures) {
        const Shot shot = build_shot(parse_scene(std::string(kScene) + figures + "}", "t"));
        return paint_frame(shot, still_view(shot.scene), scene_frame_settings(shot.scene));
    };
    const Frame with = paint(R"(, "figures": [{"position": [0, 0, 0], "top": "#c0301c"}])");
    const Frame without = paint("");
    // The blouse, between the waist and the shoulders, on screen.
    const Camera cam = parse_scene(std::string(kScene) + "}", "t").camera;
    const Projection waist = project(cam, glm::dvec3(0, 0.55 * 1.65, 0));
    const Projection shoulder = project(cam, glm::dvec3(0, 0.8 * 1.65, 0));
    ASSERT_TRUE(waist.in_front && shoulder.in_front);
    const int x0 = static_cast<int>(waist.x) - 10, x1 = static_cast<int>(waist.x) + 10;
    const int y0 = static_cast<int>(shoulder.y), y1 = static_cast<int>(waist.y);
    const int area = (x1 - x0) * (y1 - y0);
    EXPECT_GT(red_pixels(with, x0, y0, x1, y1), area / 4);
    EXPECT_EQ(red_pixels(without, x0, y0, x1, y1), 0);
    // Nowhere else: the red stays on the figure (its box, with a margin for the strokes).
    EXPECT_EQ(red_pixels(with, 0, 0, with.width, y0 - 6), 0);
    for (float v : with.rgba) ASSERT_TRUE(std::isfinite(v));
}

// The frame's plan reads the materials' shaders as well as the trees': a scene of figures alone
// takes the figure shader's sub-strokes (they were skipped, no tree asking for them).
TEST(Figure, AScenesMaterialsAloneAskForTheirSubStrokes) {
    const std::string figures = R"(, "figures": [{"position": [0, 0, 0]}])";
    const Shot shot = build_shot(parse_scene(std::string(kScene) + figures + "}", "t"));
    ASSERT_GT(shot.scene.materials[shot.scene.figures[0].material].shader.sub_stroke_amt, 0);
    EXPECT_TRUE(plan_frame(shot, scene_frame_settings(shot.scene)).sub_stroke);
    const Shot flat = build_shot(parse_scene(std::string(kScene) + R"(,
        "materials": {"figure": {"shader": "figure",
                                 "shader_keys": {"sub_stroke": {"sub_stroke_amt": 0}}}})" +
                                                 figures + "}",
                                             "t"));
    EXPECT_FALSE(plan_frame(flat, scene_frame_settings(flat.scene)).sub_stroke);
}

}  // namespace
}  // namespace pleinair
