// Trees stand in the ground (issue 52 §3, pipeline/shot/landscape.h's add_contact): touches of
// the ground in a disc about each trunk's foot, keyed by the tree, dark at the foot, with or
// without a terrain, and in every contact sheet.
#include <gtest/gtest.h>

#include <cmath>

#include "pipeline/frame/paint_frame.h"
#include "pipeline/input/error.h"
#include "pipeline/input/scene.h"
#include "pipeline/output/contact_sheet.h"
#include "pipeline/shot/landscape.h"
#include "pipeline/shot/shot.h"

namespace pleinair {
namespace {

// Trees on open ground with no terrain (the `tree` and `grove` scenes' kind), seen from 30 m.
std::string open_ground(const std::string& trees, const std::string& extra = "") {
    return R"({"camera": {"position": [0, 6, 30], "look_at": [0, 3, 0], "fov": 40,
                          "width": 160, "height": 90},
               "families": {"oak": {"preset": "oak"}},
               "trees": )" +
           trees + extra + "}";
}
const char* kOne = R"([{"family": "oak", "seed": 1, "position": [0, 0, 0]}])";
const char* kTwo = R"([{"family": "oak", "seed": 1, "position": [0, 0, 0]},
                       {"family": "oak", "seed": 2, "position": [12, 0, -6], "scale": 1.5}])";

// The contact chunks' strokes, with the tree each lies nearest to.
SurfaceParticles contact_strokes(const BuiltLandscape& land) {
    SurfaceParticles all;
    for (size_t c = 0; c < land.chunks.size(); ++c)
        if (c < land.chunk_source.size() && land.chunk_source[c].contact)
            all.append(land.chunks[c]);
    return all;
}

TEST(Contact, TouchesLieInADiscAboutEachFootOfTheGroundMaterial) {
    const SceneDesc s = parse_scene(open_ground(kTwo), "test");
    ASSERT_GE(s.contact.material, 0);
    EXPECT_EQ(s.materials[s.contact.material].name, "ground");
    const SurfaceParticles t = contact_strokes(build_landscape(s));
    size_t first = 0, second = 0;
    for (size_t i = 0; i < t.size(); ++i) {
        const glm::dvec3 p(t.position[i]);
        const double d0 = std::hypot(p.x, p.z), d1 = std::hypot(p.x - 12, p.z + 6);
        EXPECT_TRUE(d0 <= s.contact.radius + 1e-4 || d1 <= 1.5 * s.contact.radius + 1e-4)
            << p.x << " " << p.z;
        // On the foot's level, lifted or sunk by the ground strokes' own displacement.
        EXPECT_NEAR(p.y, 0.0, s.terrain.strokes.displacement_height + 1e-4);
        EXPECT_EQ(t.material[i], s.contact.material);
        // u holds the distance from the foot over the radius.
        const double q =
            d0 <= s.contact.radius ? d0 / s.contact.radius : d1 / (1.5 * s.contact.radius);
        EXPECT_NEAR(t.uv(i).x, q, 1e-3);
        (d0 <= s.contact.radius ? first : second) += 1;
    }
    // About the disc's share of the cell, less the rim's thinning; a tree of scale 1.5 takes
    // 2.25 times as many.
    EXPECT_GT(first, static_cast<size_t>(0.5 * s.contact.touches));
    EXPECT_LT(first, static_cast<size_t>(0.8 * s.contact.touches));
    EXPECT_NEAR(double(second) / double(first), 2.25, 0.6);
    // None asked for: none made, and no material added.
    const SceneDesc none = parse_scene(open_ground(kTwo, R"(, "contact": {"touches": 0})"), "t");
    EXPECT_EQ(none.contact.material, -1);
    EXPECT_TRUE(none.materials.empty());
    EXPECT_EQ(contact_strokes(build_landscape(none)).size(), 0u);
}

TEST(Contact, ATreesTouchesAreItsOwnWhateverOtherTreesStand) {
    const SurfaceParticles one =
        contact_strokes(build_landscape(parse_scene(open_ground(kOne), "t")));
    const SurfaceParticles two =
        contact_strokes(build_landscape(parse_scene(open_ground(kTwo), "t")));
    ASSERT_GT(one.size(), 10u);
    ASSERT_GT(two.size(), one.size());
    for (size_t i = 0; i < one.size(); ++i) {
        EXPECT_EQ(one.position[i], two.position[i]);
        EXPECT_EQ(one.label[i], two.label[i]);
    }
}

TEST(Contact, TouchesStandOnTheTerrainInItsMaterial) {
    const std::string scene = R"({"camera": {"position": [0, 8, 40], "look_at": [0, 2, 0],
        "fov": 40, "width": 96, "height": 64},
        "materials": {"grass": {"shader": "grass"}, "earth": {"shader": "earth"}},
        "terrain": {"seed": 2, "min": [-40, -40], "max": [40, 40], "resolution": 33,
                    "hills": [{"center": [0, 0], "radius": 20, "height": 5}],
                    "material": "grass", "second_material": "earth"},
        "families": {"oak": {"preset": "oak"}},
        "trees": [{"family": "oak", "seed": 1, "position": [3, 0, 2]}]})";
    const SceneDesc s = parse_scene(scene, "t");
    EXPECT_EQ(s.contact.material, -1);  // the terrain's own at each touch
    const SurfaceParticles t = contact_strokes(build_landscape(s));
    ASSERT_GT(t.size(), 10u);
    for (size_t i = 0; i < t.size(); ++i) {
        const glm::dvec3 p(t.position[i]);
        EXPECT_NEAR(p.y, terrain_height(s.terrain.params, s.terrain.seed, p.x, p.z),
                    s.terrain.strokes.displacement_height + 1e-3);
        EXPECT_EQ(t.material[i], terrain_material_at(s, p));
    }
    // A material named: every touch takes it; a name not among the materials is refused.
    const SceneDesc earth = parse_scene(scene, "t", {R"(/contact={"material": "earth"})"});
    for (uint16_t m : contact_strokes(build_landscape(earth)).material)
        EXPECT_EQ(m, earth.contact.material);
    try {
        parse_scene(scene, "t", {R"(/contact={"material": "moss"})"});
        FAIL() << "an unknown material was taken";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("/contact/material"), std::string::npos) << e.what();
    }
}

// Mean L* (from luminance) over a box of the frame.
double mean_lightness(const Frame& f, int x0, int y0, int x1, int y1) {
    double sum = 0;
    int n = 0;
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x, ++n) {
            const size_t i = 4 * (static_cast<size_t>(y) * f.width + x);
            const double lum = 0.2126 * f.rgba[i] + 0.7152 * f.rgba[i + 1] + 0.0722 * f.rgba[i + 2];
            sum += 116.0 * std::cbrt(std::max(lum, 0.008856)) - 16.0;
        }
    return sum / n;
}

TEST(Contact, TheFootIsPaintedDarkInTheGround) {
    // The ground about the foot (a box under and beside the trunk's base, where it meets the
    // ground on screen) is darker with the touches than without; without shade they are lighter
    // than with it.
    auto paint = [](const std::string& contact) {
        const Shot shot = build_shot(parse_scene(open_ground(kOne, contact), "t"));
        return paint_frame(shot, still_view(shot.scene), scene_frame_settings(shot.scene));
    };
    const Camera cam = parse_scene(open_ground(kOne), "t").camera;
    const Projection foot = project(cam, glm::dvec3(0, 0, 0));
    ASSERT_TRUE(foot.in_front);
    const int x0 = static_cast<int>(foot.x) - 8, x1 = static_cast<int>(foot.x) + 8;
    const int y0 = static_cast<int>(foot.y) - 1, y1 = static_cast<int>(foot.y) + 3;
    const double bare = mean_lightness(paint(R"(, "contact": {"touches": 0})"), x0, y0, x1, y1);
    const double shaded = mean_lightness(paint(""), x0, y0, x1, y1);
    const double unshaded = mean_lightness(paint(R"(, "contact": {"shade": 0})"), x0, y0, x1, y1);
    EXPECT_LT(shaded, bare - 3) << bare << " " << shaded;
    EXPECT_LT(shaded, unshaded - 3) << unshaded << " " << shaded;
}

}  // namespace
}  // namespace pleinair
