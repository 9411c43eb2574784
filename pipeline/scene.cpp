// Scene files: the key table of the fixed sections (documented where parsed) and the families
// and trees lists, each resolved to presets with errors that name the scene file and key.
#include "pipeline/scene.h"

#include <cmath>
#include <glm/geometric.hpp>

#include "pipeline/json_visitors.h"
#include "pipeline/presets.h"
#include "pipeline/shader_io.h"

namespace pleinair {

using namespace json_detail;

namespace {

template <class V>
void visit_scene(SceneDesc& s, V& v) {
    v.text("description", s.description, "One line on what the scene shows.");
    CameraParams& c = s.camera_params;
    v.object("camera", "The perspective camera", [&] {
        v.vector("position", c.position, "world units", "Where the camera stands.");
        v.vector("look_at", c.look_at, "world units",
                 "The point it looks at; its distance is the depth where strokes keep their "
                 "size.");
        v.vector("up", c.up, "", "Up direction; if parallel to the view, +z or -x stands in.");
        v.number("fov", c.fov, {1e-3, 179}, "deg", "Vertical field of view.");
        v.integer("width", c.width, {1, 16384}, "Image width in pixels.");
        v.integer("height", c.height, {1, 16384}, "Image height in pixels.");
    });
    v.object("sun", "The one light (IV.4.1)", [&] {
        v.vector("direction", s.sun_direction, "", "Direction towards the sun; normalised.");
    });
    Background& b = s.background;
    v.object("background", "What shows where no stroke covers the canvas", [&] {
        v.color("sky_zenith", b.sky_zenith, "Sky straight up.");
        v.color("sky_horizon", b.sky_horizon, "Sky at the horizon.");
        v.color("ground_horizon", b.ground_horizon, "Ground at the horizon.");
        v.color("ground_near", b.ground_near, "Ground straight down.");
        v.real("horizon_softness", b.horizon_softness, {0, 1}, "sine of elevation",
               "Band over which sky and ground blend.");
        v.real("texture", b.texture, {0, 1}, "", "Slow noise on the background's lightness.");
        v.boolean("canvas", b.canvas, "Paint one canvas colour instead of sky and ground.");
        v.color("canvas_color", b.canvas_color, "The canvas colour.");
    });
    v.object("atmosphere", "Atmospheric perspective (IV.6); absent: none", [&] {
        s.has_atmosphere = true;
        v.real("near", s.atmosphere.near_distance, {0, 1e9}, "world units",
               "View depth where the effect starts.");
        v.real("far", s.atmosphere.far_distance, {0, 1e9}, "world units",
               "View depth where it is full.");
    });
    RenderSettings& r = s.render;
    v.object("render", "Painter settings", [&] {
        v.real("stroke_perspective", r.stroke_perspective, {0, 1}, "",
               "How strokes shrink with distance: 0 keeps their screen size, 1 is true "
               "perspective (thesis ch. I: brush strokes must not shrink like geometry).");
        v.real("min_stroke_px", r.min_stroke_px, {0, 1000}, "px", "Smallest stroke drawn.");
        v.integer("samples", r.samples, {1, 16}, "Stroke-mask samples per pixel: 1, 4 or 16.");
        v.integer("octaves", r.octaves, {1, 8}, "Octaves of the stroke noise.");
        v.boolean("palette_lut", r.palette_lut,
                  "Tabulate each sprite's colours (palette, tint, atmosphere) against its "
                  "sub-stroke noise at 33 points instead of evaluating them per fragment.");
        v.boolean("filter_strokes", r.filter_strokes,
                  "At 1 sample per pixel, widen each stroke's feather by the pixel's footprint "
                  "in noise space (RenderMan's filterwidth) against aliasing.");
        v.boolean("edge_lut", r.edge_lut,
                  "Read the stroke edge mask from a 256-entry table instead of sin and pow.");
        v.real("bark_coverage", r.bark_coverage, {0, 100}, "",
               "Bark strokes' total area over the limbs' lateral area.");
    });
}

uint64_t read_seed(const json& v, const std::string& ptr, std::vector<Problem>& problems) {
    if (!v.is_number_integer() && !v.is_number_unsigned()) {
        problems.push_back({ptr, "expected a whole number >= 0, got " + describe(v)});
        return 0;
    }
    if (v.is_number_integer() && !v.is_number_unsigned() && v.get<int64_t>() < 0) {
        problems.push_back({ptr, "expected a whole number >= 0, got " + describe(v)});
        return 0;
    }
    return v.get<uint64_t>();
}

// Loads a preset named at the scene's key `ptr`. A problem inside the preset file becomes a
// problem of that key whose message names the file and its own key, so one line says both.
template <class Fn>
void load_into(std::vector<Problem>& problems, const std::string& source, const std::string& ptr,
               Fn&& fn) {
    try {
        fn();
    } catch (const InputError& e) {
        for (const auto& p : e.problems()) {
            if (e.source() == source)
                problems.push_back(p);
            else
                problems.push_back({ptr, e.source() + (p.pointer.empty() ? "" : ": " + p.pointer) +
                                             ": " + p.message});
        }
    }
}

// A file named in a scene is relative to the scene's folder, as a user writing one expects;
// bare names are presets.
std::string near_scene(const std::string& name, const std::string& source) {
    bool is_file = name.find('/') != std::string::npos || name.ends_with(".json");
    std::filesystem::path p(name);
    if (!is_file || p.is_absolute() || !source.ends_with(".json")) return name;
    return (std::filesystem::path(source).parent_path() / p).string();
}

}  // namespace

SceneDesc parse_scene(const std::string& text, const std::string& source,
                      const std::vector<std::string>& overrides) {
    std::vector<Problem> problems;
    std::set<std::string> overridden;
    json doc = parse_document(text, source, overrides, problems, overridden);
    SceneDesc s;
    std::set<std::string> plain;
    Reader reader(doc, problems, plain);
    visit_scene(s, reader);
    reader.claim("families");
    reader.claim("trees");
    reader.finish();

    if (std::string why = make_camera(s.camera_params, s.camera); !why.empty())
        problems.push_back({"/camera", why});
    double sl = glm::length(s.sun_direction);
    if (!(sl > 0) || !std::isfinite(sl))
        problems.push_back({"/sun/direction", "must be a non-zero direction"});
    else
        s.sun_direction /= sl;
    if (s.has_atmosphere && s.atmosphere.far_distance < s.atmosphere.near_distance)
        problems.push_back(
            {"/atmosphere/far", "must be >= near (" + format_number(s.atmosphere.near_distance) +
                                    "), got " + format_number(s.atmosphere.far_distance)});
    if (s.render.samples != 1 && s.render.samples != 4 && s.render.samples != 16)
        problems.push_back(
            {"/render/samples", "must be 1, 4 or 16, got " + std::to_string(s.render.samples)});

    // Families: an object of name -> {preset, leaf_shader, bark_shader, leaf_palette?, ...}.
    auto fam = doc.find("families");
    if (fam != doc.end() && !fam->is_object())
        problems.push_back({"/families", "expected an object of families, got " + describe(*fam)});
    if (fam != doc.end() && fam->is_object()) {
        for (const auto& [name, f] : fam->items()) {
            std::string ptr = "/families/" + name;
            if (!f.is_object()) {
                problems.push_back({ptr, "expected an object, got " + describe(f)});
                continue;
            }
            Family family;
            family.name = name;
            std::string leaf_shader = "corot-leaves", bark_shader = "corot-bark";
            std::string leaf_palette, bark_palette;
            Reader r(f, problems, plain, ptr);
            r.text("preset", family.preset, "");
            r.text("leaf_shader", leaf_shader, "");
            r.text("bark_shader", bark_shader, "");
            r.text("leaf_palette", leaf_palette, "");
            r.text("bark_palette", bark_palette, "");
            r.finish();
            if (family.preset.empty()) {
                problems.push_back({ptr + "/preset", "missing: a tree preset name or file"});
                continue;
            }
            load_into(problems, source, ptr + "/preset", [&] {
                auto file = resolve_preset("trees", near_scene(family.preset, source), source,
                                           ptr + "/preset");
                family.params = load_tree_preset(file);
            });
            auto shader = [&](const std::string& shader_name, const std::string& palette_name,
                              const char* key, const char* pkey, StrokeShaderParams& params,
                              Palette& palette) {
                load_into(problems, source, ptr + "/" + key, [&] {
                    ShaderPreset sp = load_shader_preset(near_scene(shader_name, source), source,
                                                         ptr + "/" + key);
                    params = sp.params;
                    std::string pal = palette_name.empty() ? sp.palette : palette_name;
                    if (pal.empty())
                        throw InputError(source, ptr + "/" + pkey,
                                         "the shader names no palette; give one here");
                    palette = shader_palette(
                        load_palette(near_scene(pal, source), source, ptr + "/" + pkey), params);
                });
            };
            shader(leaf_shader, leaf_palette, "leaf_shader", "leaf_palette", family.leaf_shader,
                   family.leaf_palette);
            shader(bark_shader, bark_palette, "bark_shader", "bark_palette", family.bark_shader,
                   family.bark_palette);
            s.families.push_back(std::move(family));
        }
    }

    auto trees = doc.find("trees");
    if (trees != doc.end() && !trees->is_array())
        problems.push_back({"/trees", "expected a list of trees, got " + describe(*trees)});
    if (trees != doc.end() && trees->is_array()) {
        for (size_t i = 0; i < trees->size(); ++i) {
            const json& t = (*trees)[i];
            std::string ptr = "/trees/" + std::to_string(i);
            if (!t.is_object()) {
                problems.push_back({ptr, "expected an object, got " + describe(t)});
                continue;
            }
            PlacedTree placed;
            std::string family;
            Reader r(t, problems, plain, ptr);
            r.text("family", family, "");
            r.claim("seed");
            r.vector("position", placed.position, "", "");
            r.number("rotation", placed.rotation, {-1e6, 1e6}, "", "");
            r.number("scale", placed.scale, {0, 1e6}, "", "");
            r.finish();
            if (auto it = t.find("seed"); it != t.end())
                placed.seed = read_seed(*it, ptr + "/seed", problems);
            if (!(placed.scale > 0))
                problems.push_back(
                    {ptr + "/scale", "must be > 0, got " + format_number(placed.scale)});
            if (!(std::abs(placed.rotation) <= 1e6))
                problems.push_back({ptr + "/rotation", "must be in [-1e6, 1e6]"});
            bool found = false;
            for (size_t k = 0; k < s.families.size(); ++k)
                if (s.families[k].name == family)
                    placed.family = static_cast<uint32_t>(k), found = true;
            if (!found) {
                std::string names;
                for (const auto& f : s.families) names += (names.empty() ? "" : ", ") + f.name;
                problems.push_back({ptr + "/family", "no family \"" + family +
                                                         "\" in /families (have: " + names + ")"});
                continue;
            }
            s.trees.push_back(placed);
        }
    }
    mark_overrides(problems, overridden);
    if (!problems.empty()) throw InputError(source, problems);
    return s;
}

SceneDesc load_scene(const std::filesystem::path& file, const std::vector<std::string>& overrides) {
    return parse_scene(read_input_file(file), file.string(), overrides);
}

std::string scene_reference() {
    Documenter d;
    d.out << "| key | default | range | unit | meaning |\n|---|---|---|---|---|\n";
    SceneDesc defaults;
    visit_scene(defaults, d);
    return d.out.str();
}

}  // namespace pleinair
