// Tree files: PLY particles carry every attribute by name, meshes round-trip counts, world
// coordinates are origin + local, and writing is atomic.
#include "pipeline/output/tree_io.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "test_util.h"

namespace pleinair {
namespace {

TEST(TreeIo, LeafPlyHasEveryAttributeByName) {
    Tree t = generate_tree(test::preset("oak"), 3, {7, {0, 0, 0}, true});
    WindStiffness st;
    st.trunk = 3, st.limbs = 1.5;
    test::Ply ply = test::parse_ply(leaves_ply(t, st));
    EXPECT_EQ(ply.format, "binary_little_endian");
    ASSERT_EQ(ply.vertex_count, t.leaves.size());
    EXPECT_EQ(ply.vertex_properties,
              (std::vector<std::string>{"x", "y", "z", "nx", "ny", "nz", "branch_distance",
                                        "center_distance", "label", "tree_id", "fade_begin",
                                        "fade_end", "limb", "limb_level", "pivot_x", "pivot_y",
                                        "pivot_z", "stiffness"}));
    for (size_t i = 0; i < t.leaves.size(); i += 97) {
        EXPECT_EQ(ply.columns["x"][i], t.leaves.position[i].x);
        EXPECT_EQ(ply.columns["ny"][i], t.leaves.normal[i].y);
        EXPECT_EQ(ply.columns["branch_distance"][i], t.leaves.branch_distance[i]);
        EXPECT_EQ(ply.columns["center_distance"][i], t.leaves.center_distance[i]);
        EXPECT_EQ(ply.columns["label"][i], t.leaves.label[i]);
        EXPECT_EQ(ply.columns["tree_id"][i], 7.0);
        EXPECT_EQ(ply.columns["fade_begin"][i], t.leaves.fade_begin[i]);
        EXPECT_EQ(ply.columns["fade_end"][i], t.leaves.fade_end[i]);
        // The wind's rig: the limb it hangs on, that limb's depth, base and stiffness.
        const BranchInfo& b = t.branches[t.leaves.limb[i]];
        EXPECT_EQ(ply.columns["limb"][i], double(t.leaves.limb[i]));
        EXPECT_EQ(ply.columns["limb_level"][i], double(b.level));
        EXPECT_EQ(ply.columns["pivot_y"][i], b.start.y);
        EXPECT_EQ(ply.columns["stiffness"][i], b.level > 0 ? 1.5 : 3.0);
    }
}

TEST(TreeIo, MeshFilesHaveTheMeshCounts) {
    Tree t = generate_tree(test::preset("birch"), 3);
    test::Ply ply = test::parse_ply(mesh_ply(t.render, t.origin));
    EXPECT_EQ(ply.vertex_count, t.render.positions.size());
    EXPECT_EQ(ply.face_count, t.render.quads.size());
    std::string obj = mesh_obj(t.control, t.origin);
    size_t v = 0, f = 0, pos = 0;
    while (pos < obj.size()) {
        size_t end = obj.find('\n', pos);
        if (end == std::string::npos) end = obj.size();
        v += obj.compare(pos, 2, "v ") == 0;
        f += obj.compare(pos, 2, "f ") == 0;
        pos = end + 1;
    }
    EXPECT_EQ(v, t.control.positions.size());
    EXPECT_EQ(f, t.control.quads.size());
}

TEST(TreeIo, FarFromOriginWritesFiniteWorldPositions) {
    TreeOptions o;
    o.origin = {1e5, 3, -1e5};
    Tree t = generate_tree(test::preset("pine"), 4, o);
    test::Ply ply = test::parse_ply(leaves_ply(t.leaves, t.origin));
    for (size_t i = 0; i < t.leaves.size(); ++i) {
        glm::dvec3 expect = o.origin + glm::dvec3(t.leaves.position[i]);
        ASSERT_TRUE(std::isfinite(ply.columns["x"][i]));
        // Within one float step at 1e5 (0.0078).
        ASSERT_NEAR(ply.columns["x"][i], expect.x, 0.008);
        ASSERT_NEAR(ply.columns["z"][i], expect.z, 0.008);
        ASSERT_NEAR(ply.columns["y"][i], expect.y, 1e-5);
    }
}

// The meshes too: the render OBJ written for a tree 1e5 away holds its vertices in world space,
// finite and within a float step of origin + local position.
TEST(TreeIo, FarFromOriginWritesFiniteWorldMeshes) {
    auto dir = test::temp_dir("tree-io-far");
    TreeOptions o;
    o.origin = {1e5, 3, -1e5};
    Tree t = generate_tree(test::preset("pine"), 4, o);
    write_tree(t, "pine", dir / "out");
    std::ifstream in(dir / "out" / "render.obj");
    std::string line;
    size_t i = 0;
    while (std::getline(in, line)) {
        if (line.rfind("v ", 0) != 0) continue;
        std::istringstream v(line.substr(2));
        double x, y, z;
        v >> x >> y >> z;
        ASSERT_LT(i, t.render.positions.size());
        const glm::dvec3 expect = o.origin + glm::dvec3(t.render.positions[i++]);
        ASSERT_TRUE(std::isfinite(x) && std::isfinite(y) && std::isfinite(z));
        ASSERT_NEAR(x, expect.x, 0.008);
        ASSERT_NEAR(y, expect.y, 1e-4);
        ASSERT_NEAR(z, expect.z, 0.008);
    }
    EXPECT_EQ(i, t.render.positions.size());
    std::filesystem::remove_all(dir);
}

TEST(TreeIo, WriteTreeWritesEveryFileAndNoTemporaries) {
    auto dir = test::temp_dir("tree-io");
    Tree t = generate_tree(test::preset("shrub"), 1);
    write_tree(t, "shrub", dir / "out");
    std::vector<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(dir / "out"))
        names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    EXPECT_EQ(names,
              (std::vector<std::string>{"control.obj", "control.ply", "leaves.ply", "lod.obj",
                                        "lod.ply", "render.obj", "render.ply", "tree.glb", "tree.json"}));
    std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace pleinair
