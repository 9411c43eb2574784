// Graftal imposters (Doss, file 002 of the seeds): images of graftals, taken from an atlas,
// stretched over quads extruded from a mesh's silhouette edges, the control texture choosing
// where and which row, the vector field the direction, and the paper's keyed blend colouring
// them with the surface's colour. Plain data read by imposter_io.cpp from
// presets/imposters/NAME.json; the shot draws the atlas (shot/imposter_atlas.h), the frame the
// imposters (frame/imposter_draw.h).
#pragma once

#include <cstdint>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
#include <memory>
#include <string>
#include <vector>

#include "pipeline/input/graftal_desc.h"

namespace pleinair {

// An RGBA image of floats, rows top to bottom (the control texture, the vector field, the colour
// texture as a designer saved them; the atlas's levels, premultiplied).
struct ImposterImage {
    int width = 0, height = 0;
    std::vector<glm::vec4> pixels;
    bool empty() const { return pixels.empty(); }
    // Bilinear at (u, v) in [0, 1]^2 (v down the rows), u wrapping round (round a cylinder) or
    // clamped, v clamped.
    glm::vec4 sample(float u, float v, bool wrap_u = true) const;
    glm::vec4 texel(int x, int y) const { return pixels[static_cast<size_t>(y) * width + x]; }
};

// How a mesh's points get the texture coordinates the control, vector field and colour textures
// are read at: both taken over the object's bounding box, so a texture fits any tree or rock.
enum class ImposterUv {
    kCylinder,  // u: the angle about the box's vertical axis; v: up its height (trunks, rocks)
    kPlan,      // u, v: x and z across the box, seen from above (terrain)
};

// Which of a tree's meshes carries the imposters.
enum class ImposterMesh {
    kRender,   // the Catmull-Clark render mesh: small, even edges
    kControl,  // the extruded control mesh: few long edges, large imposters
};

struct ImposterDesc {
    std::string description;
    float height = 0.3f;  // world length of the extrusion (x the tree's scale on a tree)
    float width = 0;      // the base's length, centred on the edge; 0: the edge's own (file 002)
    ImposterMesh mesh = ImposterMesh::kRender;
    ImposterUv uv = ImposterUv::kCylinder;
    float fade = 0.15f;        // |n.v| below which a face nearly on edge brings its edges in
    float fade_frames = 4;     // near a moving eye, the fewest frames an edge takes to come in
    float min_edge_px = 1.5f;  // edges shorter on screen fade out below this
    float light = 0.4f;        // the sun's shading, as a graftal's
    float coverage = 1.0f;     // the share of edges the control allows, chosen by a hash
    // The control texture: an image (alpha < 1/2 none; else the row of its largest of red,
    // green, blue, as in the paper; a row the atlas lacks is none) or, without one, `rows` as a
    // column of texels up v (-1: none). Read at each edge's middle (imposter_stage.h).
    ImposterImage control;
    std::vector<int> rows{0};
    // The vector field: D = normalize(normal x n + up x (0, 1, 0) + field), the field an
    // image of directions (rgb = (d + 1) / 2, in the object's frame) sampled at the edge's middle.
    float normal = 1, up = 0;
    ImposterImage field;
    // The colour texture: an image, or a gradient from `bottom` to `top` up v (sRGB as written).
    ImposterImage color;
    glm::vec3 bottom{0.25f, 0.3f, 0.12f}, top{0.45f, 0.55f, 0.22f};
    // The atlas's sources, checked as the file is read; the shot draws the atlas from them
    // (shot/imposter_atlas.h): graftal descriptions (a row each), or a designer's image.
    std::vector<GraftalDesc> atlas_descs;
    ImposterImage atlas_source;
    // As written, for messages and the reference (the atlas's source).
    std::vector<std::string> atlas_graftals;
    std::string atlas_image, control_image, field_image, color_image;
    int atlas_rows = 1, atlas_columns = 4, atlas_cell_px = 64;  // rows: the descs' count
};

// Texture coordinates of a point of an object whose bounding box is [lo, hi].
glm::vec2 imposter_uv(ImposterUv uv, const glm::vec3& p, const glm::vec3& lo, const glm::vec3& hi);

// The control texture's row at (u, v): -1 where no imposter may stand.
int control_row(const ImposterDesc& d, const glm::vec2& uv);

}  // namespace pleinair
