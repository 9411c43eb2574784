// Particles from other tools: a PLY file read the same in every format and type, its axes,
// sizes, labels, normals and colours as the scene says, painted; hostile files refused with
// the vertex and property, before anything is written.
#include "pipeline/input/particle_files.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <glm/geometric.hpp>
#include <set>

#include "generators/terrain.h"
#include "pipeline/frame/paint_frame.h"
#include "pipeline/input/error.h"
#include "pipeline/input/limits.h"
#include "pipeline/input/ply.h"
#include "pipeline/input/scene.h"
#include "ply_writer.h"
#include "test_util.h"

namespace pleinair {
namespace {

using test::PlyColumn;
using test::write_ply;

const glm::vec3 kSun = glm::normalize(glm::vec3(-0.5f, 0.7f, 0.5f));

ImportedParticles import(const std::string& bytes, ParticleFileDesc d = {}) {
    return import_particles(bytes, "cloud.ply", d, 7, kSun, 1e5);
}

// The one line an InputError prints, or "" when none is thrown.
template <class Fn>
std::string error_of(Fn&& fn) {
    try {
        fn();
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

std::vector<PlyColumn> three_points(const std::string& position_type = "float") {
    return {{position_type, "x", {0, 1.5, -2}},  {position_type, "y", {0, 2, 3}},
            {position_type, "z", {0, -4, 0.25}}, {"float", "pscale", {0.1, 0.2, 0.05}},
            {"int", "id", {30, 10, 20}},         {"float", "nx", {0, 1, 0}},
            {"float", "ny", {1, 0, 0}},          {"float", "nz", {0, 0, 2}},
            {"uchar", "red", {255, 0, 128}},     {"uchar", "green", {0, 255, 128}},
            {"uchar", "blue", {0, 0, 128}}};
}

void expect_same(const ImportedParticles& a, const ImportedParticles& b) {
    ASSERT_EQ(a.strokes.size(), b.strokes.size());
    for (size_t i = 0; i < a.strokes.size(); ++i) {
        EXPECT_EQ(a.strokes.position[i], b.strokes.position[i]) << i;
        EXPECT_EQ(a.strokes.normal_code[i], b.strokes.normal_code[i]) << i;
        EXPECT_EQ(a.strokes.label[i], b.strokes.label[i]) << i;
    }
    EXPECT_EQ(a.width, b.width);
    EXPECT_EQ(a.color, b.color);
}

TEST(ParticleFiles, EveryFormatAndPositionTypeReadsTheSameParticles) {
    const ImportedParticles ref = import(write_ply(three_points(), "binary_little_endian"));
    ASSERT_EQ(ref.strokes.size(), 3u);
    expect_same(ref, import(write_ply(three_points(), "binary_big_endian")));
    expect_same(ref, import(write_ply(three_points(), "ascii")));
    expect_same(ref, import(write_ply(three_points("double"), "binary_little_endian")));
    // The values themselves: a pscale is a radius (width = 2 x pscale), uchar colours are sRGB.
    EXPECT_EQ(ref.strokes.position[1], glm::vec3(1.5f, 2.0f, -4.0f));
    EXPECT_FLOAT_EQ(ref.width[1], 0.4f);
    EXPECT_FLOAT_EQ(ref.color[0].x, 1.0f);
    EXPECT_FLOAT_EQ(ref.color[0].y, 0.0f);
    EXPECT_NEAR(ref.color[2].x, std::pow((128 / 255.0 + 0.055) / 1.055, 2.4), 1e-5);
    // Normals are normalised ((0, 0, 2) is +z), and every stroke is a base stroke.
    EXPECT_LT(glm::length(ref.strokes.normal(2) - glm::vec3(0, 0, 1)), 1e-3f);
    for (size_t i = 0; i < 3; ++i) EXPECT_GT(ref.strokes.fade_begin(i), 1.0f);
}

TEST(ParticleFiles, BlenderZUpScaleAndPositionPlaceTheParticles) {
    ParticleFileDesc d;
    d.up = UpAxis::kZ;
    d.scale = 2;
    d.position = {10, 0, -5};
    const ImportedParticles p = import(write_ply(three_points(), "ascii"), d);
    // Blender's (1.5, 2, -4) is pleinair's (1.5, -4, -2), then scaled and moved.
    EXPECT_EQ(p.strokes.position[1], glm::vec3(13.0f, -8.0f, -9.0f));
    // Its normal (1, 0, 0) stays; (0, 0, 2), Blender's up, is pleinair's up.
    EXPECT_LT(glm::length(p.strokes.normal(2) - glm::vec3(0, 1, 0)), 1e-3f);
    EXPECT_FLOAT_EQ(p.width[1], 0.8f);  // sizes scale with the positions
}

TEST(ParticleFiles, LabelsFollowTheIdNotTheOrder) {
    std::vector<PlyColumn> c = three_points();
    std::vector<PlyColumn> r = c;
    for (PlyColumn& col : r) std::swap(col.values[0], col.values[2]);
    const ImportedParticles a = import(write_ply(c, "ascii")), b = import(write_ply(r, "ascii"));
    EXPECT_EQ(a.strokes.label[0], b.strokes.label[2]);
    EXPECT_EQ(a.strokes.label[2], b.strokes.label[0]);
    EXPECT_NE(a.strokes.label[0], a.strokes.label[1]);
    // Another file key (another entry of /particles) gives other labels for the same ids.
    const ImportedParticles other =
        import_particles(write_ply(c, "ascii"), "cloud.ply", {}, 8, kSun, 1e5);
    EXPECT_NE(a.strokes.label[0], other.strokes.label[0]);
}

TEST(ParticleFiles, MissingAttributesHaveDefaults) {
    // Positions alone: the material's size, labels from the index (distinct, in (0, 1)), each
    // particle facing the sun, the palette's colour.
    std::vector<PlyColumn> c = {{"float", "x", {}}, {"float", "y", {}}, {"float", "z", {}}};
    for (int i = 0; i < 1000; ++i)
        for (int k = 0; k < 3; ++k) c[static_cast<size_t>(k)].values.push_back(i * 0.01 * (k + 1));
    const ImportedParticles p = import(write_ply(c, "binary_little_endian"));
    EXPECT_TRUE(p.width.empty());
    EXPECT_TRUE(p.color.empty());
    std::set<float> labels(p.strokes.label.begin(), p.strokes.label.end());
    EXPECT_EQ(labels.size(), 1000u);
    EXPECT_GT(*labels.begin(), 0.0f);
    EXPECT_LT(*labels.rbegin(), 1.0f);
    for (size_t i = 0; i < p.strokes.size(); ++i)
        ASSERT_LT(glm::length(p.strokes.normal(i) - kSun), 1e-3f);
    // "none" ignores an attribute the file has.
    ParticleFileDesc d;
    d.size = d.color = d.normal = "none";
    const ImportedParticles q = import(write_ply(three_points(), "ascii"), d);
    EXPECT_TRUE(q.width.empty());
    EXPECT_TRUE(q.color.empty());
    EXPECT_LT(glm::length(q.strokes.normal(2) - kSun), 1e-3f);
    // Named attributes are read from the properties named (Houdini's Cd as floats, linear).
    std::vector<PlyColumn> h = {{"float", "x", {1}},       {"float", "y", {2}},
                                {"float", "z", {3}},       {"float", "Cd_r", {0.5}},
                                {"float", "Cd_g", {0.25}}, {"float", "Cd_b", {0}},
                                {"double", "width", {0.3}}};
    d = {};
    d.color = "Cd_r, Cd_g, Cd_b";
    d.size = "width";
    d.size_to_width = 1;
    const ImportedParticles hp = import(write_ply(h, "binary_little_endian"), d);
    ASSERT_EQ(hp.color.size(), 1u);
    EXPECT_EQ(hp.color[0], Color(0.5f, 0.25f, 0.0f));
    EXPECT_FLOAT_EQ(hp.width[0], 0.3f);
}

// Every class of hostile file: exit 2's one line names the file and where.
TEST(ParticleFiles, HostileFilesNameTheVertexAndProperty) {
    const std::string good = write_ply(three_points(), "binary_little_endian");
    struct Case {
        std::string bytes;
        std::string expect;
    };
    std::vector<PlyColumn> nan_x = three_points(), inf_size = three_points();
    nan_x[0].values[2] = NAN;
    inf_size[3].values[1] = INFINITY;
    std::vector<PlyColumn> float_id = three_points(), far = three_points(), zero_n = three_points();
    float_id[4].type = "float";
    far[2].values[1] = 2e5;
    for (int k = 5; k < 8; ++k) zero_n[static_cast<size_t>(k)].values[1] = 0;
    std::vector<PlyColumn> neg_size = three_points(), int_color = three_points();
    neg_size[3].values[0] = -0.1;
    std::vector<PlyColumn> tiny_size = three_points();  // found by fuzzing: 0 once in float
    tiny_size[3].type = "double";
    tiny_size[3].values[2] = 1e-45;
    int_color[8].type = "int";
    std::vector<PlyColumn> no_z = three_points();
    no_z.erase(no_z.begin() + 2);
    const Case cases[] = {
        {good.substr(0, good.size() - 20), "only 85 bytes follow: vertex 2 is the first missing"},
        {write_ply(three_points(), "binary_little_endian", 4), "promises 4 elements"},
        {write_ply(three_points(), "binary_little_endian", 2), "bytes follow the 2 vertices"},
        {write_ply(three_points(), "ascii", 2), "more values follow the 2 vertices"},
        {write_ply(three_points(), "ascii", 5), "vertex 3 property x: the file ends here"},
        {write_ply(nan_x, "binary_little_endian"), "vertex 2 property x: not a finite number"},
        {write_ply(nan_x, "ascii"), "vertex 2 property x: not a finite number"},
        {write_ply(inf_size, "binary_big_endian"), "vertex 1 property pscale: not a finite"},
        {write_ply(float_id, "ascii"), "property id: a label must be an integer type"},
        {write_ply(far, "ascii"), "vertex 1 property z: placed at 200000, beyond the world"},
        {write_ply(zero_n, "ascii"), "vertex 1 property nx: a normal of zero length"},
        {write_ply(neg_size, "ascii"), "vertex 0 property pscale: a size must be > 0"},
        {write_ply(tiny_size, "binary_little_endian"),
         "vertex 2 property pscale: a stroke 2e-45 wide, too narrow to paint"},
        {write_ply(int_color, "ascii"), "property red: a colour is uchar, ushort, float"},
        {write_ply(no_z, "ascii"), "no vertex property \"z\" (a particle file needs x, y and z)"},
        {"ply\nformat ascii 1.0\nelement vertex 1\nproperty uchar x\nproperty float y\n"
         "property float z\nend_header\n300 0 0\n",
         "vertex 0 property x: expected a whole number that fits uchar, got \"300\""},
        {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n1e999\n",
         "vertex 0 property x: not a finite number (\"1e999\" is out of range)"},
        {"ply\nformat binary_little_endian 1.0\nelement vertex 18446744073709551615\n"
         "property float x\nend_header\n",
         "over the limit of"},
        {"ply\nformat binary_little_endian 1.0\nelement vertex 1000\nproperty float x\n"
         "end_header\n",
         "promises 1000 elements of at least 4 bytes, but only 0 bytes follow"},
        {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n", "no end_header"},
        {"ply\nformat ascii 2.0\nend_header\n", "header line 2: expected \"format"},
        {"ply\nformat ascii 1.0\nelement face 1\nproperty list uchar int vertex_indices\n"
         "end_header\n3 0 1 2\n",
         "no \"element vertex\""},
        {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float x\n"
         "end_header\n",
         "a second property \"x\""},
        {"ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x\nend_header\n",
         "unknown property type \"quad\""},
        {"solid cube\n", "not a PLY file"},
        // Found by fuzzing: no newline after end_header put the data one byte past the end.
        {"ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nend_header",
         "but only 0 bytes follow"},
        {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header",
         "only 0 bytes follow: vertex 0 is the first missing"},
        {"", "not a PLY file"},
    };
    for (const Case& c : cases) {
        const std::string e = error_of([&] { import(c.bytes); });
        EXPECT_NE(e.find("cloud.ply: "), std::string::npos) << e;
        EXPECT_NE(e.find(c.expect), std::string::npos)
            << "expected \"" << c.expect << "\" in: " << e;
        EXPECT_EQ(e.find('\n'), std::string::npos) << e;
    }
    // The vertex limit is a limit: raised, the count is then checked against the bytes.
    const uint64_t before = limits().particles;
    limits().particles = 2;
    EXPECT_NE(error_of([&] { import(good); }).find("--limit particles=N"), std::string::npos);
    limits().particles = before;
}

TEST(ParticleFiles, ElementsBeforeTheVerticesAndListsOnThemAreSkipped) {
    // A face element first (lists), a list property among the vertex's scalars.
    const std::string ascii =
        "ply\nformat ascii 1.0\nelement face 2\nproperty list uchar int vertex_indices\n"
        "element vertex 2\nproperty float x\nproperty list uchar float extra\nproperty float y\n"
        "property float z\nend_header\n3 0 1 2\n4 0 1 2 3\n1 2 7 8 2 3\n4 0 5 6\n";
    const PlyVertices v = read_ply_vertices(ascii, "a.ply");
    ASSERT_EQ(v.count, 2u);
    EXPECT_EQ(v.find("x")->values, (std::vector<double>{1, 4}));
    EXPECT_EQ(v.find("y")->values, (std::vector<double>{2, 5}));
    EXPECT_EQ(v.find("z")->values, (std::vector<double>{3, 6}));
    EXPECT_EQ(v.find("extra"), nullptr);
    // An element of no properties takes no bytes, whatever its count: skipped at once
    // (fuzzing found one of 2.7e16 walked one by one; tests/fuzz/regressions/particle_file).
    const PlyVertices w = read_ply_vertices(
        "ply\nformat ascii 1.0\nelement nothing 26666666646666663\nelement vertex 1\n"
        "property float x\nproperty float y\nproperty float z\nend_header\n1 2 3\n",
        "b.ply");
    ASSERT_EQ(w.count, 1u);
    EXPECT_EQ(w.find("z")->values, std::vector<double>{3});
}

// A scene with a particle file: painted, its colour used as asked, and a broken file refused
// through the command line with one line and nothing written.
class ParticleScene : public ::testing::Test {
  protected:
    std::filesystem::path dir = test::temp_dir("particle-scene");
    std::string scene(double color_amount, const std::string& file = "cloud.ply") {
        return R"({"camera": {"position": [0, 1.5, 6], "look_at": [0, 0.5, 0], "fov": 40,
                   "width": 64, "height": 48},
                   "sun": {"direction": [0, 1, 0.3]},
                   "materials": {"grass": {"shader": "grass"}},
                   "particles": [{"file": ")" +
               file + R"(", "material": "grass", "color_amount": )" + std::to_string(color_amount) +
               "}]}";
    }
    void write(const std::string& name, const std::string& bytes) {
        std::ofstream(dir / name, std::ios::binary) << bytes;
    }
    Frame paint(double color_amount) {
        return paint_still(parse_scene(scene(color_amount), (dir / "s.json").string()), true);
    }
};

TEST_F(ParticleScene, PaintedInTheFilesColourAsMuchAsAsked) {
    // A ball of red particles, 1,500 of them.
    std::vector<PlyColumn> c = {{"float", "x", {}},     {"float", "y", {}},
                                {"float", "z", {}},     {"uchar", "red", {}},
                                {"uchar", "green", {}}, {"uchar", "blue", {}}};
    for (int i = 0; i < 1500; ++i) {
        const double a = i * 2.399963, h = 1.0 - 2.0 * (i + 0.5) / 1500;
        const double r = std::sqrt(1 - h * h);
        const double v[] = {r * std::cos(a), 0.6 + h, r * std::sin(a), 200, 30, 20};
        for (size_t k = 0; k < 6; ++k) c[k].values.push_back(v[k]);
    }
    write("cloud.ply", write_ply(c, "binary_little_endian"));
    const Frame palette = paint(0), red = paint(1);
    double covered = 0, redder = 0;
    for (size_t i = 0; i < palette.rgba.size(); i += 4) {
        ASSERT_TRUE(std::isfinite(red.rgba[i]) && std::isfinite(red.rgba[i + 1]));
        if (palette.alpha[i / 4] < 0.9f) continue;  // the strokes', not the background's
        covered += 1;
        // The grass palette's olives have red and green close (within a third); the file's
        // colour (sRGB 200, 30, 20) makes red twice green or more.
        redder +=
            red.rgba[i] > 2 * red.rgba[i + 1] && palette.rgba[i] < 1.35f * palette.rgba[i + 1];
    }
    EXPECT_GT(covered, 300);
    EXPECT_GT(redder / covered, 0.8) << covered;
    // color_amount 0 is the palette alone, bit for bit, whatever the file's colours.
    std::vector<PlyColumn> no_color(c.begin(), c.begin() + 3);
    write("cloud.ply", write_ply(no_color, "binary_little_endian"));
    const Frame plain = paint(0.5);
    EXPECT_EQ(plain.rgba, palette.rgba);
}

TEST_F(ParticleScene, ABrokenFileIsOneLineAndNothingIsWritten) {
    std::vector<PlyColumn> c = three_points();
    c[1].values[1] = NAN;
    write("cloud.ply", write_ply(c, "binary_little_endian"));
    write("s.json", scene(1));
    const auto out = dir / "out.png";
    const auto r =
        test::run_pleinair("render " + (dir / "s.json").string() + " -o " + out.string());
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("/particles/0/file: " + (dir / "cloud.ply").string() +
                         ": vertex 1 property y: not a finite number"),
              std::string::npos)
        << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out));
    // A missing file and a missing material, each named.
    write("s.json", scene(1, "nowhere.ply"));
    const auto m =
        test::run_pleinair("render " + (dir / "s.json").string() + " -o " + out.string());
    EXPECT_EQ(m.exit_code, 2);
    EXPECT_NE(m.err.find("nowhere.ply: cannot read the file"), std::string::npos) << m.err;
    write("s.json", R"({"particles": [{"file": "cloud.ply", "material": "moss"}]})");
    const auto n =
        test::run_pleinair("render " + (dir / "s.json").string() + " -o " + out.string());
    EXPECT_EQ(n.exit_code, 2);
    EXPECT_NE(n.err.find("/particles/0/material: no material \"moss\""), std::string::npos)
        << n.err;
    // Attribute names are counted with the scene: a normal is three properties.
    write("s.json", R"({"materials": {"grass": {"shader": "grass"}},
                        "particles": [{"file": "cloud.ply", "material": "grass",
                                       "normal": "N", "size": "a,b"}]})");
    const auto a =
        test::run_pleinair("render " + (dir / "s.json").string() + " -o " + out.string());
    EXPECT_EQ(a.exit_code, 2);
    EXPECT_NE(a.err.find("/particles/0/size: expected one property name, \"none\" or \"\", got "
                         "\"a,b\""),
              std::string::npos)
        << a.err;
    EXPECT_NE(a.err.find("/particles/0/normal: expected three property names, comma-separated"),
              std::string::npos)
        << a.err;
}

}  // namespace
}  // namespace pleinair

namespace pleinair {
namespace {

TEST(ParticleFiles, AClassPropertyPicksEachParticlesMaterial) {
    std::vector<PlyColumn> c = three_points();
    c.push_back({"uchar", "class", {2, 0, 1}});
    ParticleFileDesc d;
    d.material_by = "class";
    d.materials = {5, 3, 9};
    const ImportedParticles p = import(write_ply(c, "ascii"), d);
    EXPECT_EQ(p.strokes.material, (std::vector<uint16_t>{9, 5, 3}));
    // A value past the list, a float class, a class the file lacks: one line naming them.
    c.back().values = {2, 3, 0};
    EXPECT_EQ(error_of([&] { import(write_ply(c, "ascii"), d); }),
              "cloud.ply: vertex 1 property class: a material index must be in 0..2 "
              "(/particles/N/materials lists 3), got 3");
    c.back().type = "float";
    EXPECT_NE(error_of([&] {
                  import(write_ply(c, "ascii"), d);
              }).find("property class: a material index must be an integer type, got float"),
              std::string::npos);
    c.pop_back();
    EXPECT_NE(
        error_of([&] { import(write_ply(c, "ascii"), d); }).find("no vertex property \"class\""),
        std::string::npos);
}

// A crown of particles (class 1) floating above a bed of ground particles (class 0) in one file.
std::vector<PlyColumn> crown_over_ground() {
    std::vector<PlyColumn> c = {{"float", "x", {}},    {"float", "y", {}},  {"float", "z", {}},
                                {"float", "nx", {}},   {"float", "ny", {}}, {"float", "nz", {}},
                                {"uchar", "class", {}}};
    auto add = [&](double x, double y, double z, int cls) {
        const double v[] = {x, y, z, 0, 1, 0, double(cls)};
        for (size_t k = 0; k < 7; ++k) c[k].values.push_back(v[k]);
    };
    for (int i = -30; i <= 30; ++i)
        for (int j = -30; j <= 30; ++j) add(0.1 * i, 0.0, 0.1 * j, 0);
    for (int i = 0; i < 3000; ++i) {
        const double a = i * 2.399963, h = 1.0 - 2.0 * (i + 0.5) / 3000;
        const double r = std::sqrt(1 - h * h);
        add(0.5 * r * std::cos(a), 1.5 + 0.5 * h, 0.5 * r * std::sin(a), 1);
    }
    return c;
}

TEST_F(ParticleScene, ParticlesCastTheSunsShadowsOnEachOther) {
    write("crown.ply", write_ply(crown_over_ground(), "binary_little_endian"));
    auto ground_light = [&](bool casts) {
        const std::string json =
            R"({"camera": {"position": [0, 1.5, 6], "look_at": [0, 0.5, 0], "width": 64, "height": 48},
                "sun": {"direction": [0, 1, 0], "casts_shadows": true},
                "materials": {"grass": {"shader": "grass"}, "leaves": {"shader": "grass"}},
                "particles": [{"file": "crown.ply", "material_by": "class",
                               "materials": "grass, leaves", "casts_shadows": )" +
            std::string(casts ? "true" : "false") + "}]}";
        ShotOptions options;
        options.cache_sun_light = true;
        const Shot shot = build_shot(parse_scene(json, (dir / "s.json").string()), options);
        // Nothing else casts: without the particles no shadow is traced, all light is 1.
        EXPECT_EQ(shot.plan.shadows, casts);
        if (!casts) return std::make_pair(1.0, 1.0);
        // Each ground particle's light (material 0): under the crown (within 0.3 of the axis)
        // and away from it and its strokes' reach (beyond 1.6).
        double under = 0, away = 0;
        int n_under = 0, n_away = 0;
        const size_t trees = shot.trees->size();
        for (size_t c = 0; c < shot.land->chunks.size(); ++c) {
            const SurfaceParticles& S = shot.land->chunks[c];
            for (size_t j = 0; j < S.size(); ++j) {
                if (S.material[j] != 0) continue;
                const float r = glm::length(glm::vec2(S.position[j].x, S.position[j].z));
                bool cast = false;
                const float l = shot.sun_light->light(
                    *shot.sun_rays, trees + c, j,
                    particle_origin(shot, trees + c, SpriteKind::kSurface, j), cast);
                if (r < 0.3f) under += l, ++n_under;
                if (r > 1.6f) away += l, ++n_away;
            }
        }
        EXPECT_GT(n_under, 20);
        EXPECT_GT(n_away, 20);
        return std::make_pair(under / n_under, away / n_away);
    };
    const auto [under, away] = ground_light(true);
    EXPECT_LT(under, 0.5 * away);  // the crown's shadow
    EXPECT_GT(away, 0.95);
    ground_light(false);
}

TEST_F(ParticleScene, AMaterialListWithoutItsPropertyOrNoMaterialIsNamed) {
    write("cloud.ply", write_ply(three_points(), "ascii"));
    auto problem = [&](const std::string& entry) {
        const std::string json =
            R"({"materials": {"grass": {"shader": "grass"}}, "particles": [)" + entry + "]}";
        try {
            parse_scene(json, (dir / "s.json").string());
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    EXPECT_NE(problem(R"({"file": "cloud.ply"})").find("/particles/0/material: required"),
              std::string::npos);
    EXPECT_NE(problem(R"({"file": "cloud.ply", "material_by": "id"})")
                  .find("/particles/0/materials: expected the materials"),
              std::string::npos);
    EXPECT_NE(problem(R"({"file": "cloud.ply", "material_by": "id", "materials": "grass, moss"})")
                  .find("/particles/0/materials"),
              std::string::npos);
}

}  // namespace
}  // namespace pleinair

namespace pleinair {
namespace {

// on_terrain: a scatter laid out on flat ground (y the height above it) stands on the hills,
// each particle at the terrain's height where it is; without a terrain the key is refused.
TEST_F(ParticleScene, OnTerrainStandsEachParticleOnTheGroundUnderIt) {
    write("cloud.ply", write_ply(three_points(), "ascii"));
    auto json = [](bool terrain, bool on) {
        return std::string(R"({"materials": {"grass": {"shader": "grass"}},)") +
               (terrain ? R"("terrain": {"seed": 4, "noise_amplitude": 3, "hills": [
                             {"center": [1, 2], "radius": 9, "height": 5}]},)"
                        : "") +
               R"("particles": [{"file": "cloud.ply", "material": "grass", "on_terrain": )" +
               (on ? "true" : "false") + "}]}";
    };
    const std::string file = (dir / "s.json").string();
    const SceneDesc flat = parse_scene(json(true, false), file);
    const SceneDesc hills = parse_scene(json(true, true), file);
    const auto& a = flat.particles[0].particles->strokes.position;
    const auto& b = hills.particles[0].particles->strokes.position;
    ASSERT_EQ(a.size(), 3u);
    ASSERT_EQ(b.size(), 3u);
    double lifted = 0;
    for (size_t i = 0; i < a.size(); ++i) {
        const double h = terrain_height(hills.terrain.params, hills.terrain.seed, double(a[i].x),
                                        double(a[i].z));
        EXPECT_EQ(b[i].x, a[i].x);
        EXPECT_EQ(b[i].z, a[i].z);
        EXPECT_NEAR(b[i].y, a[i].y + h, 1e-4 * (1 + std::abs(h)));
        lifted += std::abs(h);
    }
    EXPECT_GT(lifted, 1.0) << "the hill lifts the points";
    try {
        parse_scene(json(false, true), file);
        ADD_FAILURE() << "on_terrain without a terrain was accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("/particles/0/on_terrain: needs a /terrain"),
                  std::string::npos)
            << e.what();
    }
}

}  // namespace
}  // namespace pleinair
