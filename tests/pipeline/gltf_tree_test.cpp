// tree.glb read back through tinygltf: counts, custom attributes equal to the particles', the
// bark's seams, leaf cards sized as the painter's strokes, MSFT_lod, extras, and bytes that
// repeat.
#include "pipeline/output/gltf_tree.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <glm/geometric.hpp>

#include "pipeline/output/contact_sheet.h"
#include "pipeline/output/gltf_builder.h"
#include "pipeline/output/tree_io.h"
#include "test_util.h"

namespace pleinair {
namespace {

TreeLook oak_look(const TreeParams& p) {
    const Family f = sheet_family("oak", "oak", p);
    return {f.leaf_shader, f.leaf_palette, f.bark_palette, p.unit};
}

tinygltf::Model load_glb(const std::string& bytes) {
    tinygltf::Model m;
    tinygltf::TinyGLTF loader;
    std::string err, warn;
    EXPECT_TRUE(loader.LoadBinaryFromMemory(&m, &err, &warn,
                                            reinterpret_cast<const unsigned char*>(bytes.data()),
                                            static_cast<unsigned>(bytes.size())))
        << err;
    return m;
}

// An accessor's floats (tightly packed, as GltfBuilder writes them).
std::vector<float> floats(const tinygltf::Model& m, int accessor) {
    const tinygltf::Accessor& a = m.accessors[accessor];
    const tinygltf::BufferView& v = m.bufferViews[a.bufferView];
    const int n = tinygltf::GetNumComponentsInType(a.type);
    std::vector<float> out(a.count * n);
    std::memcpy(out.data(), m.buffers[v.buffer].data.data() + v.byteOffset + a.byteOffset,
                out.size() * 4);
    return out;
}

struct OakGlb : ::testing::Test {
    static void SetUpTestSuite() {
        params = new TreeParams(test::preset("oak"));
        tree = new Tree(generate_tree(*params, 3, {5, {1, 0, 2}, true}));
        WindStiffness st;
        st.trunk = 3, st.limbs = 1.5;
        bytes = new std::string(tree_glb(*tree, "oak", st, oak_look(*params)));
    }
    static void TearDownTestSuite() { delete params, delete tree, delete bytes; }
    static TreeParams* params;
    static Tree* tree;
    static std::string* bytes;
};
TreeParams* OakGlb::params = nullptr;
Tree* OakGlb::tree = nullptr;
std::string* OakGlb::bytes = nullptr;

TEST_F(OakGlb, HoldsTheBarkAndACardPairPerLeafAtLevelZero) {
    tinygltf::Model m = load_glb(*bytes);
    ASSERT_EQ(m.scenes.size(), 1u);
    const tinygltf::Node& root = m.nodes[m.scenes[0].nodes.at(0)];
    EXPECT_EQ(root.name, "oak-seed-3");
    ASSERT_EQ(root.translation, (std::vector<double>{1, 0, 2}));  // the tree's origin
    const tinygltf::Node& lod0 = m.nodes[root.children.at(0)];
    const tinygltf::Mesh& mesh = m.meshes[lod0.mesh];
    ASSERT_EQ(mesh.primitives.size(), 2u);
    const tinygltf::Primitive& bark = mesh.primitives[0];
    const tinygltf::Primitive& leaves = mesh.primitives[1];
    EXPECT_EQ(m.materials[bark.material].name, "bark");
    EXPECT_EQ(m.materials[leaves.material].name, "leaves");
    EXPECT_EQ(m.materials[leaves.material].alphaMode, "MASK");
    EXPECT_TRUE(m.materials[leaves.material].doubleSided);
    EXPECT_EQ(m.accessors[bark.indices].count, tree->render.quads.size() * 6);
    EXPECT_GE(m.accessors[bark.attributes.at("POSITION")].count, tree->render.positions.size());
    EXPECT_EQ(m.accessors[leaves.attributes.at("POSITION")].count, tree->leaves.size() * 8);
    EXPECT_EQ(m.accessors[leaves.indices].count, tree->leaves.size() * 12);
    // The leaf texture is a PNG inside the file.
    ASSERT_EQ(m.images.size(), 1u);
    EXPECT_EQ(m.images[0].mimeType, "image/png");
    EXPECT_EQ(m.images[0].width, 512);
}

TEST_F(OakGlb, LeafCardsCarryEveryParticleAttribute) {
    tinygltf::Model m = load_glb(*bytes);
    const tinygltf::Primitive& leaves = m.meshes[0].primitives[1];
    const LeafParticles& L = tree->leaves;
    auto column = [&](const char* name) { return floats(m, leaves.attributes.at(name)); };
    const auto label = column("_LABEL"), bd = column("_BRANCH_DISTANCE"),
               cd = column("_CENTER_DISTANCE"), fb = column("_FADE_BEGIN"),
               fe = column("_FADE_END"), id = column("_TREE_ID"), limb = column("_LIMB"),
               level = column("_LIMB_LEVEL"), stiff = column("_STIFFNESS"),
               pivot = column("_PIVOT"), pos = column("_PARTICLE_POSITION"),
               nrm = column("_PARTICLE_NORMAL");
    for (size_t i = 0; i < L.size(); i += 41)
        for (size_t k = 8 * i; k < 8 * i + 8; ++k) {
            EXPECT_EQ(label[k], L.label[i]);
            EXPECT_EQ(bd[k], L.branch_distance[i]);
            EXPECT_EQ(cd[k], L.center_distance[i]);
            EXPECT_EQ(fb[k], L.fade_begin[i]);
            EXPECT_EQ(fe[k], L.fade_end[i]);
            EXPECT_EQ(id[k], 5.0f);
            EXPECT_EQ(limb[k], static_cast<float>(L.limb[i]));
            const BranchInfo& b = tree->branches[L.limb[i]];
            EXPECT_EQ(level[k], static_cast<float>(b.level));
            EXPECT_EQ(stiff[k], b.level > 0 ? 1.5f : 3.0f);
            EXPECT_EQ(pivot[3 * k + 1], b.start.y);
            EXPECT_EQ(pos[3 * k + 2], L.position[i].z);
            EXPECT_EQ(nrm[3 * k], L.normal[i].x);
        }
}

TEST_F(OakGlb, TheLowDetailLevelIsMsftLodOutsideTheScene) {
    tinygltf::Model m = load_glb(*bytes);
    ASSERT_EQ(m.extensionsUsed, (std::vector<std::string>{"MSFT_lod"}));
    EXPECT_TRUE(m.extensionsRequired.empty());  // a viewer without it shows level 0
    const tinygltf::Node& lod0 = m.nodes[m.nodes[m.scenes[0].nodes[0]].children[0]];
    const tinygltf::Value& ids = lod0.extensions.at("MSFT_lod").Get("ids");
    ASSERT_EQ(ids.ArrayLen(), 1u);
    const int lod1 = ids.Get(0).GetNumberAsInt();
    for (const tinygltf::Node& n : m.nodes)
        for (int c : n.children) EXPECT_NE(c, lod1);
    EXPECT_NE(m.scenes[0].nodes[0], lod1);
    size_t kept = 0;
    for (float e : tree->leaves.fade_end) kept += e > 1.0f;
    ASSERT_GT(kept, 0u);
    const tinygltf::Mesh& mesh = m.meshes[m.nodes[lod1].mesh];
    EXPECT_EQ(m.accessors[mesh.primitives[0].indices].count, tree->lod.quads.size() * 6);
    EXPECT_EQ(m.accessors[mesh.primitives[1].attributes.at("POSITION")].count, kept * 8);
}

TEST_F(OakGlb, ExtrasNameThePresetAndSeed) {
    tinygltf::Model m = load_glb(*bytes);
    const tinygltf::Value& x = m.nodes[m.scenes[0].nodes[0]].extras;
    EXPECT_EQ(x.Get("preset").Get<std::string>(), "oak");
    EXPECT_EQ(x.Get("seed").GetNumberAsInt(), 3);
    EXPECT_EQ(x.Get("generator").Get<std::string>(), "pleinair");
    EXPECT_EQ(x.Get("stiffness").Get("trunk").GetNumberAsDouble(), 3.0);
}

TEST_F(OakGlb, TheSameTreeGivesTheSameBytes) {
    WindStiffness st;
    st.trunk = 3, st.limbs = 1.5;
    EXPECT_EQ(tree_glb(*tree, "oak", st, oak_look(*params)), *bytes);
}

TEST_F(OakGlb, BarkUvsNeverStretchAcrossTheSeam) {
    const GltfSurface s = bark_surface(tree->render, tree->branches);
    ASSERT_EQ(s.indices.size(), tree->render.quads.size() * 6);
    for (size_t k = 0; k < s.positions.size(); ++k) {
        ASSERT_EQ(s.positions[k], tree->render.positions[s.source[k]]);
        ASSERT_TRUE(std::isfinite(s.uv[k].x) && std::isfinite(s.uv[k].y));
    }
    // Around a limb u runs 0..1; a triangle spanning more than half a turn would be smeared
    // across the whole texture.
    for (size_t t = 0; t < s.indices.size(); t += 3) {
        float lo = 2, hi = -1;
        for (int c = 0; c < 3; ++c)
            lo = std::min(lo, s.uv[s.indices[t + c]].x),
            hi = std::max(hi, s.uv[s.indices[t + c]].x);
        ASSERT_LT(hi - lo, 0.5f) << "triangle " << t / 3;
    }
    // Along the trunk v grows with height.
    size_t low = 0, high = 0;
    for (size_t k = 0; k < s.positions.size(); ++k) {
        if (s.positions[k].y < s.positions[low].y) low = k;
        if (s.positions[k].y > s.positions[high].y && s.positions[k].y < 2.0f) high = k;
    }
    EXPECT_LT(s.uv[low].y, s.uv[high].y);
}

TEST_F(OakGlb, CardsAreCentredOnTheirParticleAndSizedAsItsStroke) {
    const TreeLook look = oak_look(*params);
    const std::vector<uint32_t> which = {0, 17, 300};
    const GltfSurface s = leaf_cards(*tree, look, which);
    ASSERT_EQ(s.positions.size(), 24u);
    const StrokeShaderParams& p = look.leaf_shader;
    for (size_t j = 0; j < which.size(); ++j) {
        const uint32_t i = which[j];
        glm::dvec3 c(0.0);
        for (size_t k = 8 * j; k < 8 * j + 8; ++k) c += glm::dvec3(s.positions[k]) / 8.0;
        EXPECT_LT(glm::length(c - glm::dvec3(tree->leaves.position[i])), 1e-5);
        // Card one's first edge is its width, its second its length along the particle normal.
        const double w = glm::length(s.positions[8 * j + 1] - s.positions[8 * j]);
        const double l = glm::length(s.positions[8 * j + 2] - s.positions[8 * j + 1]);
        const double want = params->unit * p.sprite_size *
                            stroke_size_jitter(p, tree->leaves.label[i]) *
                            crown_edge_size(p, tree->leaves.center_distance[i]);
        EXPECT_NEAR(w, want, 1e-5 * want);
        EXPECT_NEAR(l, want * p.stroke_aspect, 1e-5 * want);
        const glm::dvec3 along =
            glm::normalize(glm::dvec3(s.positions[8 * j + 2] - s.positions[8 * j + 1]));
        EXPECT_NEAR(glm::dot(along, glm::normalize(glm::dvec3(tree->leaves.normal[i]))), 1.0, 1e-5);
        // The two cards cross at right angles.
        EXPECT_NEAR(glm::dot(s.normals[8 * j], s.normals[8 * j + 4]), 0.0, 1e-5);
    }
}

TEST(GltfTree, EveryAtlasCellHoldsAStrokeClearOfItsBorder) {
    const TreeParams params = test::preset("oak");
    const std::vector<uint8_t> rgba = leaf_texture(oak_look(params), 32);
    const int side = 128;
    ASSERT_EQ(rgba.size(), size_t(side) * side * 4);
    for (int cell = 0; cell < 16; ++cell) {
        const int x0 = (cell % 4) * 32, y0 = (cell / 4) * 32;
        int opaque = 0, border = 0;
        for (int y = 0; y < 32; ++y)
            for (int x = 0; x < 32; ++x) {
                const uint8_t a = rgba[(size_t(y0 + y) * side + size_t(x0 + x)) * 4 + 3];
                opaque += a >= 128;
                if (x == 0 || y == 0 || x == 31 || y == 31) border = std::max<int>(border, a);
            }
        EXPECT_GT(opaque, 32 * 32 / 20) << "cell " << cell;
        EXPECT_LT(border, 128) << "cell " << cell;  // no card shows its square edge
    }
}

TEST(GltfTree, AGlbFolderHoldsTreeGlbAndTreeJsonAlone) {
    const auto dir = test::temp_dir("gltf_format");
    const TreeParams params = test::preset("shrub");
    const Tree t = generate_tree(params, 1);
    TreeOutput out;
    out.format = TreeFormat::kGlb;
    write_tree(t, "shrub", dir / "t", out);
    std::vector<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(dir / "t"))
        names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    EXPECT_EQ(names, (std::vector<std::string>{"tree.glb", "tree.json"}));
    TreeFormat f;
    EXPECT_TRUE(parse_tree_format("obj-ply", f));
    EXPECT_EQ(f, TreeFormat::kObjPly);
    EXPECT_FALSE(parse_tree_format("fbx", f));
}

}  // namespace
}  // namespace pleinair
