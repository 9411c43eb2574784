// PLY particles to world strokes: attributes found by name, every value checked, the axes,
// scale and position applied, labels hashed so two files never share one.
#include "pipeline/input/particle_files.h"

#include <cmath>
#include <glm/geometric.hpp>

#include "generators/rng.h"
#include "generators/tree_params.h"
#include "pipeline/input/error.h"
#include "pipeline/input/ply.h"
#include "shading/portable_math.h"

namespace pleinair {

void push_stroke_keys(SurfaceParticles& s, uint64_t label_hash, Rng& rng) {
    s.label.push_back((static_cast<float>(label_hash >> 40) + 0.5f) / 16777216.0f);
    // Uniform on the sphere: z uniform in [-1, 1], angle uniform.
    const double z = rand_range(rng, -1.0, 1.0), a = rand_range(rng, 0.0, 2 * M_PI);
    const double r = std::sqrt(std::max(0.0, 1 - z * z));
    s.random_code.push_back(
        encode_unit(glm::vec3(glm::dvec3(r * pmath::cos(a), r * pmath::sin(a), z))));
}

std::vector<std::string> split_names(const std::string& names) {
    std::vector<std::string> out;
    size_t start = 0;
    while (true) {
        size_t comma = names.find(',', start);
        std::string w = names.substr(start, comma == std::string::npos ? comma : comma - start);
        while (!w.empty() && w.front() == ' ') w.erase(w.begin());
        while (!w.empty() && w.back() == ' ') w.pop_back();
        out.push_back(w);
        if (comma == std::string::npos) return out;
        start = comma + 1;
    }
}

namespace {

using Column = PlyVertices::Column;

// The columns an attribute reads: those `wanted` names (the scene's choice, which must be
// there), or the first set of `usual` names present (none: an empty result).
std::vector<const Column*> attribute(const PlyVertices& v, const std::string& source,
                                     const char* key, const std::string& wanted,
                                     std::initializer_list<const char*> usual, size_t arity) {
    std::vector<const Column*> out;
    if (wanted == "none") return out;
    if (!wanted.empty()) {
        const std::vector<std::string> names = split_names(wanted);
        if (names.size() != arity)
            throw InputError(source, "",
                             std::string("the scene's ") + key + " names " +
                                 std::to_string(names.size()) + " properties, expected " +
                                 std::to_string(arity));
        for (const std::string& n : names) {
            const Column* c = v.find(n);
            if (!c)
                throw InputError(source, "",
                                 std::string("no vertex property \"") + n + "\" (" +
                                     (std::string(key) == "position"
                                          ? std::string("a particle file needs x, y and z")
                                          : std::string("/particles/N/") + key + " names it") +
                                     ")");
            out.push_back(c);
        }
        return out;
    }
    for (const char* set : usual) {
        out.clear();
        for (const std::string& n : split_names(set))
            if (const Column* c = v.find(n)) out.push_back(c);
        if (out.size() == arity) return out;
    }
    out.clear();
    return out;
}

[[noreturn]] void bad(const std::string& source, size_t i, const Column& c,
                      const std::string& what) {
    throw InputError(source, "vertex " + std::to_string(i) + " property " + c.name, what);
}

}  // namespace

ImportedParticles import_particles(const std::string& bytes, const std::string& source,
                                   const ParticleFileDesc& d, uint64_t file_key,
                                   const glm::vec3& sun, double max_coordinate) {
    const PlyVertices v = read_ply_vertices(bytes, source);
    const auto xyz = attribute(v, source, "position", "x,y,z", {}, 3);
    const auto size = attribute(v, source, "size", d.size, {"pscale", "radius"}, 1);
    const auto label = attribute(v, source, "label", d.label, {"id"}, 1);
    const auto normal = attribute(v, source, "normal", d.normal, {"nx,ny,nz"}, 3);
    const auto color = attribute(v, source, "color", d.color,
                                 {"red,green,blue", "r,g,b",
                                  "diffuse_red,"
                                  "diffuse_green,diffuse_blue"},
                                 3);
    const auto by = attribute(v, source, "material_by", d.material_by, {}, 1);
    if (!by.empty() && !by[0]->integer)
        throw InputError(source, "property " + by[0]->name,
                         "a material index must be an integer type, got " + by[0]->type);
    if (!label.empty() && !label[0]->integer)
        throw InputError(source, "property " + label[0]->name,
                         "a label must be an integer type, got " + label[0]->type);

    // The file's axes in pleinair's (y up): Blender's z up turns (x, y, z) into (x, z, -y).
    auto axes = [&](double x, double y, double z) {
        return d.up == UpAxis::kZ ? glm::dvec3(x, z, -y) : glm::dvec3(x, y, z);
    };
    const glm::vec3 facing_sun = glm::normalize(sun);
    ImportedParticles out;
    SurfaceParticles& s = out.strokes;
    s.reserve(v.count);
    if (!size.empty()) out.width.reserve(v.count);
    if (!color.empty()) out.color.reserve(v.count);
    for (size_t i = 0; i < v.count; ++i) {
        const glm::dvec3 w =
            d.position + d.scale * axes(xyz[0]->values[i], xyz[1]->values[i], xyz[2]->values[i]);
        for (int k = 0; k < 3; ++k)
            if (!(std::abs(w[k]) <= max_coordinate))
                bad(source, i, *xyz[static_cast<size_t>(k)],
                    "placed at " + format_number(w[k]) +
                        ", beyond the world pleinair supports (every coordinate within +-" +
                        format_number(max_coordinate) + ")");
        s.position.push_back(glm::vec3(w));

        glm::vec3 n = facing_sun;
        if (!normal.empty()) {
            const glm::dvec3 f =
                axes(normal[0]->values[i], normal[1]->values[i], normal[2]->values[i]);
            const double len = glm::length(f);
            if (!(len > 1e-12)) bad(source, i, *normal[0], "a normal of zero length");
            n = glm::vec3(f / len);
        }
        s.normal_code.push_back(encode_unit(n));

        // The label from the file's id (stable when the tool reorders points) or the index.
        uint64_t id = i;
        if (!label.empty()) {
            const double l = label[0]->values[i];
            if (l < 0) bad(source, i, *label[0], "a label must be >= 0, got " + format_number(l));
            id = static_cast<uint64_t>(l);
        }
        const uint64_t h = hash_keys(file_key, static_cast<uint64_t>(Purpose::kImported), id);
        Rng rng = make_rng(file_key, Purpose::kImported, id);  // the random normal, same key
        push_stroke_keys(s, h, rng);
        s.uv_code.push_back(0);
        s.height_code.push_back(encode_unorm(1.0f));
        uint32_t material = d.material;
        if (!by.empty()) {
            const double k = by[0]->values[i];
            if (!(k >= 0 && k < static_cast<double>(d.materials.size())))
                bad(source, i, *by[0],
                    "a material index must be in 0.." + std::to_string(d.materials.size() - 1) +
                        " (/particles/N/materials lists " + std::to_string(d.materials.size()) +
                        "), got " + format_number(k));
            material = d.materials[static_cast<size_t>(k)];
        }
        s.material.push_back(static_cast<uint16_t>(material));
        s.fade_code.push_back((2u * 16384u) | ((3u * 16384u) << 16));  // never fades

        if (!size.empty()) {
            const double sz = size[0]->values[i];
            if (!(sz > 0)) bad(source, i, *size[0], "a size must be > 0, got " + format_number(sz));
            const double width = sz * d.size_to_width * d.scale;
            if (!(width <= max_coordinate))
                bad(source, i, *size[0],
                    "a stroke " + format_number(width) + " wide, larger than the world");
            // Fuzzing found a size of 1e-45: > 0 in double, a stroke of width 0 in float.
            if (!(static_cast<float>(width) >= 1e-30f))
                bad(source, i, *size[0],
                    "a stroke " + format_number(width) +
                        " wide, too narrow to paint (the least is 1e-30)");
            out.width.push_back(static_cast<float>(width));
        }
        if (!color.empty()) {
            Color c;
            for (int k = 0; k < 3; ++k) {
                const Column& col = *color[static_cast<size_t>(k)];
                const double x = col.values[i];
                // Integer colours are sRGB in their type's range (Blender, MeshLab); floats are
                // linear in 0..1 (Houdini's Cd).
                const double full = col.type == "uchar" || col.type == "uint8"     ? 255.0
                                    : col.type == "ushort" || col.type == "uint16" ? 65535.0
                                    : col.integer                                  ? 0.0
                                                                                   : 1.0;
                if (full == 0.0)
                    throw InputError(source, "property " + col.name,
                                     "a colour is uchar, ushort, float or double, got " + col.type);
                if (!(x >= 0 && x <= full))
                    bad(source, i, col,
                        "a colour must be in [0, " + format_number(full) + "], got " +
                            format_number(x));
                c[k] = col.integer ? srgb_to_linear(static_cast<float>(x / full))
                                   : static_cast<float>(x);
            }
            out.color.push_back(c);
        }
    }
    return out;
}

}  // namespace pleinair
