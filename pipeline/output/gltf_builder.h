// A glTF 2.0 model assembled in memory (tinygltf's Model) over one binary buffer, and its GLB
// bytes: the shared part of every glTF pleinair writes (trees now, scenes next).
#pragma once

#include <tiny_gltf.h>

#include <cstdint>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace pleinair {

// Appends typed arrays to buffer 0 as views and accessors (4-byte aligned, tightly packed), and
// serialises the model as GLB. Accessors of positions carry min and max, as the spec requires.
class GltfBuilder {
  public:
    GltfBuilder();

    tinygltf::Model& model() { return model_; }

    // `vertex`: the view holds vertex attributes (target ARRAY_BUFFER); animation samplers and
    // instancing attributes are not vertex data, and the validator refuses a view used as both.
    int add_positions(const std::vector<glm::vec3>& v);                 // VEC3 float with min/max
    int add_vec3(const std::vector<glm::vec3>& v, bool vertex = true);  // normals, vectors
    int add_vec2(const std::vector<glm::vec2>& v);                      // texture coordinates
    int add_vec4(const std::vector<glm::vec4>& v, bool vertex = true);  // colours, rotations
    int add_scalar(const std::vector<float>& v, bool vertex = true);    // custom attributes
    int add_indices(const std::vector<uint32_t>& v);                    // triangle corners, uint32
    // An image stored in the buffer (a GLB carries its textures inside).
    int add_image(const std::string& bytes, const std::string& mime_type, const std::string& name);

    // Bytes of the whole file: JSON chunk and BIN chunk, the same for the same model.
    std::string glb();

  private:
    int add_view(const void* data, size_t bytes, int target);
    int add_accessor(int view, int component_type, int type, size_t count);
    tinygltf::Model model_;
};

// nlohmann JSON as a tinygltf Value (extras). Integers beyond 32 bits become doubles, exact up
// to 2^53; pleinair's seeds are 32-bit.
tinygltf::Value to_gltf_value(const nlohmann::json& j);

}  // namespace pleinair
