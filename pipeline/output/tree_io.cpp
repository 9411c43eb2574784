// Tree output through OpenMesh's IO and nlohmann/json; folders written whole or not at all.
#include "pipeline/output/tree_io.h"

// MeshIO must come before the mesh kernel headers so the readers and writers register.
#include <tbb/parallel_for.h>

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <cstdio>
#include <mutex>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "pipeline/input/error.h"
#include "pipeline/output/partial_files.h"
#include "pipeline/output/write_file.h"

namespace pleinair {

namespace fs = std::filesystem;

namespace {

struct OutTraits : public OpenMesh::DefaultTraits {
    VertexAttributes(OpenMesh::Attributes::Normal);
};
using OutMesh = OpenMesh::PolyMesh_ArrayKernelT<OutTraits>;

OpenMesh::Vec3f world(const glm::vec3& local, const glm::dvec3& origin) {
    glm::dvec3 p = origin + glm::dvec3(local);
    return {static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z)};
}

OutMesh to_openmesh(const QuadMesh& q, const glm::dvec3& origin) {
    OutMesh m;
    m.reserve(q.positions.size(), q.quads.size() * 2, q.quads.size());
    auto normals = vertex_normals(q);
    for (size_t i = 0; i < q.positions.size(); ++i) {
        auto v = m.add_vertex(world(q.positions[i], origin));
        m.set_normal(v, {normals[i].x, normals[i].y, normals[i].z});
    }
    for (const auto& f : q.quads) {
        auto h = m.add_face(OpenMesh::VertexHandle(static_cast<int>(f[0])),
                            OpenMesh::VertexHandle(static_cast<int>(f[1])),
                            OpenMesh::VertexHandle(static_cast<int>(f[2])),
                            OpenMesh::VertexHandle(static_cast<int>(f[3])));
        if (!h.is_valid()) throw std::runtime_error("mesh is not manifold; cannot be written");
    }
    return m;
}

template <class Mesh>
std::string write_to_string(const Mesh& m, const char* ext, OpenMesh::IO::Options opt) {
    // OpenMesh logs every write on its own streams; a command's output is ours to say.
    static const bool quiet = [] {
        omlog().disable();
        omout().disable();
        return true;
    }();
    (void)quiet;
    std::ostringstream out(std::ios::binary);
    // OpenMesh's writers are process-wide singletons that keep per-call state in mutable
    // members (OBJWriter's path_ and material lists, PLYWriter's options_): one call at a time.
    static std::mutex writer_mutex;
    std::lock_guard<std::mutex> lock(writer_mutex);
    // 9 significant digits: floats round-trip through OBJ text.
    if (!OpenMesh::IO::write_mesh(m, out, ext, opt, 9))
        throw std::runtime_error(std::string("OpenMesh could not write ") + ext);
    return out.str();
}

}  // namespace

std::string mesh_obj(const QuadMesh& mesh, const glm::dvec3& origin) {
    return write_to_string(to_openmesh(mesh, origin), ".obj", OpenMesh::IO::Options::VertexNormal);
}

std::string mesh_ply(const QuadMesh& mesh, const glm::dvec3& origin) {
    return write_to_string(to_openmesh(mesh, origin), ".ply",
                           OpenMesh::IO::Options::Binary | OpenMesh::IO::Options::VertexNormal);
}

std::string leaves_ply(const Tree& t, const WindStiffness& stiffness) {
    return leaves_ply(t.leaves, t.origin, t.branches, stiffness);
}

std::string leaves_ply(const LeafParticles& l, const glm::dvec3& origin,
                       const std::vector<BranchInfo>& limbs, const WindStiffness& stiffness) {
    OutMesh m;
    m.reserve(l.size(), 0, 0);
    // Persistent named properties become PLY vertex properties of the same name.
    auto add = [&](auto& handle, const char* name) {
        m.add_property(handle, name);
        m.property(handle).set_persistent(true);
    };
    OpenMesh::VPropHandleT<float> branch_distance, center_distance, label, fade_begin, fade_end;
    // Signed: OpenMesh 9.0's binary PLY writer declares an unsigned int property as "uint" but
    // writes one byte of it, which corrupts every record after it.
    OpenMesh::VPropHandleT<int> tree_id, limb, limb_level;
    OpenMesh::VPropHandleT<float> pivot_x, pivot_y, pivot_z, stiff;
    add(branch_distance, "branch_distance");
    add(center_distance, "center_distance");
    add(label, "label");
    add(tree_id, "tree_id");
    add(fade_begin, "fade_begin");
    add(fade_end, "fade_end");
    add(limb, "limb");
    add(limb_level, "limb_level");
    add(pivot_x, "pivot_x");
    add(pivot_y, "pivot_y");
    add(pivot_z, "pivot_z");
    add(stiff, "stiffness");
    for (size_t i = 0; i < l.size(); ++i) {
        auto v = m.add_vertex(world(l.position[i], origin));
        m.set_normal(v, {l.normal[i].x, l.normal[i].y, l.normal[i].z});
        m.property(branch_distance, v) = l.branch_distance[i];
        m.property(center_distance, v) = l.center_distance[i];
        m.property(label, v) = l.label[i];
        m.property(tree_id, v) = static_cast<int>(l.tree_id[i]);
        m.property(fade_begin, v) = l.fade_begin[i];
        m.property(fade_end, v) = l.fade_end[i];
        const uint32_t k = i < l.limb.size() ? l.limb[i] : 0;
        const BranchInfo* b = k < limbs.size() ? &limbs[k] : nullptr;
        const OpenMesh::Vec3f pivot = world(b ? b->start : glm::vec3(0.0f), origin);
        m.property(limb, v) = static_cast<int>(k);
        m.property(limb_level, v) = b ? b->level : 0;
        m.property(pivot_x, v) = pivot[0];
        m.property(pivot_y, v) = pivot[1];
        m.property(pivot_z, v) = pivot[2];
        m.property(stiff, v) =
            static_cast<float>(b && b->level > 0 ? stiffness.limbs : stiffness.trunk);
    }
    return write_to_string(m, ".ply",
                           OpenMesh::IO::Options::Binary | OpenMesh::IO::Options::VertexNormal |
                               OpenMesh::IO::Options::Custom);
}

std::string tree_json(const Tree& t, const std::string& preset_name,
                      const WindStiffness& stiffness) {
    using ordered_json = nlohmann::ordered_json;
    auto vec = [](const glm::dvec3& v) { return ordered_json::array({v.x, v.y, v.z}); };
    ordered_json j;
    j["preset"] = preset_name;
    j["seed"] = t.seed;
    j["id"] = t.id;
    j["origin"] = vec(t.origin);
    j["center"] = vec(t.origin + glm::dvec3(t.center));
    j["counts"] = {{"control_vertices", t.control.positions.size()},
                   {"control_faces", t.control.quads.size()},
                   {"render_vertices", t.render.positions.size()},
                   {"render_faces", t.render.quads.size()},
                   {"lod_vertices", t.lod.positions.size()},
                   {"lod_faces", t.lod.quads.size()},
                   {"leaves", t.leaves.size()}};
    ordered_json branches = ordered_json::array();
    for (const auto& b : t.branches) {
        branches.push_back({{"id", b.id},
                            {"level", b.level},
                            {"parent", b.parent},
                            {"start", vec(t.origin + glm::dvec3(b.start))},
                            {"end", vec(t.origin + glm::dvec3(b.end))},
                            {"length", b.length},
                            {"base_radius", b.ring_radii.front()},
                            {"tip_radius", b.ring_radii.back()},
                            {"stiffness", b.level > 0 ? stiffness.limbs : stiffness.trunk}});
    }
    j["branches"] = std::move(branches);
    j["stiffness"] = {
        {"trunk", stiffness.trunk}, {"limbs", stiffness.limbs}, {"leaves", stiffness.leaves}};
    return j.dump(2) + "\n";
}

namespace {

// Everything is formatted before the first byte is written.
std::vector<std::pair<std::string, std::string>> tree_files(const Tree& t,
                                                            const std::string& preset_name,
                                                            const TreeOutput& out) {
    std::vector<std::pair<std::string, std::string>> files;
    if (out.format != TreeFormat::kGlb) {
        files = {
            {"control.obj", mesh_obj(t.control, t.origin)},
            {"control.ply", mesh_ply(t.control, t.origin)},
            {"render.obj", mesh_obj(t.render, t.origin)},
            {"render.ply", mesh_ply(t.render, t.origin)},
            {"leaves.ply", leaves_ply(t, out.stiffness)},
        };
        if (!t.lod.quads.empty()) {
            files.emplace_back("lod.obj", mesh_obj(t.lod, t.origin));
            files.emplace_back("lod.ply", mesh_ply(t.lod, t.origin));
        }
    }
    if (out.format != TreeFormat::kObjPly)
        files.emplace_back("tree.glb", tree_glb(t, preset_name, out.stiffness, out.look));
    files.emplace_back("tree.json", tree_json(t, preset_name, out.stiffness));
    return files;
}

// A new folder inside a temporary one: no temporaries of its own, the enclosing one is renamed.
// Errors name `shown`, where the folder will be once renamed.
void make_folder(const fs::path& dir, const fs::path& shown) {
    std::error_code ec;
    fs::create_directory(dir, ec);
    if (ec) throw std::runtime_error("cannot write " + shown.string() + ": " + ec.message());
}

void write_tree_files(const std::vector<std::pair<std::string, std::string>>& files,
                      const fs::path& dir, const fs::path& shown) {
    make_folder(dir, shown);
    for (const auto& [name, bytes] : files) write_new_file(dir / name, bytes, shown / name);
}

void make_parent(const fs::path& dir) {
    fs::path parent = fs::absolute(dir).parent_path();
    std::error_code ec;
    fs::create_directories(parent, ec);
    if (ec) throw std::runtime_error("cannot write " + dir.string() + ": " + ec.message());
}

std::string member_folder(const std::string& preset_name, const Tree& t) {
    char name[64];
    std::snprintf(name, sizeof name, "%s-%03u-seed-%llu", preset_name.c_str(), t.id,
                  static_cast<unsigned long long>(t.seed));
    return name;
}

}  // namespace

bool parse_tree_format(const std::string& name, TreeFormat& format) {
    if (name == "all") return format = TreeFormat::kAll, true;
    if (name == "glb") return format = TreeFormat::kGlb, true;
    if (name == "obj-ply") return format = TreeFormat::kObjPly, true;
    return false;
}

void check_output_folder(const fs::path& dir, const std::string& marker) {
    std::error_code ec;
    auto status = fs::symlink_status(dir, ec);
    if (!fs::exists(status)) return;
    if (fs::is_symlink(status))
        throw InputError("--out", "", dir.string() + " is a symbolic link; give the folder itself");
    if (!fs::is_directory(status))
        throw InputError("--out", "", dir.string() + " exists and is not a directory");
    if (fs::is_empty(dir, ec) || fs::exists(dir / marker, ec)) return;
    throw InputError("--out", "",
                     dir.string() + " is a folder without " + marker +
                         ": the output replaces its folder as a whole, so give a new or empty "
                         "folder, or an earlier output of the same command");
}

void write_tree(const Tree& t, const std::string& preset_name, const fs::path& dir,
                const TreeOutput& out) {
    check_output_folder(dir, "tree.json");
    auto files = tree_files(t, preset_name, out);
    make_parent(dir);
    PartialOutput tmp(dir);
    write_tree_files(files, tmp.path(), dir);
    tmp.commit();
}

void write_family(const std::vector<Tree>& trees, const std::string& preset_name,
                  uint64_t base_seed, const fs::path& dir, const TreeOutput& out) {
    check_output_folder(dir, "family.json");
    make_parent(dir);
    PartialOutput tmp(dir);
    make_folder(tmp.path(), dir);
    // Writing costs more than growing: members are converted and written in parallel, each into
    // its own folder (OpenMesh's own formatting step takes one member at a time).
    tbb::parallel_for(size_t(0), trees.size(), [&](size_t i) {
        const std::string member = member_folder(preset_name, trees[i]);
        write_tree_files(tree_files(trees[i], preset_name, out), tmp.path() / member, dir / member);
    });
    nlohmann::ordered_json index;
    index["preset"] = preset_name;
    index["base_seed"] = base_seed;
    index["members"] = nlohmann::ordered_json::array();
    for (const Tree& t : trees)
        index["members"].push_back(
            {{"index", t.id}, {"seed", t.seed}, {"dir", member_folder(preset_name, t)}});
    write_new_file(tmp.path() / "family.json", index.dump(2) + "\n", dir / "family.json");
    tmp.commit();
}

}  // namespace pleinair
