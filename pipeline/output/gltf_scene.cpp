// scene.glb: the landscape's meshes, the trees as instances, the sun and the camera's track.
#include "pipeline/output/gltf_scene.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <map>

#include "pipeline/frame/frame_view.h"
#include "pipeline/output/gltf_builder.h"
#include "pipeline/output/gltf_tree.h"
#include "shading/portable_math.h"

namespace pleinair {

bool parse_instancing(const std::string& name, Instancing& out) {
    if (name == "gpu") return out = Instancing::kGpu, true;
    if (name == "nodes") return out = Instancing::kNodes, true;
    return false;
}

namespace {

// A surface material: its palette's colour halfway up the lightness range, rough.
int surface_material(GltfBuilder& g, const Material& mat, std::map<const Material*, int>& done) {
    if (auto it = done.find(&mat); it != done.end()) return it->second;
    tinygltf::Material m;
    m.name = mat.name;
    const Color c = palette_lookup(mat.palette, 0.5f);  // linear, as glTF's factors are
    m.pbrMetallicRoughness.baseColorFactor = {c.x, c.y, c.z, 1.0};
    m.pbrMetallicRoughness.metallicFactor = 0.0;
    m.pbrMetallicRoughness.roughnessFactor = 0.95;
    g.model().materials.push_back(m);
    return done[&mat] = static_cast<int>(g.model().materials.size()) - 1;
}

// A quad mesh (world) as one node: smooth normals, each quad two triangles (one where its last
// corner repeats the third, as glTF meshes are read in); `uv_from` maps a position to texture
// coordinates, or nothing.
int add_surface(GltfBuilder& g, const std::string& name, const QuadMesh& q, int material,
                const glm::dvec2* uv_min = nullptr, const glm::dvec2* uv_max = nullptr) {
    tinygltf::Primitive prim;
    prim.mode = TINYGLTF_MODE_TRIANGLES;
    prim.material = material;
    prim.attributes["POSITION"] = g.add_positions(q.positions);
    prim.attributes["NORMAL"] = g.add_vec3(vertex_normals(q));
    if (uv_min && uv_max) {
        std::vector<glm::vec2> uv(q.positions.size());
        const glm::dvec2 span = glm::max(*uv_max - *uv_min, glm::dvec2(1e-9));
        for (size_t i = 0; i < uv.size(); ++i)
            uv[i] = glm::vec2((q.positions[i].x - uv_min->x) / span.x,
                              (q.positions[i].z - uv_min->y) / span.y);
        prim.attributes["TEXCOORD_0"] = g.add_vec2(uv);
    }
    std::vector<uint32_t> idx;
    idx.reserve(q.quads.size() * 6);
    for (const glm::uvec4& f : q.quads) {
        idx.insert(idx.end(), {f[0], f[1], f[2]});
        if (f[3] != f[2]) idx.insert(idx.end(), {f[0], f[2], f[3]});
    }
    prim.indices = g.add_indices(idx);
    tinygltf::Mesh mesh;
    mesh.name = name;
    mesh.primitives.push_back(prim);
    tinygltf::Model& m = g.model();
    m.meshes.push_back(mesh);
    tinygltf::Node node;
    node.name = name;
    node.mesh = static_cast<int>(m.meshes.size()) - 1;
    m.nodes.push_back(node);
    return static_cast<int>(m.nodes.size()) - 1;
}

// Rotation about +y by `degrees`, as a glTF quaternion (x, y, z, w).
std::vector<double> turn_about_y(double degrees) {
    const double half = 0.5 * degrees * M_PI / 180.0;
    return {0.0, pmath::sin(half), 0.0, pmath::cos(half)};
}

// The quaternion that turns glTF's camera frame (looking down -z, +y up) to `cam`'s.
glm::dquat camera_rotation(const Camera& cam) {
    return glm::quat_cast(glm::dmat3(cam.right, cam.up, -cam.forward));
}

// Every tree: one mesh per grown member (shared_ptr identity), placed by instancing or by a
// node per tree.
void add_trees(GltfBuilder& g, const SceneDesc& scene, const std::vector<BuiltTree>& trees,
               const SceneExport& options, std::vector<int>& roots) {
    const Instancing instancing = options.instancing;
    std::map<uint32_t, TreeMaterials> family_materials;
    std::map<const Tree*, TreeMeshes> meshes;
    std::map<const Tree*, std::vector<size_t>> drawn;
    std::vector<const Tree*> order;  // members in the order of their first tree
    for (size_t i = 0; i < trees.size(); ++i) {
        const BuiltTree& b = trees[i];
        const Family& f = scene.families[b.family];
        if (!family_materials.count(b.family))
            family_materials[b.family] = add_tree_materials(
                g, {f.leaf_shader, f.leaf_palette, f.bark_palette, f.params.unit}, f.name + "-");
        const Tree* t = &b.tree();
        if (!meshes.count(t)) {
            meshes[t] =
                add_tree_meshes(g, *t, f.name + "-" + std::to_string(b.member), f.params.stiffness,
                                {f.leaf_shader, f.leaf_palette, f.bark_palette, f.params.unit},
                                family_materials[b.family], options.low_detail);
            order.push_back(t);
        }
        drawn[t].push_back(i);
    }
    tinygltf::Model& m = g.model();
    for (const Tree* t : order) {
        const std::vector<size_t>& list = drawn[t];
        const BuiltTree& first = trees[list[0]];
        const std::string name =
            scene.families[first.family].name + "-" + std::to_string(first.member);
        if (instancing == Instancing::kGpu && list.size() > 1) {
            std::vector<glm::vec3> at, scale;
            std::vector<glm::vec4> turn;
            for (size_t i : list) {
                const std::vector<double> q = turn_about_y(trees[i].rotation);
                at.emplace_back(trees[i].position);
                turn.emplace_back(q[0], q[1], q[2], q[3]);
                scale.emplace_back(static_cast<float>(trees[i].scale));
            }
            tinygltf::Node node;
            node.name = name + "-instances";
            node.mesh = meshes[t].lod0;
            tinygltf::Value::Object attributes;
            attributes["TRANSLATION"] = tinygltf::Value(g.add_vec3(at, false));
            attributes["ROTATION"] = tinygltf::Value(g.add_vec4(turn, false));
            attributes["SCALE"] = tinygltf::Value(g.add_vec3(scale, false));
            tinygltf::Value::Object ext;
            ext["attributes"] = tinygltf::Value(std::move(attributes));
            node.extensions["EXT_mesh_gpu_instancing"] = tinygltf::Value(std::move(ext));
            m.nodes.push_back(node);
            roots.push_back(static_cast<int>(m.nodes.size()) - 1);
            if (std::find(m.extensionsUsed.begin(), m.extensionsUsed.end(),
                          "EXT_mesh_gpu_instancing") == m.extensionsUsed.end())
                m.extensionsUsed.push_back("EXT_mesh_gpu_instancing");
            continue;
        }
        for (size_t i : list) {
            const int n = add_tree_lod_node(g, "tree-" + std::to_string(i) + "-" + name, meshes[t]);
            m.nodes[n].translation = {trees[i].position.x, trees[i].position.y,
                                      trees[i].position.z};
            m.nodes[n].rotation = turn_about_y(trees[i].rotation);
            if (trees[i].scale != 1.0) m.nodes[n].scale = std::vector<double>(3, trees[i].scale);
            roots.push_back(n);
        }
    }
}

// The camera: a still's transform, or a track sampled at every frame (linear between frames,
// as Blender bakes its own), at Blender's times.
void add_camera(GltfBuilder& g, const SceneDesc& scene, std::vector<int>& roots) {
    tinygltf::Model& m = g.model();
    tinygltf::Camera cam;
    cam.name = "camera";
    cam.type = "perspective";
    const Camera still = still_view(scene).camera;
    cam.perspective.aspectRatio = double(still.width) / double(still.height);
    cam.perspective.znear = 0.1;
    cam.perspective.zfar = 1e5;  // the world's extent (kMaxWorldCoordinate)
    const double fov =
        scene.camera_track.keys.empty() ? scene.camera_params.fov : scene.camera_track.keys[0].fov;
    cam.perspective.yfov = fov * M_PI / 180.0;
    m.cameras.push_back(cam);
    tinygltf::Node node;
    node.name = "camera";
    node.camera = 0;
    if (!scene.animated() || scene.camera_track.keys.empty()) {
        const glm::dquat q = camera_rotation(still);
        node.translation = {still.eye.x, still.eye.y, still.eye.z};
        node.rotation = {q.x, q.y, q.z, q.w};
        m.nodes.push_back(node);
        roots.push_back(static_cast<int>(m.nodes.size()) - 1);
        return;
    }
    std::vector<float> times;
    std::vector<glm::vec3> at;
    std::vector<glm::vec4> turn;
    for (int f : animation_frames(scene).frames()) {
        const double t = frame_time(f, scene.fps);
        const Camera c = view_at(scene, t).camera;
        const glm::dquat q = camera_rotation(c);
        // Frame / fps, as Blender writes and reads glTF times: frame N here is Blender's frame N
        // (pleinair's own frame N is at (N - 1) / fps).
        times.push_back(static_cast<float>(double(f) / scene.fps));
        at.emplace_back(c.eye);
        turn.emplace_back(q.x, q.y, q.z, q.w);
    }
    const glm::dquat q0 = camera_rotation(view_at(scene, 0.0).camera);
    node.translation = {at[0].x, at[0].y, at[0].z};
    node.rotation = {q0.x, q0.y, q0.z, q0.w};
    m.nodes.push_back(node);
    const int n = static_cast<int>(m.nodes.size()) - 1;
    roots.push_back(n);
    const int input = g.add_scalar(times, false);
    m.accessors[input].minValues = {times.front()};
    m.accessors[input].maxValues = {times.back()};
    tinygltf::Animation anim;
    anim.name = "camera track";
    for (int k = 0; k < 2; ++k) {
        tinygltf::AnimationSampler s;
        s.input = input;
        s.output = k == 0 ? g.add_vec3(at, false) : g.add_vec4(turn, false);
        s.interpolation = "LINEAR";
        anim.samplers.push_back(s);
        tinygltf::AnimationChannel c;
        c.sampler = k;
        c.target_node = n;
        c.target_path = k == 0 ? "translation" : "rotation";
        anim.channels.push_back(c);
    }
    m.animations.push_back(anim);
}

// The sun as KHR_lights_punctual's directional light, shining down -z of its node.
void add_sun(GltfBuilder& g, const SceneDesc& scene, std::vector<int>& roots) {
    tinygltf::Model& m = g.model();
    tinygltf::Value::Object light;
    light["type"] = tinygltf::Value(std::string("directional"));
    light["name"] = tinygltf::Value(std::string("sun"));
    light["intensity"] = tinygltf::Value(3.0);
    tinygltf::Value::Object ext;
    ext["lights"] = tinygltf::Value(tinygltf::Value::Array{tinygltf::Value(std::move(light))});
    m.extensions["KHR_lights_punctual"] = tinygltf::Value(std::move(ext));
    m.extensionsUsed.push_back("KHR_lights_punctual");
    const glm::dvec3 to_sun = glm::normalize(scene.sun_direction);
    // The shortest turn from -z to the light's direction (half-way quaternion).
    const glm::dvec3 a(0, 0, -1), b = -to_sun;
    const double d = glm::dot(a, b);
    const glm::dquat q = d < -0.999999 ? glm::dquat(0, 0, 1, 0)
                                       : glm::normalize(glm::dquat(1 + d, glm::cross(a, b)));
    tinygltf::Node node;
    node.name = "sun";
    node.rotation = {q.x, q.y, q.z, q.w};
    tinygltf::Value::Object use;
    use["light"] = tinygltf::Value(0);
    node.extensions["KHR_lights_punctual"] = tinygltf::Value(std::move(use));
    m.nodes.push_back(node);
    roots.push_back(static_cast<int>(m.nodes.size()) - 1);
}

}  // namespace

std::string scene_glb(const SceneDesc& scene, const BuiltLandscape& land,
                      const std::vector<BuiltTree>& trees, const SceneExport& options) {
    GltfBuilder g;
    std::vector<int> roots;
    std::map<const Material*, int> materials;
    if (land.has_terrain) {
        const TerrainParams& p = scene.terrain.params;
        roots.push_back(
            add_surface(g, "terrain", land.terrain_mesh,
                        surface_material(g, scene.materials[scene.terrain.material], materials),
                        &p.min, &p.max));
    }
    if (land.has_water)
        roots.push_back(
            add_surface(g, "water", land.water_mesh,
                        surface_material(g, scene.materials[scene.water.material], materials)));
    for (size_t i = 0; i < land.rocks.size(); ++i) {
        const bool file = i >= scene.rocks.size();
        const std::string name =
            file ? "mesh-" + std::to_string(i - scene.rocks.size()) : "rock-" + std::to_string(i);
        roots.push_back(
            add_surface(g, name, land.rocks[i],
                        surface_material(g, scene.materials[land.rock_material[i]], materials)));
    }
    add_trees(g, scene, trees, options, roots);
    add_sun(g, scene, roots);
    add_camera(g, scene, roots);
    tinygltf::Model& m = g.model();
    tinygltf::Scene sc;
    sc.name = scene.description.empty() ? "pleinair scene" : scene.description;
    sc.nodes = roots;
    m.scenes.push_back(sc);
    m.defaultScene = 0;
    m.asset.extras = to_gltf_value({{"generator", "pleinair"}, {"fps", scene.fps}});
    return g.glb();
}

}  // namespace pleinair
