// Particles made by another tool (a PLY file from Blender, Houdini or MeshLab) painted as
// surface strokes with one of the scene's materials: its stroke shader and palette.
#pragma once

#include <cstdint>
#include <glm/vec3.hpp>
#include <memory>
#include <string>
#include <vector>

#include "generators/surface_strokes.h"
#include "shading/color.h"

namespace pleinair {

// A file's particles in the world, ready to paint: the strokes (material, label, normal; no
// fade with distance), and per particle the width and colour when the file holds them.
struct ImportedParticles {
    SurfaceParticles strokes;
    std::vector<float> width;  // world units; empty: the material's sprite_size times scale
    std::vector<Color> color;  // linear RGB; empty: the palette's colour alone
};

struct Rng;

// Appends an imported stroke's label and random normal (a particle file's, a figure's): the
// label from the top 24 bits of `label_hash`, in (0, 1) and never either end; the normal
// uniform on the sphere, two draws of `rng`.
void push_stroke_keys(SurfaceParticles& strokes, uint64_t label_hash, Rng& rng);

// Which axis of the file is up: y (Houdini, MeshLab, pleinair) or z (Blender).
enum class UpAxis { kY, kZ };

// One entry of a scene's /particles list (documented where parsed, in scene.cpp).
struct ParticleFileDesc {
    std::string file;  // as written in the scene; resolved against its folder
    std::string material_name;
    uint32_t material = 0;
    // Materials by an integer vertex property (a class: 0 ground, 1 bark, 2 and on crowns,
    // say): its name, and the materials' names, comma-separated, that its values 0, 1, ...
    // pick (resolved into `materials`). Empty: every particle takes `material`.
    std::string material_by, material_list;
    std::vector<uint32_t> materials;
    bool casts_shadows = true;  // cards facing the sun in its scene, like leaf strokes
    UpAxis up = UpAxis::kY;
    glm::dvec3 position{0.0};  // the file's origin in the world
    double scale = 1;          // world units per file unit (positions and sizes)
    // Attributes: a property name (or three, comma-separated, for the normal and colour);
    // empty picks the usual names when present; "none" ignores the attribute.
    std::string size, label, normal, color;
    double size_to_width = 2;  // stroke width per unit of size (2: the size is a radius)
    float color_amount = 1;    // how much of the stroke's hue comes from the file's colour
    bool on_terrain = false;   // y is the height above the scene's terrain, as a tree's
    std::shared_ptr<const ImportedParticles> particles;  // read when the scene is parsed
};

// Comma-separated names, each trimmed of spaces ("nx, ny, nz").
std::vector<std::string> split_names(const std::string& names);

// Reads `file` (bytes of a PLY file) into world strokes: positions placed by the entry's axis,
// scale and position, labels from the label attribute (else the vertex index) hashed with
// `file_key`, normals from the attribute (else towards `sun`). Throws InputError naming
// `source` (the PLY file) and the vertex and property of any value that is not usable, and
// refuses positions beyond `max_coordinate`.
ImportedParticles import_particles(const std::string& bytes, const std::string& source,
                                   const ParticleFileDesc& desc, uint64_t file_key,
                                   const glm::vec3& sun, double max_coordinate);

}  // namespace pleinair
