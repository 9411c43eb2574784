// GltfBuilder: typed arrays into one buffer, serialised by tinygltf as GLB.
#include "pipeline/output/gltf_builder.h"

#include <algorithm>
#include <cstring>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace pleinair {

GltfBuilder::GltfBuilder() {
    model_.asset.version = "2.0";
    model_.asset.generator = "pleinair";
    model_.buffers.emplace_back();
}

int GltfBuilder::add_view(const void* data, size_t bytes, int target) {
    std::vector<unsigned char>& buf = model_.buffers[0].data;
    // Every accessor's offset a multiple of its component size: 4 bytes serves all we write.
    buf.resize((buf.size() + 3) & ~size_t(3), 0);
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = buf.size();
    view.byteLength = bytes;
    view.target = target;
    const auto* p = static_cast<const unsigned char*>(data);
    buf.insert(buf.end(), p, p + bytes);
    model_.bufferViews.push_back(std::move(view));
    return static_cast<int>(model_.bufferViews.size()) - 1;
}

int GltfBuilder::add_accessor(int view, int component_type, int type, size_t count) {
    tinygltf::Accessor a;
    a.bufferView = view;
    a.byteOffset = 0;
    a.normalized = false;
    a.componentType = component_type;
    a.type = type;
    a.count = count;
    model_.accessors.push_back(std::move(a));
    return static_cast<int>(model_.accessors.size()) - 1;
}

int GltfBuilder::add_positions(const std::vector<glm::vec3>& v) {
    const int a = add_vec3(v);
    // The spec asks for POSITION's bounds; the validator checks them against the data exactly.
    std::vector<double> lo(3, std::numeric_limits<double>::max()), hi(3, -lo[0]);
    for (const glm::vec3& p : v)
        for (int k = 0; k < 3; ++k)
            lo[k] = std::min<double>(lo[k], p[k]), hi[k] = std::max<double>(hi[k], p[k]);
    if (v.empty()) lo.assign(3, 0.0), hi.assign(3, 0.0);
    model_.accessors[a].minValues = lo;
    model_.accessors[a].maxValues = hi;
    return a;
}

int GltfBuilder::add_vec3(const std::vector<glm::vec3>& v, bool vertex) {
    static_assert(sizeof(glm::vec3) == 12);
    return add_accessor(
        add_view(v.data(), v.size() * 12, vertex ? TINYGLTF_TARGET_ARRAY_BUFFER : 0),
        TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, v.size());
}

int GltfBuilder::add_vec2(const std::vector<glm::vec2>& v) {
    static_assert(sizeof(glm::vec2) == 8);
    return add_accessor(add_view(v.data(), v.size() * 8, TINYGLTF_TARGET_ARRAY_BUFFER),
                        TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC2, v.size());
}

int GltfBuilder::add_vec4(const std::vector<glm::vec4>& v, bool vertex) {
    static_assert(sizeof(glm::vec4) == 16);
    return add_accessor(
        add_view(v.data(), v.size() * 16, vertex ? TINYGLTF_TARGET_ARRAY_BUFFER : 0),
        TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC4, v.size());
}

int GltfBuilder::add_scalar(const std::vector<float>& v, bool vertex) {
    return add_accessor(add_view(v.data(), v.size() * 4, vertex ? TINYGLTF_TARGET_ARRAY_BUFFER : 0),
                        TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_SCALAR, v.size());
}

int GltfBuilder::add_indices(const std::vector<uint32_t>& v) {
    return add_accessor(add_view(v.data(), v.size() * 4, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER),
                        TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR, v.size());
}

int GltfBuilder::add_image(const std::string& bytes, const std::string& mime_type,
                           const std::string& name) {
    tinygltf::Image img;
    img.name = name;
    img.mimeType = mime_type;
    img.bufferView = add_view(bytes.data(), bytes.size(), 0);
    model_.images.push_back(std::move(img));
    return static_cast<int>(model_.images.size()) - 1;
}

std::string GltfBuilder::glb() {
    model_.buffers[0].data.resize((model_.buffers[0].data.size() + 3) & ~size_t(3), 0);
    std::ostringstream out(std::ios::binary);
    tinygltf::TinyGLTF writer;
    if (!writer.WriteGltfSceneToStream(&model_, out, false, true))
        throw std::runtime_error("tinygltf could not serialise the model");
    return out.str();
}

tinygltf::Value to_gltf_value(const nlohmann::json& j) {
    using tinygltf::Value;
    if (j.is_object()) {
        Value::Object o;
        for (auto it = j.begin(); it != j.end(); ++it) o[it.key()] = to_gltf_value(it.value());
        return Value(std::move(o));
    }
    if (j.is_array()) {
        Value::Array a;
        for (const auto& e : j) a.push_back(to_gltf_value(e));
        return Value(std::move(a));
    }
    if (j.is_boolean()) return Value(j.get<bool>());
    if (j.is_number_integer()) {
        const auto n = j.is_number_unsigned() ? static_cast<double>(j.get<uint64_t>())
                                              : static_cast<double>(j.get<int64_t>());
        if (n >= std::numeric_limits<int>::min() && n <= std::numeric_limits<int>::max())
            return Value(static_cast<int>(n));
        return Value(n);
    }
    if (j.is_number()) return Value(j.get<double>());
    if (j.is_string()) return Value(j.get<std::string>());
    return Value();
}

}  // namespace pleinair
