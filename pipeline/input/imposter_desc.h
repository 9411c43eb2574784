// Graftal imposters (Doss, file 002 of the seeds): images of graftals, taken from an atlas,
// stretched over quads extruded from a mesh's silhouette edges, the control texture choosing
// where and which row, the vector field the direction, and the paper's keyed blend colouring
// them with the surface's colour. Plain data read by imposter_io.cpp from
// presets/imposters/NAME.json, the atlas, and the drawing of one imposter into a patch.
#pragma once

#include <cstdint>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
#include <memory>
#include <string>
#include <vector>

#include "pipeline/shot/graftal_draw.h"

namespace pleinair {

struct Camera;

// An RGBA image of floats, rows top to bottom (the control texture, the vector field, the colour
// texture as a designer saved them; the atlas's levels, premultiplied).
struct ImposterImage {
    int width = 0, height = 0;
    std::vector<glm::vec4> pixels;
    bool empty() const { return pixels.empty(); }
    // Bilinear at (u, v) in [0, 1]^2 (v down the rows), u wrapping round (round a cylinder) or
    // clamped, v clamped.
    glm::vec4 sample(float u, float v, bool wrap_u = true) const;
};

// The texture atlas (file 002, figure 5.9.1): `rows` types of graftal imposter, `columns`
// variations of each, every cell the same size. Premultiplied, and in the paper's key: red is
// 1 inside a graftal (where the surface's colour shows), green and blue carry the outline's
// colour (red 0), alpha its coverage. Levels halve down to a cell of 1 pixel, so a small
// imposter reads an image its own size (no shimmer as it shrinks).
struct ImposterAtlas {
    int rows = 1, columns = 1;
    int cell_w = 1, cell_h = 1;         // of level 0
    std::vector<ImposterImage> levels;  // [0] full size
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
    std::shared_ptr<const ImposterAtlas> atlas;
    // As written, for messages and the reference (the atlas's source).
    std::vector<std::string> atlas_graftals;
    std::string atlas_image, control_image, field_image, color_image;
    int atlas_rows = 1, atlas_columns = 4, atlas_cell_px = 64;
};

// An atlas drawn from graftal descriptions (the "atlas of graftal images"): row r from
// descriptions[r], column c its example c mod count, varied by the description's ranges from a
// fixed seed, seen face on, fills keyed red and outlines in (0, g, b).
ImposterAtlas atlas_from_graftals(const std::vector<GraftalDesc>& descriptions, int columns,
                                  int cell_px);
// An atlas from a designer's image in the paper's format (straight alpha), cut into cells.
ImposterAtlas atlas_from_image(const ImposterImage& image, int rows, int columns);

// The paper's keyed blend for one atlas sample (premultiplied): the outline's (0, g, b) where
// the key red is 0, the surface's colour where it is 1, between them in proportion; alpha kept.
// Premultiplied linear RGB and alpha out.
glm::vec4 keyed_blend(const glm::vec4& atlas_premultiplied, const glm::vec3& surface_linear);

// One imposter as the frame draws it: the quad (base v0, v1 on the silhouette edge; tips
// extruded from them) in the world, its atlas cell and the surface's colour at each end.
struct ImposterQuad {
    glm::dvec3 v0{0.0}, v1{0.0}, t0{0.0}, t1{0.0};
    int row = 0, column = 0;
    glm::vec3 color0{1.0f}, color1{1.0f};  // linear, shaded
    float opacity = 1;
};

// The quad as `cam` sees it, textured from its atlas cell (trilinear between the two levels that
// bracket its size on screen) and keyed, into an 8-bit premultiplied sRGB patch like a graftal's.
// Empty when a corner lies behind the near plane or it misses the frame; `max_px` bounds the
// patch's side. Pure: the same arguments give the same bytes on any thread.
GraftalPatch draw_imposter(const ImposterAtlas& atlas, const ImposterQuad& q, const Camera& cam,
                           int max_px = 2048);

// Texture coordinates of a point of an object whose bounding box is [lo, hi].
glm::vec2 imposter_uv(ImposterUv uv, const glm::vec3& p, const glm::vec3& lo, const glm::vec3& hi);

// The control texture's row at (u, v): -1 where no imposter may stand.
int control_row(const ImposterDesc& d, const glm::vec2& uv);

}  // namespace pleinair
