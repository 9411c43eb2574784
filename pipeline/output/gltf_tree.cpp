// tree.glb: bark and leaf cards of a generated tree as glTF 2.0 through GltfBuilder.
#include "pipeline/output/gltf_tree.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <glm/geometric.hpp>
#include <unordered_map>

#include "pipeline/output/gltf_builder.h"
#include "pipeline/output/image_io.h"
#include "shading/noise.h"
#include "shading/portable_math.h"

namespace pleinair {

namespace {

constexpr double kTwoPi = 6.283185307179586;
constexpr int kAtlasSide = 4;  // the leaf atlas holds kAtlasSide^2 strokes

// A unit vector at right angles to unit `a`, the same for the same `a`.
glm::dvec3 perpendicular(const glm::dvec3& a) {
    const glm::dvec3 ref = std::abs(a.y) < 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0);
    return glm::normalize(glm::cross(ref, a));
}

// One segment of a limb's skeleton (ring s to ring s + 1) with a frame carried along the limb
// by projection, so u does not jump from one segment to the next.
struct Segment {
    glm::dvec3 start, axis, e1, e2;  // axis unit
    double length, along, r0, r1;    // along: skeleton length before it
    double circumference;            // of the limb's base ring: v's unit
};

std::vector<Segment> skeleton_segments(const std::vector<BranchInfo>& limbs) {
    std::vector<Segment> out;
    for (const BranchInfo& b : limbs) {
        const auto& c = b.ring_centers;
        if (c.size() < 2) continue;
        const double base_r = b.ring_radii.empty() ? 0.1 : std::max<double>(b.ring_radii[0], 1e-4);
        glm::dvec3 e1(0.0);
        double along = 0;
        for (size_t s = 0; s + 1 < c.size(); ++s) {
            Segment g;
            g.start = glm::dvec3(c[s]);
            glm::dvec3 d = glm::dvec3(c[s + 1]) - g.start;
            g.length = glm::length(d);
            if (!(g.length > 1e-9)) continue;
            g.axis = d / g.length;
            glm::dvec3 p = e1 - glm::dot(e1, g.axis) * g.axis;
            e1 = glm::length(p) > 1e-6 ? glm::normalize(p) : perpendicular(g.axis);
            g.e1 = e1;
            g.e2 = glm::cross(g.axis, e1);
            g.along = along;
            g.r0 = s < b.ring_radii.size() ? b.ring_radii[s] : base_r;
            g.r1 = s + 1 < b.ring_radii.size() ? b.ring_radii[s + 1] : g.r0;
            g.circumference = kTwoPi * base_r;
            along += g.length;
            out.push_back(g);
        }
    }
    return out;
}

// How far `p` lies from the segment's surface (its distance from the axis less the radius).
double surface_distance(const Segment& g, const glm::dvec3& p, double& t) {
    t = std::clamp(glm::dot(p - g.start, g.axis), 0.0, g.length);
    const double r = g.r0 + (g.r1 - g.r0) * (t / g.length);
    return std::abs(glm::length(p - (g.start + g.axis * t)) - r);
}

// A face across a limb's end (a cap, or the dome Catmull-Clark rounds it into) has corners all
// around the axis: there the texture is laid flat across the axis instead, centred on u 0.5.
glm::vec2 cap_uv(const Segment& g, const glm::dvec3& p) {
    const double t = glm::dot(p - g.start, g.axis);
    const glm::dvec3 d = p - (g.start + g.axis * t);
    return {static_cast<float>(0.5 + glm::dot(d, g.e1) / g.circumference),
            static_cast<float>((g.along + t + glm::dot(d, g.e2)) / g.circumference)};
}

glm::vec2 cylinder_uv(const Segment& g, const glm::dvec3& p) {
    const double t = glm::dot(p - g.start, g.axis);
    const glm::dvec3 d = p - (g.start + g.axis * t);
    const double angle = pmath::atan2(glm::dot(d, g.e2), glm::dot(d, g.e1));
    return {static_cast<float>(angle / kTwoPi + 0.5),
            static_cast<float>((g.along + t) / g.circumference)};
}

struct VertexKey {
    uint32_t vertex;
    float u, v;
    bool operator==(const VertexKey& o) const {
        return vertex == o.vertex && std::memcmp(&u, &o.u, 4) == 0 && std::memcmp(&v, &o.v, 4) == 0;
    }
};
struct VertexKeyHash {
    size_t operator()(const VertexKey& k) const {
        uint32_t u, v;
        std::memcpy(&u, &k.u, 4), std::memcpy(&v, &k.v, 4);
        return (size_t(k.vertex) * 0x9e3779b97f4a7c15ull) ^ (size_t(u) << 21) ^ size_t(v);
    }
};

// The cell of the leaf atlas a label draws, and the label its stroke was drawn with.
int atlas_cell(float label) {
    const int n = kAtlasSide * kAtlasSide;
    return std::min(n - 1, static_cast<int>(label_hash(label, 9) * static_cast<float>(n)));
}
float cell_label(int cell) {
    return (static_cast<float>(cell) + 0.5f) / static_cast<float>(kAtlasSide * kAtlasSide);
}

}  // namespace

GltfSurface bark_surface(const QuadMesh& mesh, const std::vector<BranchInfo>& limbs) {
    const std::vector<Segment> segs = skeleton_segments(limbs);
    const std::vector<glm::vec3> normals = vertex_normals(mesh);
    GltfSurface out;
    std::unordered_map<VertexKey, uint32_t, VertexKeyHash> index;
    index.reserve(mesh.positions.size() * 2);
    for (const glm::uvec4& q : mesh.quads) {
        glm::dvec3 c(0.0);
        for (int k = 0; k < 4; ++k) c += glm::dvec3(mesh.positions[q[k]]) * 0.25;
        // The limb whose surface the face lies on: nearest to the limb's surface, not its axis,
        // so a thin branch's faces beside the trunk stay the branch's.
        const Segment* best = nullptr;
        double best_d = 1e300, t;
        for (const Segment& g : segs)
            if (double d = surface_distance(g, c, t); d < best_d) best_d = d, best = &g;
        glm::vec2 uv[4];
        for (int k = 0; k < 4; ++k)
            uv[k] = best ? cylinder_uv(*best, glm::dvec3(mesh.positions[q[k]])) : glm::vec2(0.0f);
        // Across the seam some corners read u near 1 and others near 0: those move past 1, and
        // their vertices are split from the neighbours' on the other side.
        float lo = 1, hi = 0;
        for (const auto& w : uv) lo = std::min(lo, w.x), hi = std::max(hi, w.x);
        if (hi - lo > 0.5f) {
            lo = 2, hi = -1;
            for (auto& w : uv) {
                if (w.x < 0.5f) w.x += 1.0f;
                lo = std::min(lo, w.x), hi = std::max(hi, w.x);
            }
        }
        if (best && hi - lo > 0.25f)
            for (int k = 0; k < 4; ++k) uv[k] = cap_uv(*best, glm::dvec3(mesh.positions[q[k]]));
        uint32_t corner[4];
        for (int k = 0; k < 4; ++k) {
            const VertexKey key{q[k], uv[k].x, uv[k].y};
            auto [it, fresh] = index.try_emplace(key, static_cast<uint32_t>(out.positions.size()));
            if (fresh) {
                out.positions.push_back(mesh.positions[q[k]]);
                out.normals.push_back(normals[q[k]]);
                out.uv.push_back(uv[k]);
                out.source.push_back(q[k]);
            }
            corner[k] = it->second;
        }
        out.indices.insert(out.indices.end(),
                           {corner[0], corner[1], corner[2], corner[0], corner[2], corner[3]});
    }
    return out;
}

GltfSurface leaf_cards(const Tree& tree, const TreeLook& look, const std::vector<uint32_t>& which,
                       float grow) {
    const LeafParticles& L = tree.leaves;
    const StrokeShaderParams& p = look.leaf_shader;
    GltfSurface out;
    out.positions.reserve(which.size() * 8);
    for (uint32_t i : which) {
        const glm::dvec3 c(L.position[i]);
        glm::dvec3 n(L.normal[i]);
        n = glm::length(n) > 1e-9 ? glm::normalize(n) : glm::dvec3(0, 1, 0);
        const float label = L.label[i];
        const double w = look.unit * p.sprite_size * stroke_size_jitter(p, label) *
                         crown_edge_size(p, L.center_distance[i]) * grow;
        const double hw = 0.5 * w, hl = 0.5 * w * std::max(p.stroke_aspect, 0.1f);
        const glm::dvec3 b0 = perpendicular(n);
        double sn, cs;
        pmath::sincos(kTwoPi * label_hash(label, 5), sn, cs);
        const glm::dvec3 b1 = cs * b0 + sn * glm::cross(n, b0);
        const glm::dvec3 b2 = glm::cross(n, b1);
        const int cell = atlas_cell(label);
        const glm::vec2 uv0(static_cast<float>(cell % kAtlasSide) / kAtlasSide,
                            static_cast<float>(cell / kAtlasSide) / kAtlasSide);
        const float du = 1.0f / kAtlasSide;
        for (const glm::dvec3& b : {b1, b2}) {
            const auto base = static_cast<uint32_t>(out.positions.size());
            const glm::dvec3 corners[4] = {c - hl * n - hw * b, c - hl * n + hw * b,
                                           c + hl * n + hw * b, c + hl * n - hw * b};
            const glm::vec2 uvs[4] = {uv0 + glm::vec2(0, du), uv0 + glm::vec2(du, du),
                                      uv0 + glm::vec2(du, 0), uv0};
            const glm::vec3 face(
                glm::normalize(glm::cross(corners[1] - corners[0], corners[2] - corners[0])));
            for (int k = 0; k < 4; ++k) {
                out.positions.emplace_back(corners[k]);
                out.normals.push_back(face);
                out.uv.push_back(uvs[k]);
                out.source.push_back(i);
            }
            out.indices.insert(out.indices.end(),
                               {base, base + 1, base + 2, base, base + 2, base + 3});
        }
    }
    return out;
}

std::vector<uint8_t> leaf_texture(const TreeLook& look, int cell) {
    const StrokeShaderParams& p = look.leaf_shader;
    const int side = cell * kAtlasSide;
    std::vector<uint8_t> rgba(size_t(side) * side * 4, 0);
    const float max_opacity = std::max(clamp01(p.max_stroke_opacity), 1e-3f);
    for (int k = 0; k < kAtlasSide * kAtlasSide; ++k) {
        const StrokeNoise noise = stroke_noise_for(p, 0.55f, 0.5f, cell_label(k));
        const int x0 = (k % kAtlasSide) * cell, y0 = (k / kAtlasSide) * cell;
        for (int y = 0; y < cell; ++y)
            for (int x = 0; x < cell; ++x) {
                const float s = (static_cast<float>(x) + 0.5f) / static_cast<float>(cell);
                const float t = (static_cast<float>(y) + 0.5f) / static_cast<float>(cell);
                const float v = stroke_noise(noise, s, t, 3);
                const float a = stroke_opacity(p, v, edge_mask(s, t, p.stroke_fullness));
                // Dabs lighter where the noise is high, as the painter's lights sit on a mass.
                const Color c = linear_to_srgb(palette_lookup(look.leaf_palette, 0.25f + 0.6f * v));
                uint8_t* px = &rgba[(size_t(y0 + y) * side + size_t(x0 + x)) * 4];
                px[0] = static_cast<uint8_t>(std::lround(255.0f * clamp01(c.x)));
                px[1] = static_cast<uint8_t>(std::lround(255.0f * clamp01(c.y)));
                px[2] = static_cast<uint8_t>(std::lround(255.0f * clamp01(c.z)));
                px[3] = static_cast<uint8_t>(std::lround(255.0f * clamp01(a / max_opacity)));
            }
    }
    return rgba;
}

namespace {

// Leaf card attributes, one value per card vertex from its particle: what leaves.ply carries.
void add_leaf_attributes(GltfBuilder& g, tinygltf::Primitive& prim, const Tree& tree,
                         const GltfSurface& cards, const WindStiffness& stiffness) {
    const LeafParticles& L = tree.leaves;
    const size_t n = cards.source.size();
    auto scalar = [&](const char* name, auto value) {
        std::vector<float> v(n);
        for (size_t k = 0; k < n; ++k) v[k] = static_cast<float>(value(cards.source[k]));
        prim.attributes[name] = g.add_scalar(v);
    };
    auto vector = [&](const char* name, auto value) {
        std::vector<glm::vec3> v(n);
        for (size_t k = 0; k < n; ++k) v[k] = value(cards.source[k]);
        prim.attributes[name] = g.add_vec3(v);
    };
    auto limb = [&](uint32_t i) -> const BranchInfo* {
        const uint32_t b = i < L.limb.size() ? L.limb[i] : 0;
        return b < tree.branches.size() ? &tree.branches[b] : nullptr;
    };
    scalar("_BRANCH_DISTANCE", [&](uint32_t i) { return L.branch_distance[i]; });
    scalar("_CENTER_DISTANCE", [&](uint32_t i) { return L.center_distance[i]; });
    scalar("_LABEL", [&](uint32_t i) { return L.label[i]; });
    scalar("_TREE_ID", [&](uint32_t i) { return L.tree_id[i]; });
    scalar("_FADE_BEGIN", [&](uint32_t i) { return L.fade_begin[i]; });
    scalar("_FADE_END", [&](uint32_t i) { return L.fade_end[i]; });
    scalar("_LIMB", [&](uint32_t i) { return i < L.limb.size() ? L.limb[i] : 0u; });
    scalar("_LIMB_LEVEL", [&](uint32_t i) { return limb(i) ? limb(i)->level : 0; });
    scalar("_STIFFNESS", [&](uint32_t i) {
        return limb(i) && limb(i)->level > 0 ? stiffness.limbs : stiffness.trunk;
    });
    vector("_PIVOT", [&](uint32_t i) { return limb(i) ? limb(i)->start : glm::vec3(0.0f); });
    vector("_PARTICLE_POSITION", [&](uint32_t i) { return L.position[i]; });
    vector("_PARTICLE_NORMAL", [&](uint32_t i) { return L.normal[i]; });
}

tinygltf::Primitive surface_primitive(GltfBuilder& g, const GltfSurface& s, int material) {
    tinygltf::Primitive prim;
    prim.mode = TINYGLTF_MODE_TRIANGLES;
    prim.material = material;
    prim.attributes["POSITION"] = g.add_positions(s.positions);
    prim.attributes["NORMAL"] = g.add_vec3(s.normals);
    prim.attributes["TEXCOORD_0"] = g.add_vec2(s.uv);
    prim.indices = g.add_indices(s.indices);
    return prim;
}

}  // namespace

// Bark: the palette's middle colour, rough. Leaves: the atlas under an alpha mask, both sides.
TreeMaterials add_tree_materials(GltfBuilder& g, const TreeLook& look, const std::string& prefix) {
    tinygltf::Model& m = g.model();
    TreeMaterials out;
    tinygltf::Material bark;
    bark.name = prefix + "bark";
    const Color b = palette_lookup(look.bark_palette, 0.45f);  // linear, as glTF's factors are
    bark.pbrMetallicRoughness.baseColorFactor = {b.x, b.y, b.z, 1.0};
    bark.pbrMetallicRoughness.metallicFactor = 0.0;
    bark.pbrMetallicRoughness.roughnessFactor = 0.9;
    out.bark = static_cast<int>(m.materials.size());
    m.materials.push_back(bark);

    const int image = g.add_image(encode_png_rgba8(leaf_texture(look), 4 * 128, 4 * 128),
                                  "image/png", prefix + "leaf_strokes");
    tinygltf::Sampler sampler;
    sampler.magFilter = TINYGLTF_TEXTURE_FILTER_LINEAR;
    sampler.minFilter = TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR;
    sampler.wrapS = sampler.wrapT = TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE;
    tinygltf::Texture tex;
    tex.source = image;
    tex.sampler = static_cast<int>(m.samplers.size());
    m.samplers.push_back(sampler);
    tinygltf::Material leaves;
    leaves.name = prefix + "leaves";
    leaves.pbrMetallicRoughness.baseColorTexture.index = static_cast<int>(m.textures.size());
    m.textures.push_back(tex);
    leaves.pbrMetallicRoughness.metallicFactor = 0.0;
    leaves.pbrMetallicRoughness.roughnessFactor = 0.8;
    leaves.alphaMode = "MASK";
    leaves.alphaCutoff = 0.5;
    leaves.doubleSided = true;
    out.leaves = static_cast<int>(m.materials.size());
    m.materials.push_back(leaves);
    return out;
}

namespace {

// One level of detail as a mesh of two primitives (bark, leaves); -1 when it has neither.
int add_level(GltfBuilder& g, const std::string& name, const GltfSurface& bark,
              const GltfSurface& cards, const Tree& tree, const WindStiffness& stiffness,
              TreeMaterials mat) {
    tinygltf::Mesh mesh;
    mesh.name = name;
    if (!bark.indices.empty()) mesh.primitives.push_back(surface_primitive(g, bark, mat.bark));
    if (!cards.indices.empty()) {
        tinygltf::Primitive leaves = surface_primitive(g, cards, mat.leaves);
        add_leaf_attributes(g, leaves, tree, cards, stiffness);
        mesh.primitives.push_back(std::move(leaves));
    }
    if (mesh.primitives.empty()) return -1;
    tinygltf::Model& m = g.model();
    m.meshes.push_back(std::move(mesh));
    return static_cast<int>(m.meshes.size()) - 1;
}

int add_node(GltfBuilder& g, const std::string& name, int mesh) {
    tinygltf::Node node;
    node.name = name;
    node.mesh = mesh;
    g.model().nodes.push_back(std::move(node));
    return static_cast<int>(g.model().nodes.size()) - 1;
}

}  // namespace

TreeMeshes add_tree_meshes(GltfBuilder& g, const Tree& tree, const std::string& name,
                           const WindStiffness& stiffness, const TreeLook& look,
                           TreeMaterials materials, bool low_only) {
    std::vector<uint32_t> all(tree.leaves.size()), kept;
    for (uint32_t i = 0; i < all.size(); ++i) {
        all[i] = i;
        if (tree.leaves.fade_end[i] > 1.0f) kept.push_back(i);
    }
    TreeMeshes out;
    out.kept = kept.size();
    // A tree grown without its low-detail mesh (a scene's) takes its control mesh for bark.
    const QuadMesh& low = tree.lod.quads.empty() ? tree.control : tree.lod;
    const bool has_low = !tree.lod.quads.empty() || low_only;
    if (!low_only)
        out.lod0 = add_level(g, name + "_LOD0", bark_surface(tree.render, tree.branches),
                             leaf_cards(tree, look, all), tree, stiffness, materials);
    if (has_low) {
        // The painter grows the leaves that never fade as the others go (Cook et al.: area by
        // 1 / kept); the cards, which do not spread over the crown as the painter's do, take
        // the whole of it.
        const float grow =
            kept.empty() ? 1.0f
                         : static_cast<float>(std::sqrt(double(all.size()) / double(kept.size())));
        out.lod1 = add_level(g, name + "_LOD1", bark_surface(low, tree.branches),
                             leaf_cards(tree, look, kept, grow), tree, stiffness, materials);
    }
    if (low_only) out.lod0 = out.lod1, out.lod1 = -1;
    return out;
}

int add_tree_lod_node(GltfBuilder& g, const std::string& name, const TreeMeshes& meshes) {
    const int lod0 = add_node(g, name + "_LOD0", meshes.lod0);
    if (meshes.lod1 < 0) return lod0;
    const int lod1 = add_node(g, name + "_LOD1", meshes.lod1);
    // MSFT_lod: an engine that knows it (Babylon.js, glTFast) switches to level 1 below the
    // screen coverage given; one that does not shows level 0 alone, since level 1 is in no
    // scene (Blender 3.4 imports it too, as a second object named _LOD1).
    tinygltf::Model& m = g.model();
    tinygltf::Value::Object lod;
    lod["ids"] = tinygltf::Value(tinygltf::Value::Array{tinygltf::Value(lod1)});
    m.nodes[lod0].extensions["MSFT_lod"] = tinygltf::Value(std::move(lod));
    m.nodes[lod0].extras = to_gltf_value({{"MSFT_screencoverage", {0.25, 0.02}}});
    if (std::find(m.extensionsUsed.begin(), m.extensionsUsed.end(), "MSFT_lod") ==
        m.extensionsUsed.end())
        m.extensionsUsed.push_back("MSFT_lod");
    return lod0;
}

std::string tree_glb(const Tree& tree, const std::string& preset_name,
                     const WindStiffness& stiffness, const TreeLook& look) {
    GltfBuilder g;
    const TreeMaterials materials = add_tree_materials(g, look);
    const std::string name = preset_name + "-seed-" + std::to_string(tree.seed);
    const TreeMeshes meshes = add_tree_meshes(g, tree, name, stiffness, look, materials);
    const int lod0 = add_tree_lod_node(g, name, meshes);
    tinygltf::Model& m = g.model();
    tinygltf::Node root;
    root.name = name;
    root.translation = {tree.origin.x, tree.origin.y, tree.origin.z};
    if (tree.origin == glm::dvec3(0.0)) root.translation.clear();
    root.children = {lod0};
    nlohmann::ordered_json extras;
    extras["generator"] = "pleinair";
    extras["preset"] = preset_name;
    extras["seed"] = tree.seed;
    extras["id"] = tree.id;
    extras["leaves"] = tree.leaves.size();
    extras["kept_leaves"] = meshes.kept;
    extras["stiffness"] = {
        {"trunk", stiffness.trunk}, {"limbs", stiffness.limbs}, {"leaves", stiffness.leaves}};
    root.extras = to_gltf_value(nlohmann::json(extras));
    m.nodes.push_back(std::move(root));
    tinygltf::Scene scene;
    scene.name = name;
    scene.nodes = {static_cast<int>(m.nodes.size()) - 1};
    m.scenes.push_back(scene);
    m.defaultScene = 0;
    return g.glb();
}

}  // namespace pleinair
