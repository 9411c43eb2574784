// glTF scenes in: tinygltf parses; every accessor is checked against its buffer here before a
// byte of it is read, since a file from elsewhere may lie about its sizes.
#include "pipeline/input/gltf_import.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/mat4x4.hpp>
#include <map>
#include <set>

#include "pipeline/input/error.h"
#include "pipeline/input/limits.h"
#include "pipeline/input/presets.h"
#include "shading/portable_math.h"

namespace pleinair {

namespace fs = std::filesystem;

struct GltfDocument {
    tinygltf::Model model;
    std::string file;  // as named in errors
};

namespace {

// Images are not read: a scene takes geometry and cameras from a glTF file, never textures.
bool skip_image(tinygltf::Image*, const int, std::string*, std::string*, int, int,
                const unsigned char*, int, void*) {
    return true;
}

class GltfReader {
  public:
    GltfReader(const GltfDocument& doc, const std::string& source, const std::string& pointer)
        : m_(doc.model), doc_(doc), source_(source), pointer_(pointer) {}

    [[noreturn]] void fail(const std::string& what) const {
        throw InputError(source_, pointer_, doc_.file + ": " + what);
    }

    // An accessor's elements as doubles, `components` a row, after checking that every byte of
    // it lies inside its view and buffer.
    std::vector<double> read(int index, int components, const std::string& what) const {
        if (index < 0 || index >= static_cast<int>(m_.accessors.size()))
            fail(what + ": accessor " + std::to_string(index) + " does not exist");
        const tinygltf::Accessor& a = m_.accessors[index];
        const std::string name = what + " (accessor " + std::to_string(index) + ")";
        if (a.sparse.isSparse) fail(name + ": sparse accessors are not read");
        if (tinygltf::GetNumComponentsInType(a.type) != components)
            fail(name + ": expected " + std::to_string(components) + " components a element");
        const int size = tinygltf::GetComponentSizeInBytes(a.componentType);
        if (size <= 0) fail(name + ": unknown component type " + std::to_string(a.componentType));
        if (a.bufferView < 0 || a.bufferView >= static_cast<int>(m_.bufferViews.size()))
            fail(name + ": no buffer view");
        const tinygltf::BufferView& v = m_.bufferViews[a.bufferView];
        if (v.buffer < 0 || v.buffer >= static_cast<int>(m_.buffers.size()))
            fail(name + ": its view names no buffer");
        const std::vector<unsigned char>& buf = m_.buffers[v.buffer].data;
        const uint64_t elem = uint64_t(size) * components;
        const uint64_t stride = v.byteStride ? v.byteStride : elem;
        if (stride < elem) fail(name + ": byteStride smaller than an element");
        if (uint64_t(v.byteOffset) + v.byteLength > buf.size())
            fail(name + ": its view runs past the end of buffer " + std::to_string(v.buffer));
        if (a.count > 0 &&
            uint64_t(a.byteOffset) + stride * (uint64_t(a.count) - 1) + elem > v.byteLength)
            fail(name + ": " + std::to_string(a.count) + " elements run past the end of its view");
        std::vector<double> out(a.count * components);
        const unsigned char* base = buf.data() + v.byteOffset + a.byteOffset;
        for (size_t i = 0; i < a.count; ++i)
            for (int c = 0; c < components; ++c)
                out[i * components + c] = component(base + i * stride + size_t(c) * size, a);
        return out;
    }

    const tinygltf::Model& model() const { return m_; }

  private:
    static double component(const unsigned char* p, const tinygltf::Accessor& a) {
        auto get = [&](auto v) {
            std::memcpy(&v, p, sizeof v);
            return v;
        };
        double x = 0, max = 1;
        switch (a.componentType) {
            case TINYGLTF_COMPONENT_TYPE_FLOAT:
                return get(float{});
            case TINYGLTF_COMPONENT_TYPE_DOUBLE:
                return get(double{});
            case TINYGLTF_COMPONENT_TYPE_BYTE:
                x = get(int8_t{}), max = 127;
                break;
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
                x = get(uint8_t{}), max = 255;
                break;
            case TINYGLTF_COMPONENT_TYPE_SHORT:
                x = get(int16_t{}), max = 32767;
                break;
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
                x = get(uint16_t{}), max = 65535;
                break;
            case TINYGLTF_COMPONENT_TYPE_INT:
                x = get(int32_t{}), max = 2147483647.0;
                break;
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
                x = get(uint32_t{}), max = 4294967295.0;
                break;
        }
        return a.normalized ? std::max(x / max, -1.0) : x;
    }

    const tinygltf::Model& m_;
    const GltfDocument& doc_;
    const std::string& source_;
    const std::string& pointer_;
};

// A node's own transform: its matrix, or translation * rotation * scale.
glm::dmat4 local_matrix(const tinygltf::Node& n) {
    if (n.matrix.size() == 16) {
        glm::dmat4 m;
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r) m[c][r] = n.matrix[size_t(c) * 4 + r];
        return m;
    }
    glm::dmat4 m(1.0);
    if (n.translation.size() == 3)
        m[3] = glm::dvec4(n.translation[0], n.translation[1], n.translation[2], 1.0);
    glm::dmat4 r(1.0);
    if (n.rotation.size() == 4) {
        glm::dquat q(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]);
        const double len = glm::length(q);
        r = glm::mat4_cast(len > 0 ? q / len : glm::dquat(1, 0, 0, 0));
    }
    glm::dmat4 s(1.0);
    if (n.scale.size() == 3) s[0][0] = n.scale[0], s[1][1] = n.scale[1], s[2][2] = n.scale[2];
    return m * r * s;
}

// Each node's parent (-1 at a root), refusing a node that is its own ancestor.
std::vector<int> parents_of(const GltfReader& rd) {
    const auto& nodes = rd.model().nodes;
    std::vector<int> parent(nodes.size(), -1);
    for (size_t i = 0; i < nodes.size(); ++i)
        for (int c : nodes[i].children) {
            if (c < 0 || c >= static_cast<int>(nodes.size()) || parent[c] != -1 ||
                c == static_cast<int>(i))
                rd.fail("node " + std::to_string(i) + " has a child " + std::to_string(c) +
                        " that does not exist or has another parent");
            parent[c] = static_cast<int>(i);
        }
    for (size_t i = 0; i < nodes.size(); ++i) {
        size_t steps = 0;
        for (int p = parent[i]; p >= 0; p = parent[p])
            if (++steps > nodes.size()) rd.fail("node " + std::to_string(i) + " is in a cycle");
    }
    return parent;
}

glm::dmat4 world_matrix(const GltfReader& rd, const std::vector<int>& parent, int node,
                        const std::map<int, glm::dmat4>& overrides = {}) {
    glm::dmat4 m(1.0);
    for (int n = node; n >= 0; n = parent[n]) {
        auto it = overrides.find(n);
        m = (it != overrides.end() ? it->second : local_matrix(rd.model().nodes[n])) * m;
    }
    return m;
}

std::string node_label(const tinygltf::Model& m, int i) {
    return m.nodes[i].name.empty() ? "node " + std::to_string(i) : "\"" + m.nodes[i].name + "\"";
}

}  // namespace

std::shared_ptr<const GltfDocument> load_gltf(const fs::path& path, const std::string& source,
                                              const std::string& pointer) {
    std::string bytes;
    try {
        bytes = read_input_file(path, "particle_file_mb");
    } catch (const InputError& e) {
        const Problem& p = e.problems().at(0);
        throw InputError(source, pointer,
                         "glTF \"" + path.string() + "\"" +
                             (p.pointer.empty() ? "" : " " + p.pointer) + ": " + p.message);
    }
    const fs::path base = path.parent_path().empty() ? fs::path(".") : path.parent_path();
    return parse_gltf(bytes, path.string(), base, source, pointer);
}

namespace {
bool no_file(const std::string&, void*) { return false; }
std::string same_path(const std::string& p, void*) { return p; }
bool no_read(std::vector<unsigned char>*, std::string* err, const std::string& p, void*) {
    if (err) *err = "external file \"" + p + "\" not read";
    return false;
}
bool no_write(std::string*, const std::string&, const std::vector<unsigned char>&, void*) {
    return false;
}
}  // namespace

std::shared_ptr<const GltfDocument> parse_gltf(const std::string& bytes, const std::string& name,
                                               const fs::path& base, const std::string& source,
                                               const std::string& pointer) {
    auto doc = std::make_shared<GltfDocument>();
    doc->file = name;
    tinygltf::TinyGLTF loader;
    loader.SetImageLoader(skip_image, nullptr);
    if (base.empty()) loader.SetFsCallbacks({no_file, same_path, no_read, no_write, nullptr});
    std::string err, warn;
    const bool binary = bytes.size() >= 4 && bytes.compare(0, 4, "glTF") == 0;
    bool ok = false;
    try {
        ok = binary
                 ? loader.LoadBinaryFromMemory(&doc->model, &err, &warn,
                                               reinterpret_cast<const unsigned char*>(bytes.data()),
                                               static_cast<unsigned>(bytes.size()), base.string())
                 : loader.LoadASCIIFromString(&doc->model, &err, &warn, bytes.data(),
                                              static_cast<unsigned>(bytes.size()), base.string());
    } catch (const std::exception& e) {
        // tinygltf 2.7 indexes some malformed documents with .at() (found by the fuzz target).
        err = std::string("malformed (") + e.what() + ")";
    }
    if (!ok)
        throw InputError(source, pointer,
                         "cannot read glTF \"" + name + "\": " +
                             (err.empty() ? std::string("not a glTF 2.0 file") : first_line(err)));
    return doc;
}

QuadMesh gltf_triangles(const GltfDocument& doc, const std::vector<std::string>& nodes,
                        const glm::dvec3& position, double scale, const std::string& source,
                        const std::string& pointer) {
    const GltfReader rd(doc, source, pointer);
    const tinygltf::Model& m = doc.model;
    const std::vector<int> parent = parents_of(rd);
    std::set<std::string> wanted(nodes.begin(), nodes.end());
    for (const std::string& name : wanted) {
        bool found = false;
        for (const auto& n : m.nodes) found |= n.name == name && n.mesh >= 0;
        if (!found) {
            std::string have;
            for (const auto& n : m.nodes)
                if (n.mesh >= 0 && !n.name.empty()) have += (have.empty() ? "" : ", ") + n.name;
            rd.fail("no mesh node \"" + name + "\" (mesh nodes: " + (have.empty() ? "none" : have) +
                    ")");
        }
    }
    QuadMesh out;
    for (int i = 0; i < static_cast<int>(m.nodes.size()); ++i) {
        const tinygltf::Node& node = m.nodes[i];
        if (node.mesh < 0 || (!wanted.empty() && !wanted.count(node.name))) continue;
        if (node.mesh >= static_cast<int>(m.meshes.size()))
            rd.fail(node_label(m, i) + " names mesh " + std::to_string(node.mesh) +
                    ", which does not exist");
        const glm::dmat4 world = world_matrix(rd, parent, i);
        const tinygltf::Mesh& mesh = m.meshes[node.mesh];
        for (size_t pi = 0; pi < mesh.primitives.size(); ++pi) {
            const tinygltf::Primitive& prim = mesh.primitives[pi];
            const std::string what = "mesh \"" + mesh.name + "\" primitive " + std::to_string(pi);
            const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
            if (mode != TINYGLTF_MODE_TRIANGLES)
                rd.fail(what + " has mode " + std::to_string(mode) +
                        "; only triangles (mode 4) are read");
            auto pos = prim.attributes.find("POSITION");
            if (pos == prim.attributes.end()) rd.fail(what + " has no POSITION");
            const std::vector<double> p = rd.read(pos->second, 3, what + " POSITION");
            const size_t n = p.size() / 3;
            std::vector<double> idx;
            if (prim.indices >= 0) {
                idx = rd.read(prim.indices, 1, what + " indices");
            } else {
                idx.resize(n);
                for (size_t k = 0; k < n; ++k) idx[k] = static_cast<double>(k);
            }
            if (idx.size() % 3 != 0)
                rd.fail(what + ": " + std::to_string(idx.size()) + " indices, not whole triangles");
            const uint32_t first = static_cast<uint32_t>(out.positions.size());
            for (size_t k = 0; k < n; ++k) {
                const glm::dvec3 local(p[3 * k], p[3 * k + 1], p[3 * k + 2]);
                const glm::dvec3 w = position + scale * glm::dvec3(world * glm::dvec4(local, 1.0));
                if (!std::isfinite(local.x) || !std::isfinite(local.y) || !std::isfinite(local.z) ||
                    !(std::abs(w.x) <= 1e5 && std::abs(w.y) <= 1e5 && std::abs(w.z) <= 1e5))
                    rd.fail(what + ": vertex " + std::to_string(k) +
                            " is not finite or lies beyond 1e5 of the origin");
                out.positions.emplace_back(w);
            }
            for (size_t t = 0; t < idx.size(); t += 3) {
                for (int c = 0; c < 3; ++c)
                    if (!(idx[t + c] >= 0 && idx[t + c] < static_cast<double>(n)))
                        rd.fail(what + ": index " + std::to_string(t + c) + " is " +
                                std::to_string(static_cast<int64_t>(idx[t + c])) + ", past its " +
                                std::to_string(n) + " vertices");
                const uint32_t a = first + static_cast<uint32_t>(idx[t]),
                               b = first + static_cast<uint32_t>(idx[t + 1]),
                               c = first + static_cast<uint32_t>(idx[t + 2]);
                out.quads.push_back({a, b, c, c});
            }
            if (out.quads.size() > limits().particles)
                rd.fail("more than " + std::to_string(limits().particles) + " triangles; " +
                        how_to_raise("particles"));
        }
    }
    if (out.quads.empty()) rd.fail("no triangles in the nodes named");
    return out;
}

namespace {

// The value of one animation channel at time t: linear (slerp for rotations), a step, or a
// cubic spline's key values joined linearly (keys land on the samples' times exactly).
std::vector<double> channel_at(const std::vector<double>& times, const std::vector<double>& values,
                               int width, const std::string& interpolation, bool rotation,
                               double t) {
    const bool cubic = interpolation == "CUBICSPLINE";
    auto key = [&](size_t k) {
        const size_t at = (cubic ? 3 * k + 1 : k) * width;
        return std::vector<double>(values.begin() + at, values.begin() + at + width);
    };
    if (t <= times.front()) return key(0);
    if (t >= times.back()) return key(times.size() - 1);
    const size_t k = std::upper_bound(times.begin(), times.end(), t) - times.begin() - 1;
    if (interpolation == "STEP") return key(k);
    const double f = (t - times[k]) / std::max(times[k + 1] - times[k], 1e-12);
    std::vector<double> a = key(k), b = key(k + 1);
    if (rotation) {
        // Spherical, the short way round, through pmath (glm::slerp is libm's).
        double d = a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3];
        if (d < 0) {
            for (double& x : b) x = -x;
            d = -d;
        }
        double wa = 1 - f, wb = f;
        if (d < 0.9995) {
            const double theta = pmath::acos(std::min(d, 1.0)), s = pmath::sin(theta);
            wa = pmath::sin((1 - f) * theta) / s, wb = pmath::sin(f * theta) / s;
        }
        std::vector<double> q(4);
        double len = 0;
        for (int c = 0; c < 4; ++c) q[c] = wa * a[c] + wb * b[c], len += q[c] * q[c];
        len = std::sqrt(len);
        for (double& x : q) x = len > 0 ? x / len : x;
        return q;
    }
    for (int c = 0; c < width; ++c) a[c] += (b[c] - a[c]) * f;
    return a;
}

}  // namespace

namespace {

// The camera node named `name` (the first with a camera when empty), checked: perspective, a
// field of view in range. Its yfov in degrees goes to `yfov`.
int find_camera(const GltfReader& rd, const std::string& name, double& yfov) {
    const tinygltf::Model& m = rd.model();
    int node = -1;
    std::string cameras;
    for (int i = 0; i < static_cast<int>(m.nodes.size()); ++i) {
        if (m.nodes[i].camera < 0) continue;
        cameras += (cameras.empty() ? "" : ", ") + node_label(m, i);
        if (node < 0 && (name.empty() || m.nodes[i].name == name)) node = i;
    }
    if (node < 0)
        rd.fail(name.empty() ? "no camera node"
                             : "no camera node \"" + name +
                                   "\" (cameras: " + (cameras.empty() ? "none" : cameras) + ")");
    if (m.nodes[node].camera >= static_cast<int>(m.cameras.size()))
        rd.fail(node_label(m, node) + " names a camera that does not exist");
    const tinygltf::Camera& cam = m.cameras[m.nodes[node].camera];
    if (cam.type != "perspective") rd.fail(node_label(m, node) + " is not a perspective camera");
    yfov = cam.perspective.yfov * 180.0 / M_PI;
    if (!(yfov > 0.001 && yfov < 179)) rd.fail(node_label(m, node) + ": yfov out of range");
    return node;
}

struct Channel {
    int node;
    std::string path, interpolation;
    std::vector<double> times, values;
};

// The animation channels that move `node`: of it or of any node above it, read and checked;
// their sample times go into `times`.
std::vector<Channel> channels_moving(const GltfReader& rd, const std::vector<int>& parent, int node,
                                     std::set<double>& times) {
    std::set<int> chain;
    for (int n = node; n >= 0; n = parent[n]) chain.insert(n);
    std::vector<Channel> channels;
    for (const tinygltf::Animation& anim : rd.model().animations)
        for (const tinygltf::AnimationChannel& ch : anim.channels) {
            if (!chain.count(ch.target_node) || ch.target_path == "weights") continue;
            const std::string what = "animation \"" + anim.name + "\"";
            if (ch.sampler < 0 || ch.sampler >= static_cast<int>(anim.samplers.size()))
                rd.fail(what + " names a sampler that does not exist");
            const tinygltf::AnimationSampler& s = anim.samplers[ch.sampler];
            const int width = ch.target_path == "rotation" ? 4 : 3;
            Channel c{ch.target_node, ch.target_path,
                      s.interpolation.empty() ? "LINEAR" : s.interpolation,
                      rd.read(s.input, 1, what + " times"),
                      rd.read(s.output, width, what + " values")};
            const size_t per = c.interpolation == "CUBICSPLINE" ? 3 : 1;
            if (c.times.empty() || c.values.size() != c.times.size() * per * width)
                rd.fail(what + ": values do not match its times");
            for (size_t k = 0; k < c.times.size(); ++k) {
                if (!std::isfinite(c.times[k]) || (k && !(c.times[k] > c.times[k - 1])))
                    rd.fail(what + ": times must increase");
                times.insert(c.times[k]);
            }
            for (double v : c.values)
                if (!std::isfinite(v)) rd.fail(what + ": a value is not finite");
            channels.push_back(std::move(c));
        }
    return channels;
}

// `node`'s world matrix at time t, its channels and its parents' applied.
glm::dmat4 posed_world(const GltfReader& rd, const std::vector<int>& parent, int node,
                       const std::vector<Channel>& channels, double t) {
    std::map<int, tinygltf::Node> posed;
    for (const Channel& c : channels) {
        tinygltf::Node& n = posed.try_emplace(c.node, rd.model().nodes[c.node]).first->second;
        n.matrix.clear();
        const bool rotation = c.path == "rotation";
        const std::vector<double> v =
            channel_at(c.times, c.values, rotation ? 4 : 3, c.interpolation, rotation, t);
        if (c.path == "translation") n.translation = v;
        if (rotation) n.rotation = v;
        if (c.path == "scale") n.scale = v;
    }
    std::map<int, glm::dmat4> overrides;
    for (const auto& [i, n] : posed) overrides[i] = local_matrix(n);
    return world_matrix(rd, parent, node, overrides);
}

}  // namespace

CameraTrack gltf_camera_track(const GltfDocument& doc, const std::string& name,
                              double focus_distance, double fps, const std::string& source,
                              const std::string& pointer) {
    const GltfReader rd(doc, source, pointer);
    const std::vector<int> parent = parents_of(rd);
    double yfov = 0;
    // The vertical field of view whatever the image's shape (the file's aspect ratio is not
    // enforced): a preview of another shape sees as far up and down, more or less to the sides.
    const int node = find_camera(rd, name, yfov);
    std::set<double> times;
    const std::vector<Channel> channels = channels_moving(rd, parent, node, times);
    if (times.empty()) times.insert(0.0);
    CameraTrack track;
    track.interpolation = TrackInterpolation::kLinear;
    const double t0 = *times.begin();
    // Blender bakes a sample per frame, its times frame / fps in float: a time within a
    // thousandth of a frame of the scene's frame grid is put on it, so frame N is the file's
    // N-th sample exactly.
    bool on_grid = true;
    for (double t : times) on_grid &= std::abs((t - t0) * fps - std::round((t - t0) * fps)) < 1e-3;
    for (double t : times) {
        const glm::dmat4 w = posed_world(rd, parent, node, channels, t);
        CameraKey k;
        k.time = on_grid ? std::round((t - t0) * fps) / fps : t - t0;
        k.position = glm::dvec3(w[3]);
        const glm::dvec3 forward = glm::normalize(glm::dvec3(w * glm::dvec4(0, 0, -1, 0)));
        k.up = glm::normalize(glm::dvec3(w * glm::dvec4(0, 1, 0, 0)));
        k.look_at = k.position + forward * focus_distance;
        k.fov = yfov;
        if (!std::isfinite(k.look_at.x + k.look_at.y + k.look_at.z + k.up.x + k.up.y + k.up.z))
            rd.fail(node_label(doc.model, node) + ": its transform at time " + std::to_string(t) +
                    " is degenerate");
        track.keys.push_back(k);
    }
    return track;
}

}  // namespace pleinair
