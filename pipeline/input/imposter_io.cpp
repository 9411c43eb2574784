// The imposter description's key table (each key documented where it is read), its checks, and
// the loading of what it names: the graftal descriptions or image of its atlas, and its control,
// vector field and colour textures.
#include "pipeline/input/imposter_io.h"

#include <OpenImageIO/imageio.h>

#include <filesystem>
#include <set>

#include "pipeline/input/graftal_io.h"
#include "pipeline/input/json_visitors.h"
#include "pipeline/input/presets.h"
#include "shading/color.h"

namespace pleinair {

using namespace json_detail;

namespace {

std::string near_file_path(const std::string& name, const std::string& source) {
    std::filesystem::path p(name);
    if (p.is_absolute() || !source.ends_with(".json")) return name;
    return (std::filesystem::path(source).parent_path() / p).string();
}

const std::pair<ImposterMesh, const char*> kMeshes[] = {{ImposterMesh::kRender, "render"},
                                                        {ImposterMesh::kControl, "control"}};
const std::pair<ImposterUv, const char*> kUvs[] = {{ImposterUv::kCylinder, "cylinder"},
                                                   {ImposterUv::kPlan, "plan"}};

// D is ImposterDesc or const ImposterDesc.
template <class D, class V>
void visit_imposter(D& d, V& v) {
    v.text("description", d.description, "What the imposters depict, for `pleinair presets`.");
    v.real("height", d.height, {1e-4, 1000}, "world units",
           "How far a silhouette edge is extruded (file 002's GraftalHeight); on a tree, times "
           "the tree's scale.");
    v.real("width", d.width, {0, 1000}, "world units",
           "Length of an imposter's base, centred on its edge and along it; on a tree, times the "
           "tree's scale. 0: the edge's own length, as in file 002 (so the mesh's edges should be "
           "of a size); a width gives every imposter the same, whatever the edges.");
    v.choice("mesh", d.mesh, kMeshes,
             "A tree's mesh whose silhouette carries them: \"render\" (Catmull-Clark, small even "
             "edges) or \"control\" (the extruded mesh: few long edges, large imposters).");
    v.choice("uv", d.uv, kUvs,
             "Where the textures are read: \"cylinder\" (u round the object's vertical axis, v up "
             "its height; trunks, rocks) or \"plan\" (x and z across its box; terrain).");
    v.real("fade", d.fade, {0, 1}, "",
           "Edges whose two faces turn the same way come in as the nearer to edge-on of them "
           "turns within this of it (abs(n.v) from this down to 0), so imposters grow in before "
           "an edge is a silhouette instead of popping; 0: silhouettes only.");
    v.real("fade_frames", d.fade_frames, {0, 60}, "frames",
           "Near a moving eye an edge turns fast (by up to the eye's travel over its distance, in "
           "radians, a frame), so the fade band widens there until no edge comes in or goes in "
           "fewer frames than this; 0: `fade` alone.");
    v.real("min_edge_px", d.min_edge_px, {0, 100}, "px",
           "Imposters whose base (the edge, or `width`) is shorter than this on screen (at its "
           "depth, not foreshortened) fade out, to nothing at half of it.");
    v.real("light", d.light, {0, 0.9}, "",
           "How much the sun shades them: colours x (1 - light + light x max(0, n.l)).");
    v.object("atlas", "The texture atlas (file 002, figure 5.9.1): a row per type", [&] {
        v.claim("graftals");  // names, read by read_atlas
        v.text("image", d.atlas_image,
               "Instead of graftals: a designer's atlas image in the paper's key (alpha the "
               "shape, red 1 inside where the surface's colour shows, green and blue the "
               "outline's colour), `rows` x `columns` cells; a path relative to this file.");
        v.integer("rows", d.atlas_rows, {1, 3},
                  "With an image: its rows of cells (types; the control texture's red, green "
                  "and blue pick them).");
        v.integer("columns", d.atlas_columns, {1, 64},
                  "Variations of each type: drawn from a graftal's examples and ranges, or the "
                  "image's columns. Each edge keeps its own, chosen by a hash of its vertices.");
        v.integer("cell_px", d.atlas_cell_px, {4, 512},
                  "Pixels a side of a cell drawn from graftals.");
    });
    v.object("control", "The control texture (file 002, figure 5.9.2), read at each edge's middle",
             [&] {
                 v.text("image", d.control_image,
                        "An image: alpha under 1/2 allows none; elsewhere its largest of red, "
                        "green and blue picks the atlas's row 0, 1 or 2 (a row the atlas lacks: "
                        "none). Relative to this file.");
                 v.claim("rows");  // a list, read by read_rows
                 v.real("coverage", d.coverage, {0, 1}, "",
                        "The share of the edges the control allows that carry imposters, chosen "
                        "by a hash of the edge (fixed on the surface).");
             });
    v.object("direction", "The vector field (file 002, figure 5.9.3): where imposters point", [&] {
        v.real("normal", d.normal, {-10, 10}, "",
               "Weight of the edge's normal (the mean of its two faces') in D.");
        v.real("up", d.up, {-10, 10}, "", "Weight of the world's up (0, 1, 0) in D.");
        v.text("image", d.field_image,
               "A field of directions (rgb = (d + 1) / 2, in the object's frame) added to D, read "
               "at the edge's middle; relative to this file.");
    });
    v.object("color", "The colour texture (file 002, figure 5.9.4): the imposters' insides", [&] {
        v.color("bottom", d.bottom, "Colour at the bottom of the object (v = 0), sRGB.");
        v.color("top", d.top, "Colour at its top (v = 1), sRGB.");
        v.text("image", d.color_image,
               "Instead of the gradient: an image read at each end of the edge; relative to this "
               "file.");
    });
}

// A bare name (no '/', no .json) is a preset's; a path is taken relative to the source file.
std::string near_preset(const std::string& name, const std::string& source) {
    const bool is_file = name.find('/') != std::string::npos || name.ends_with(".json");
    return is_file ? near_file_path(name, source) : name;
}

void read_rows(const json& doc, ImposterDesc& d, std::vector<Problem>& problems) {
    auto c = doc.find("control");
    if (c == doc.end() || !c->is_object() || !c->contains("rows")) return;
    const json& rows = (*c)["rows"];
    if (!rows.is_array() || rows.empty() || rows.size() > 256)
        return problems.push_back({"/control/rows",
                                   "expected a list of 1 to 256 atlas rows (-1: none), bottom to "
                                   "top, got " +
                                       describe(rows)});
    d.rows.clear();
    for (size_t i = 0; i < rows.size(); ++i) {
        const json& r = rows[i];
        const double x = r.is_number() ? r.get<double>() : -2.0;
        if (!(x >= -1 && x <= 2) || x != std::floor(x)) {
            problems.push_back(
                {"/control/rows/" + std::to_string(i),
                 "expected an atlas row (0, 1 or 2) or -1 for none, got " + describe(r)});
            continue;
        }
        d.rows.push_back(static_cast<int>(x));
    }
}

}  // namespace

ImposterImage read_imposter_image(const std::string& path, const std::string& source,
                                  const std::string& pointer) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
        throw InputError(source, pointer, "no image file \"" + path + "\"");
    auto in = OIIO::ImageInput::open(path);
    if (!in) {
        const std::string err = OIIO::geterror();
        throw InputError(source, pointer,
                         "cannot read image \"" + path + "\"" + (err.empty() ? "" : ": " + err));
    }
    const OIIO::ImageSpec& spec = in->spec();
    const int nch = std::min(spec.nchannels, 4);  // RGBA at most: more is not read
    if (spec.width < 1 || spec.height < 1 || spec.width > 4096 || spec.height > 4096 || nch < 1)
        throw InputError(source, pointer,
                         "image \"" + path + "\" must be 1 to 4096 pixels a side, got " +
                             std::to_string(spec.width) + " x " + std::to_string(spec.height));
    std::vector<float> data(static_cast<size_t>(spec.width) * spec.height * nch);
    if (!in->read_image(0, 0, 0, nch, OIIO::TypeDesc::FLOAT, data.data())) {
        const std::string err = in->geterror();
        throw InputError(source, pointer, "cannot read image \"" + path + "\": " + err);
    }
    in->close();
    ImposterImage img;
    img.width = spec.width, img.height = spec.height;
    img.pixels.resize(static_cast<size_t>(img.width) * img.height);
    for (size_t i = 0; i < img.pixels.size(); ++i) {
        const float* p = &data[i * nch];
        glm::vec4 v = nch >= 3 ? glm::vec4(p[0], p[1], p[2], nch >= 4 ? p[3] : 1.0f)
                               : glm::vec4(p[0], p[0], p[0], nch == 2 ? p[1] : 1.0f);
        for (int k = 0; k < 4; ++k) v[k] = std::isfinite(v[k]) ? std::clamp(v[k], 0.0f, 1.0f) : 0;
        img.pixels[i] = v;
    }
    return img;
}

ImposterDesc parse_imposter(const std::string& text, const std::string& source,
                            const std::vector<std::string>& overrides) {
    std::vector<Problem> problems;
    std::set<std::string> overridden;
    json doc = parse_document(text, source, overrides, problems, overridden);
    ImposterDesc d;
    std::set<std::string> plain;
    std::vector<std::string> graftals;
    if (doc.is_object()) {
        Reader reader(doc, problems, plain);
        visit_imposter(d, reader);
        reader.finish();
        read_rows(doc, d, problems);
        const json* atlas =
            doc.contains("atlas") && doc["atlas"].is_object() ? &doc["atlas"] : nullptr;
        const bool has_graftals = atlas && atlas->contains("graftals");
        if (has_graftals) {
            const json& g = (*atlas)["graftals"];
            if (!g.is_array() || g.empty() || g.size() > 3) {
                problems.push_back({"/atlas/graftals",
                                    "expected a list of 1 to 3 graftal descriptions (one per "
                                    "row), got " +
                                        describe(g)});
            } else {
                for (size_t i = 0; i < g.size(); ++i) {
                    if (!g[i].is_string() || g[i].get_ref<const std::string&>().empty())
                        problems.push_back({"/atlas/graftals/" + std::to_string(i),
                                            "expected a graftal description's name or file, got " +
                                                describe(g[i])});
                    else
                        graftals.push_back(g[i].get<std::string>());
                }
            }
        }
        if (has_graftals == !d.atlas_image.empty())
            problems.push_back({"/atlas", has_graftals
                                              ? "give \"graftals\" or \"image\", not both"
                                              : "missing: \"graftals\" (descriptions to draw the "
                                                "cells from) or \"image\" (an atlas image)"});
        if (atlas && !d.atlas_image.empty() && atlas->contains("cell_px"))
            problems.push_back({"/atlas/cell_px",
                                "only an atlas drawn from graftals has cells "
                                "of cell_px; an image's cells are its size "
                                "over rows and columns"});
        if (has_graftals && atlas->contains("rows"))
            problems.push_back({"/atlas/rows",
                                "an atlas drawn from graftals has a row per "
                                "graftal description"});
        const int atlas_rows = has_graftals ? static_cast<int>(graftals.size()) : d.atlas_rows;
        for (size_t i = 0; i < d.rows.size(); ++i)
            if (d.rows[i] >= atlas_rows)
                problems.push_back({"/control/rows/" + std::to_string(i),
                                    "the atlas has " + std::to_string(atlas_rows) +
                                        " row(s), so a row must be -1 to " +
                                        std::to_string(atlas_rows - 1) + ", got " +
                                        std::to_string(d.rows[i])});
        const auto has = [&](const char* object, const char* key) {
            const auto it = doc.find(object);
            return it != doc.end() && it->is_object() && it->contains(key);
        };
        if (!d.control_image.empty() && has("control", "rows"))
            problems.push_back({"/control/rows", "give \"rows\" or \"image\", not both"});
        if (!d.color_image.empty() && (has("color", "bottom") || has("color", "top")))
            problems.push_back({"/color/image",
                                "give \"image\" or \"bottom\" and \"top\", not "
                                "both"});
        if (d.normal == 0 && d.up == 0 && d.field_image.empty())
            problems.push_back({"/direction",
                                "normal and up are both 0 and there is no image: "
                                "imposters would have no direction"});
        d.atlas_graftals = graftals;
    }
    mark_overrides(problems, overridden);
    if (!problems.empty()) throw InputError(source, problems);
    d.bottom = srgb_to_linear(d.bottom), d.top = srgb_to_linear(d.top);
    // The files it names, each error at its own key.
    if (!d.atlas_graftals.empty()) {
        std::vector<GraftalDesc> descs;
        for (size_t i = 0; i < d.atlas_graftals.size(); ++i)
            descs.push_back(load_graftal(near_preset(d.atlas_graftals[i], source), source,
                                         "/atlas/graftals/" + std::to_string(i)));
        d.atlas_rows = static_cast<int>(descs.size());
        d.atlas_descs = std::move(descs);
    } else {
        const ImposterImage img =
            read_imposter_image(near_file_path(d.atlas_image, source), source, "/atlas/image");
        if (img.width < d.atlas_columns || img.height < d.atlas_rows)
            throw InputError(source, "/atlas/image",
                             "an image of " + std::to_string(img.width) + " x " +
                                 std::to_string(img.height) + " cannot hold " +
                                 std::to_string(d.atlas_rows) + " x " +
                                 std::to_string(d.atlas_columns) + " cells");
        d.atlas_source = img;
    }
    if (!d.control_image.empty())
        d.control =
            read_imposter_image(near_file_path(d.control_image, source), source, "/control/image");
    if (!d.field_image.empty())
        d.field =
            read_imposter_image(near_file_path(d.field_image, source), source, "/direction/image");
    if (!d.color_image.empty()) {
        d.color =
            read_imposter_image(near_file_path(d.color_image, source), source, "/color/image");
        for (glm::vec4& p : d.color.pixels) p = glm::vec4(srgb_to_linear(glm::vec3(p)), p.w);
    }
    return d;
}

ImposterDesc load_imposter(const std::string& name, const std::string& source,
                           const std::string& pointer) {
    auto file = resolve_preset("imposters", name, source.empty() ? "--imposters" : source, pointer);
    return parse_imposter(read_input_file(file), file.string());
}

std::string imposter_reference() {
    Documenter d;
    d.out << "| key | default | range | unit | meaning |\n|---|---|---|---|---|\n";
    const ImposterDesc g;
    visit_imposter(g, d);
    d.note("atlas/graftals", "required without image",
           "Graftal descriptions (names or files), one per row of the atlas (1 to 3): each "
           "column an example of it, seen face on, fills keyed red.");
    d.note("control/rows", "[0]",
           "Without an image: the atlas row at each height band, bottom to top (-1: none), a "
           "control texture one texel wide.");
    return d.out.str();
}

}  // namespace pleinair
