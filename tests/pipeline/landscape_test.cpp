// Landscapes painted: the plan builds only the ray scenes a frame needs, a lit flat ground
// without casters has no shadowed stroke, the hard cases of the issue stay finite, a landscape
// far from the origin paints the same picture, and the bytes do not depend on threads.
#include "pipeline/shot/landscape.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <cmath>
#include <cstring>
#include <set>
#include <tuple>

#include "pipeline/frame/lod.h"
#include "pipeline/frame/paint_frame.h"
#include "pipeline/input/error.h"
#include "pipeline/input/scene.h"
#include "pipeline/output/image_io.h"
#include "pipeline/shot/particle_input.h"
#include "pipeline/shot/shot.h"
#include "shading/surface_shader.h"

namespace pleinair {
namespace {

// A small landscape: a hill and a pond, a rock, a scattered group and one explicit tree.
// `o` offsets every x and z (terrain, hills, camera, trees, rocks, groups).
std::string landscape(const std::string& sun, double o = 0, const std::string& extra = "",
                      const std::string& camera_pos = "") {
    auto x = [&](double v) { return std::to_string(v + o); };
    std::string cam = camera_pos;
    if (cam.empty()) cam.append("[").append(x(0)).append(", 3, ").append(x(40)).append("]");
    return R"({"camera": {"position": )" + cam + R"(, "look_at": [)" + x(0) + ", 4, " + x(-10) +
           R"(], "fov": 50, "width": 96, "height": 64},
        "sun": )" +
           sun + R"(,
        "atmosphere": {"near": 10, "far": 150},
        "materials": {"grass": {"shader": "grass"}, "earth": {"shader": "earth"},
                      "water": {"shader": "water"}, "rock": {"shader": "rock"}},
        "terrain": {"seed": 2, "min": [)" +
           x(-60) + ", " + x(-80) + "], \"max\": [" + x(60) + ", " + x(50) + R"(], "resolution": 49,
                    "hills": [{"center": [)" +
           x(-20) + ", " + x(-40) + R"(], "radius": 25,
                               "height": 6},
                              {"center": [)" +
           x(15) + ", " + x(5) + R"(], "radius": 15,
                               "height": -2}],
                    "material": "grass", "second_material": "earth", "bank_material": "earth",
                    "strokes": {"particle_spans_u": 50, "particle_spans_v": 50,
                                "particles_per_cluster": 2}},
        "water": {"level": 0.0, "strokes": {"particle_spans_u": 10, "particle_spans_v": 10}},
        "rocks": [{"seed": 1, "position": [)" +
           x(-6) + ", 0.2, " + x(20) + R"(]}],
        "families": {"birch": {"preset": "birch"}, "shrub": {"preset": "shrub"}},
        "groups": [{"seed": 1, "center": [)" +
           x(-15) + ", " + x(-30) + R"(], "radius": 14,
                    "min_distance": 7, "max_trees": 4, "families": {"birch": 1, "shrub": 1}}],
        "trees": [{"family": "birch", "seed": 3, "position": [)" +
           x(8) + ", 0, " + x(18) + "]}]" + extra + "}";
}

const char* kSun = R"({"direction": [-0.5, 0.6, 0.4], "casts_shadows": true})";

Frame paint(const SceneDesc& s, FrameReport* rep = nullptr) { return paint_still(s, false, rep); }

void expect_finite(const Frame& f) {
    for (float v : f.rgba) {
        ASSERT_TRUE(std::isfinite(v));
        ASSERT_GE(v, 0.0f);
    }
}

TEST(Landscape, BuildsStrokesOfEveryKind) {
    SceneDesc s = parse_scene(landscape(kSun), "test");
    BuiltLandscape land = build_landscape(s);
    ASSERT_TRUE(land.has_terrain && land.has_water);
    EXPECT_EQ(land.rocks.size(), 1u);
    EXPECT_TRUE(check_mesh(land.rocks[0]).ok());
    const SurfaceParticles strokes = land.all_strokes();
    EXPECT_EQ(strokes.size(), land.stroke_count());
    size_t per_material[4] = {0, 0, 0, 0};
    for (size_t i = 0; i < strokes.size(); ++i) ++per_material[strokes.material[i]];
    for (size_t m = 0; m < 4; ++m) EXPECT_GT(per_material[m], 0u) << s.materials[m].name;
    // No ground stroke under the water; every water stroke over ground below the level.
    for (size_t i = 0; i < strokes.size(); ++i) {
        const glm::vec3& p = strokes.position[i];
        double ground = terrain_height(s.terrain.params, s.terrain.seed, p.x, p.z);
        if (strokes.material[i] == s.water.material) {
            EXPECT_LT(ground, s.water.level + 0.05 + 1e-4);
        } else if (strokes.material[i] != s.rocks[0].material) {
            EXPECT_GE(p.y, s.water.level - 0.02 - 0.1 - 1e-4);
        }
    }
    EXPECT_EQ(s.trees.size(), s.explicit_trees + 4);  // the group planted its four
    for (size_t i = s.explicit_trees; i < s.trees.size(); ++i)
        EXPECT_NEAR(s.trees[i].position.y,
                    terrain_height(s.terrain.params, s.terrain.seed, s.trees[i].position.x,
                                   s.trees[i].position.z),
                    1e-9);
}

// A region paints its disc with its own material; the bank still wins at the water's edge.
TEST(Landscape, RegionsPaintTheirDiscWithTheirMaterial) {
    SceneDesc s = parse_scene(
        landscape(kSun), "test",
        {R"(/terrain/regions=[{"center": [-30, 30], "radius": 12, "material": "rock"}])"});
    ASSERT_EQ(s.terrain.regions.size(), 1u);
    const SurfaceParticles strokes = build_landscape(s).all_strokes();
    size_t inside = 0;
    for (size_t i = 0; i < strokes.size(); ++i) {
        const glm::vec3& p = strokes.position[i];
        if (std::hypot(p.x + 30.0, p.z - 30.0) >= 0.75 * 12.0 ||
            strokes.material[i] == s.water.material)
            continue;
        ++inside;
        const bool bank = p.y < s.water.level + s.terrain.bank_height;
        if (!bank) {
            EXPECT_EQ(strokes.material[i], s.rocks[0].material) << p.y;
        }
    }
    EXPECT_GT(inside, 30u);
    EXPECT_EQ(terrain_material_at(s, {-30, 5, 30}), s.rocks[0].material);
    EXPECT_NE(terrain_material_at(s, {-30, 5, 60}), s.rocks[0].material);  // 30 away: > 1.25 r
}

// A region with a density of its own paints its ground in that many times the strokes a
// square metre, each smaller by the square root (the same cover), in place of the terrain's own
// there and nowhere else; the rest of the terrain keeps its strokes, the same bytes.
TEST(Landscape, ADenseRegionPaintsItsGroundInMoreSmallerStrokes) {
    const char* kRegion =
        R"(/terrain/regions=[{"center": [-20, -40], "radius": 20, "material": "meadow"%s}])";
    auto scene = [&](const char* density) {
        char buf[256];
        std::snprintf(buf, sizeof buf, kRegion, density);
        return parse_scene(landscape(kSun), "test",
                           {R"(/materials/meadow={"shader": "grass", "palette": "corot-bank"})",
                            buf, "/contact/touches=0"});  // the group's trees' feet stand in it
    };
    const SceneDesc plain = scene(""), dense = scene(R"(, "density": 4)");
    ASSERT_EQ(dense.terrain.regions[0].density, 4.0);
    const uint16_t meadow = static_cast<uint16_t>(dense.terrain.regions[0].material);
    const BuiltLandscape a = build_landscape(plain), b = build_landscape(dense);
    // Strokes and their summed area (size squared) inside the region, and the others' keys.
    struct Count {
        size_t n = 0;
        double area = 0;
        std::multiset<std::tuple<float, float, float, uint16_t>> outside;
    };
    auto count = [&](const BuiltLandscape& land) {
        Count c;
        for (size_t k = 0; k < land.chunks.size(); ++k) {
            const SurfaceParticles& S = land.chunks[k];
            for (size_t i = 0; i < S.size(); ++i) {
                const glm::vec3& p = S.position[i];
                if (S.material[i] == meadow && terrain_region_at(dense, glm::dvec3(p)) == 0) {
                    ++c.n;
                    c.area += double(land.chunk_size[k]) * land.chunk_size[k];
                } else {
                    c.outside.insert({p.x, p.y, p.z, S.material[i]});
                }
            }
        }
        return c;
    };
    const Count ca = count(a), cb = count(b);
    ASSERT_GT(ca.n, 100u);
    // Both are random samples of the disc (398 and 1,596 strokes): within 10%.
    EXPECT_NEAR(double(cb.n) / double(ca.n), 4.0, 0.4) << ca.n << " " << cb.n;
    EXPECT_NEAR(cb.area / ca.area, 1.0, 0.1);
    // Every stroke outside the region is one the plain terrain had, and none is lost.
    EXPECT_TRUE(ca.outside == cb.outside);
    // No stroke of the region's material stands outside its wandering rim.
    for (const SurfaceParticles& S : b.chunks)
        for (size_t i = 0; i < S.size(); ++i)
            if (S.material[i] == meadow &&
                std::hypot(S.position[i].x + 20.0, S.position[i].z + 40.0) > 1.25 * 20.0 + 1e-3) {
                ADD_FAILURE() << "a region's stroke outside it";
                break;
            }
    // A density out of range is refused with its key.
    try {
        scene(R"(, "density": 100)");
        ADD_FAILURE() << "density 100 accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("/terrain/regions/0/density"), std::string::npos)
            << e.what();
    }
}

TEST(Landscape, ShadowSceneOnlyWhenTheSunCastsShadows) {
    FrameReport with, without, trees_only;
    SceneDesc lit = parse_scene(landscape(kSun), "test");
    Frame a = paint(lit, &with);
    EXPECT_TRUE(build_shot(lit).sun_rays);
    EXPECT_GT(with.shadow_rays, 0u);
    EXPECT_TRUE(build_shot(lit).view_rays);
    EXPECT_GT(with.underpaint_rays, 0u);

    SceneDesc flat = parse_scene(landscape(R"({"direction": [-0.5, 0.6, 0.4]})"), "test");
    const Shot flat_shot = build_shot(flat);
    EXPECT_FALSE(plan_frame(flat_shot, scene_frame_settings(flat)).shadows);
    Frame b = paint(flat, &without);
    EXPECT_FALSE(flat_shot.sun_rays);
    EXPECT_EQ(without.shadow_rays, 0u);
    EXPECT_TRUE(flat_shot.view_rays);
    // The shadows did something: the pictures differ and the lit one is darker somewhere.
    EXPECT_NE(frame_srgb8(a), frame_srgb8(b));

    // Trees only, no terrain or rock: no visible mesh, so no underpainting and no camera scene.
    SceneDesc t = parse_scene(R"({"camera": {"position": [0, 6, 40], "look_at": [0, 7, 0],
        "width": 64, "height": 48}, "families": {"oak": {"preset": "oak"}},
        "trees": [{"family": "oak", "seed": 1}]})",
                              "test");
    const Shot trees_shot = build_shot(t);
    FramePlan plan = plan_frame(trees_shot, scene_frame_settings(t));
    EXPECT_FALSE(plan.underpaint);
    EXPECT_FALSE(plan.shadows);
    paint(t, &trees_only);
    EXPECT_FALSE(trees_shot.view_rays);
    EXPECT_FALSE(trees_shot.sun_rays);
    EXPECT_FALSE(trees_shot.limbs);  // no Embree device at all
    EXPECT_EQ(trees_only.underpaint_rays, 0u);
}

// Shadows per fragment: a grid of rays over every sprite, the light varying inside strokes.
TEST(Landscape, ShadowsPerFragmentTraceAGridPerSprite) {
    SceneDesc s = parse_scene(landscape(kSun), "test");
    FrameReport particle, fragment;
    Frame a = paint(s, &particle);
    s.render.shadow_samples = ShadowSamples::kFragment;
    Frame b = paint(s, &fragment);
    const uint64_t sprites =
        fragment.leaf_sprites + fragment.bark_sprites + fragment.surface_sprites;
    EXPECT_EQ(sprites, particle.leaf_sprites + particle.bark_sprites + particle.surface_sprites);
    EXPECT_GE(fragment.shadow_rays, 16 * sprites);
    EXPECT_NE(frame_srgb8(a), frame_srgb8(b));
    expect_finite(b);
}

// A flat lit ground and nothing to cast a shadow: shadow rays run and find nothing, so the
// picture is the same bytes as without shadows, near the origin and near the edge of the world
// (scene.h: kMaxWorldCoordinate), with the sun
// overhead, at 20 degrees and grazing at 2 degrees.
TEST(Landscape, LitFlatGroundWithoutCastersHasNoShadowedStroke) {
    for (double far : {0.0, kMaxWorldCoordinate - 100})
        for (double elevation : {90.0, 20.0, 2.0}) {
            SCOPED_TRACE("far " + std::to_string(far) + ", elevation " + std::to_string(elevation));
            double e = elevation * M_PI / 180;
            auto text = [&](bool shadows) {
                auto x = [&](double v) { return std::to_string(v + far); };
                return R"({"camera": {"position": [)" + x(0) + ", 2, " + x(30) +
                       R"(], "look_at": [)" + x(0) + ", 0, " + x(-10) +
                       R"(], "width": 64, "height": 48},
                    "sun": {"direction": [)" +
                       std::to_string(0.6 * std::cos(e)) + ", " + std::to_string(std::sin(e)) +
                       ", " + std::to_string(0.8 * std::cos(e)) +
                       "], \"casts_shadows\": " + (shadows ? "true" : "false") + R"(},
                    "materials": {"grass": {"shader": "grass"}},
                    "terrain": {"min": [)" +
                       x(-50) + ", " + x(-50) + "], \"max\": [" + x(50) + ", " + x(50) +
                       R"(], "noise_amplitude": 0, "resolution": 9,
                                "strokes": {"particle_spans_u": 40, "particle_spans_v": 40,
                                            "particles_per_cluster": 2}}})";
            };
            FrameReport rep;
            Frame with = paint(parse_scene(text(true), "test"), &rep);
            Frame without = paint(parse_scene(text(false), "test"));
            EXPECT_GT(rep.shadow_rays, 1000u);
            EXPECT_EQ(frame_srgb8(with), frame_srgb8(without));
            expect_finite(with);
        }
}

TEST(Landscape, FarFromTheOriginPaintsTheSamePicture) {
    Frame fn = paint(parse_scene(landscape(kSun), "test"));
    // Near the edge of the world a scene may use (scene.h), the whole landscape inside it.
    Frame ff = paint(parse_scene(landscape(kSun, kMaxWorldCoordinate - 100), "test"));
    std::vector<uint8_t> near = frame_srgb8(fn);
    std::vector<uint8_t> far = frame_srgb8(ff);
    ASSERT_EQ(near.size(), far.size());
    double sq = 0;
    for (size_t i = 0; i < near.size(); ++i) sq += std::pow(int(near[i]) - int(far[i]), 2);
    // Float positions there are 8 mm apart: strokes move by a fraction of a pixel, and a
    // few strokes at the water's edge change sides of the level (measured: 3.9 levels).
    const double rmse = std::sqrt(sq / near.size());
    EXPECT_LT(rmse, 6.0) << "RMSE in 8-bit levels";
    RecordProperty("rmse", std::to_string(rmse));
    std::printf("RMSE near vs 99,900 away: %.3f levels\n", rmse);
}

TEST(Landscape, SameBytesOnOneAndTwoThreads) {
    SceneDesc s = parse_scene(landscape(kSun), "test");
    Frame one, two;
    tbb::task_arena(1).execute([&] { one = paint(s); });
    tbb::task_arena(2).execute([&] { two = paint(s); });
    ASSERT_EQ(one.rgba.size(), two.rgba.size());
    EXPECT_EQ(0, std::memcmp(one.rgba.data(), two.rgba.data(), one.rgba.size() * sizeof(float)));
    expect_finite(one);
}

// Finite only; what each paints is asserted in the hard-case suite (hard_cases_test.cpp).
TEST(LandscapeHardCases, SunAtTheHorizonAndOverheadCameraUnderGroundOrInATreeStayFinite) {
    const std::string horizon = R"({"direction": [1, 0, 0], "casts_shadows": true})";
    const std::string below = R"({"direction": [0.3, -0.2, 0.1], "casts_shadows": true})";
    const std::string overhead = R"({"direction": [0, 1, 0], "casts_shadows": true})";
    for (const std::string& sun : {horizon, below, overhead}) {
        SCOPED_TRACE(sun);
        expect_finite(paint(parse_scene(landscape(sun), "test")));
    }
    // Under the ground, looking at it from below; inside the explicit birch's crown.
    for (const char* pos : {"[0, -8, 40]", "[8, 6, 18]"}) {
        SCOPED_TRACE(pos);
        FrameReport rep;
        expect_finite(paint(parse_scene(landscape(kSun, 0, "", pos), "test"), &rep));
    }
}

TEST(LandscapeHardCases, NoRoomForTreesDegenerateRockAndEmptyRegions) {
    // A group whose disc lies in the pond plants nothing; a rock a tenth of a millimetre
    // across, squashed flat (one of radius 0 or scale 0 is refused as input); water below every
    // point of the ground emits no stroke.
    std::string text = landscape(kSun);
    auto replace = [&](const std::string& from, const std::string& to) {
        size_t at = text.find(from);
        ASSERT_NE(at, std::string::npos) << from;
        text.replace(at, from.size(), to);
    };
    replace(R"("center": [-15.000000, -30.000000], "radius": 14)",
            R"("center": [15, 5], "radius": 2)");
    replace(R"("rocks": [{"seed": 1,)",
            R"("rocks": [{"radius": 1e-4, "scale": [1, 1e-6, 1], "roughness": 0.9, "seed": 1,)");
    EXPECT_THROW(parse_scene(text, "test", {"/rocks/0/radius=0"}), InputError);
    EXPECT_THROW(parse_scene(text, "test", {"/rocks/0/scale=[1, 0, 1]"}), InputError);
    SceneDesc s = parse_scene(text, "test");
    EXPECT_EQ(s.trees.size(), s.explicit_trees);
    BuiltLandscape land = build_landscape(s);
    ASSERT_EQ(land.rocks.size(), 1u);
    const MeshCheck c = check_mesh(land.rocks[0]);
    EXPECT_TRUE(c.finite && c.indices_valid);
    expect_finite(paint(s));

    replace(R"("water": {"level": 0.0,)", R"("water": {"level": -100,)");
    SceneDesc dry = parse_scene(text, "test");
    BuiltLandscape d = build_landscape(dry);
    for (uint32_t m : d.all_strokes().material) EXPECT_NE(m, dry.water.material);
    expect_finite(paint(dry));
}

}  // namespace
}  // namespace pleinair

namespace pleinair {
namespace {

TEST(NearField, GroundStrokesAlongTheCameraPathKeyedByTheirCells) {
    const BuiltLandscape none = build_landscape(parse_scene(landscape(kSun), "test"));
    EXPECT_FALSE(none.is_near(0));
    EXPECT_EQ(none.near_chunk, ~size_t{0});
    const SceneDesc still = parse_scene(landscape(kSun), "test", {"/camera/near_field=8"});
    const BuiltLandscape a = build_landscape(still);
    ASSERT_LT(a.near_chunk, a.chunks.size());
    const SurfaceParticles& na = a.chunks[a.near_chunk];
    ASSERT_GT(na.size(), 100u);
    EXPECT_LT(a.chunk_size[a.near_chunk], a.chunk_size[0]);  // smaller than the terrain's own
    const double cell = 0.5 * still.materials[still.terrain.material].shader.sprite_size;
    for (size_t i = 0; i < na.size(); ++i) {
        const glm::vec3 p = na.position[i];
        ASSERT_LT(std::hypot(p.x - 0.0, p.z - 40.0), 1.2 * 8 + 1.5 * cell);
        // Never under the water (level 0), and on the ground.
        const double ground = terrain_height(still.terrain.params, still.terrain.seed, p.x, p.z);
        ASSERT_GE(ground, -0.02);
        ASSERT_NEAR(p.y, ground, still.terrain.strokes.displacement_height + 1e-3);
    }
    // A track that walks on from the same place keeps every stroke the still had, bit for bit:
    // a cell's strokes depend on its key alone.
    SceneDesc walk = still;
    CameraKey k0, k1;
    k0.time = 0, k0.position = {0, 3, 40}, k0.look_at = {0, 4, -10};
    k1.time = 1, k1.position = {0, 3, 30}, k1.look_at = {0, 4, -20};
    walk.camera_track.keys = {k0, k1};
    const BuiltLandscape b = build_landscape(walk);
    const SurfaceParticles& nb = b.chunks.at(b.near_chunk);
    EXPECT_GT(nb.size(), na.size());
    std::set<std::tuple<float, float, float, float>> in_b;
    for (size_t i = 0; i < nb.size(); ++i)
        in_b.emplace(nb.position[i].x, nb.position[i].y, nb.position[i].z, nb.label[i]);
    for (size_t i = 0; i < na.size(); ++i)
        ASSERT_TRUE(in_b.count({na.position[i].x, na.position[i].y, na.position[i].z, na.label[i]}))
            << i;
}

TEST(NearField, GroundStrokesAppearOneByOneAsTheCameraNears) {
    const Shot shot = build_shot(parse_scene(landscape(kSun), "test", {"/camera/near_field=8"}));
    const size_t item = shot.trees->size() + shot.land->near_chunk;
    const SurfaceParticles& S = shot.land->chunks.at(shot.land->near_chunk);
    RenderSettings rs;
    std::vector<float> last(S.size(), -1.0f);
    float total_last = 0;
    for (double back : {12.0, 8.0, 5.0, 3.0, 1.0}) {
        FrameView view = still_view(shot.scene);
        CameraParams p = shot.scene.camera_params;
        p.position = {0, 3, 40 - 8 + back};  // the strokes lie around z = 40
        p.look_at = p.position + glm::dvec3(0, -0.5, -1);
        ASSERT_EQ(make_camera(p, view.camera), "");
        const FrameLod lod = level_of_detail(shot, view, rs);
        float total = 0;
        for (size_t j = 0; j < S.size(); ++j) {
            const glm::dvec3 w(S.position[j]);
            if (view_depth(view.camera, w) < 0.5) continue;  // behind, or under the camera
            const float f = particle_lod(shot, lod, item, SpriteKind::kSurface, j, w).fade;
            ASSERT_TRUE(f >= 0 && f <= 1);
            if (last[j] >= 0) {
                ASSERT_GE(f, last[j] - 1e-6f) << "a stroke faded as the camera came nearer";
            }
            last[j] = f;
            total += f;
        }
        total_last = total;
        // Level of detail off: none of them.
        RenderSettings off = rs;
        off.level_of_detail = false;
        const FrameLod none = level_of_detail(shot, view, off);
        for (size_t j = 0; j < S.size(); j += 7)
            ASSERT_EQ(
                particle_lod(shot, none, item, SpriteKind::kSurface, j, glm::dvec3(S.position[j]))
                    .fade,
                0.0f);
    }
    EXPECT_GT(total_last, 0.0f);
}

}  // namespace
}  // namespace pleinair

namespace pleinair {
namespace {

// A material's shader_keys edit its shader preset as a family's leaf_shader_keys do: the edited
// keys change, the others keep the preset's, and a key the shader does not have is named where
// the scene wrote it.
TEST(Landscape, AMaterialsShaderKeysEditItsShader) {
    auto scene = [](const std::string& keys) {
        return parse_scene(R"({"materials": {"grass": {"shader": "grass"},
                                             "hazy": {"shader": "grass", "shader_keys": )" +
                               keys + "}}}",
                           "keys.json");
    };
    const SceneDesc s = scene(R"({"distance": {"dist_value_min": 0.5, "dist_hue_color": "#a4b2bc"},
                                  "sprite": {"sprite_size": 0.7}})");
    ASSERT_EQ(s.materials.size(), 2u);
    const StrokeShaderParams &plain = s.materials[0].shader, &hazy = s.materials[1].shader;
    EXPECT_FLOAT_EQ(hazy.dist_value_min, 0.5f);
    EXPECT_FLOAT_EQ(hazy.sprite_size, 0.7f);
    EXPECT_NEAR(hazy.dist_hue_color.r, 0xa4 / 255.0f, 1e-6f);
    EXPECT_NEAR(hazy.dist_hue_color.b, 0xbc / 255.0f, 1e-6f);
    EXPECT_FLOAT_EQ(plain.dist_value_min, 0.3f);  // grass.json's
    EXPECT_FLOAT_EQ(plain.sprite_size, 1.6f);
    EXPECT_EQ(hazy.stroke_fullness, plain.stroke_fullness);
    EXPECT_EQ(hazy.dist_curve_bias, plain.dist_curve_bias);
    auto problem = [&](const std::string& keys) {
        try {
            scene(keys);
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    EXPECT_NE(problem(R"({"sprite": {"sprite_sise": 1}})").find("/materials/hazy/shader_keys"),
              std::string::npos)
        << problem(R"({"sprite": {"sprite_sise": 1}})");
    EXPECT_NE(problem(R"({"sprite": {"sprite_size": -1}})").find("/materials/hazy/shader_keys"),
              std::string::npos)
        << problem(R"({"sprite": {"sprite_size": -1}})");
    EXPECT_NE(problem("3").find("/materials/hazy/shader_keys: expected an object"),
              std::string::npos)
        << problem("3");
}

// surface/base_aspect lengthens a material's base strokes and leaves its tufts' shape: every
// surface particle's stroke is its width times the shader's aspect, times base_aspect below
// the detail threshold.
TEST(Landscape, BaseAspectLengthensTheBaseStrokesOnly) {
    const Shot shot = build_shot(parse_scene(R"({
        "camera": {"position": [0, 2, 14], "look_at": [0, 1.5, 0], "width": 64, "height": 48},
        "materials": {"long": {"shader": "grass", "shader_keys": {"surface": {"base_aspect": 2}}}},
        "terrain": {"seed": 2, "min": [-10, -10], "max": [10, 10], "resolution": 9,
                    "material": "long",
                    "strokes": {"particle_spans_u": 12, "particle_spans_v": 12}}})",
                                             "long.json"));
    const ParticleSource particles = shot.particles();
    const size_t trees = shot.trees->size();
    size_t base = 0, detail = 0;
    for (size_t c = 0; c < shot.land->chunks.size(); ++c) {
        const SurfaceParticles& S = shot.land->chunks[c];
        for (size_t j = 0; j < S.size(); ++j) {
            MaterialId mat;
            const ParticleInput in =
                particle_input(particles, trees + c, SpriteKind::kSurface, j,
                               particle_origin(particles, trees + c, SpriteKind::kSurface, j), mat);
            const SpriteMaterial& m = shot.materials[mat];
            const bool tuft = is_detail(*m.surface, S.height(j));
            const double aspect = m.shader->stroke_aspect * (tuft ? 1.0 : 2.0);
            ASSERT_NEAR(in.length / in.width, aspect, 1e-5 * aspect) << j;
            ++(tuft ? detail : base);
        }
    }
    EXPECT_GT(base, 50u);
    EXPECT_GT(detail, 10u);
}

}  // namespace
}  // namespace pleinair
