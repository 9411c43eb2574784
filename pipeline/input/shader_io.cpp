// The stroke shader's key table (every parameter documented where it is parsed, with its
// default) and the palette file reader.
#include "pipeline/input/shader_io.h"

#include "pipeline/input/json_visitors.h"
#include "pipeline/input/presets.h"

namespace pleinair {

using namespace json_detail;

namespace {

// P is StrokeShaderParams or const StrokeShaderParams.
template <class P, class V>
void visit_stroke_shader(P& p, V& v) {
    v.object(
        "palette_cutoffs", "Lightness ranges of the palette's three splines (thesis IV.5)", [&] {
            v.real("dark_cutoff_start", p.dark_cutoff_start, {0, 1}, "lightness",
                   "Below this, colours come from the dark spline only.");
            v.real("dark_cutoff_end", p.dark_cutoff_end, {0, 1}, "lightness",
                   "Between dark_cutoff_start and this, dark and mid splines are mixed.");
            v.real("mid_cutoff_start", p.mid_cutoff_start, {0, 1}, "lightness",
                   "Between dark_cutoff_end and this, the mid spline only.");
            v.real(
                "mid_cutoff_end", p.mid_cutoff_end, {0, 1}, "lightness",
                "Between mid_cutoff_start and this, mid and light are mixed; above, light only.");
        });
    v.real("shadow_bias", p.shadow_bias, {0, 1}, "",
           "Bias on the shadow multiplier after its remap to 0.5..1 (IV.4.2): below 0.5 darkens "
           "shadows, above lightens them.");
    v.object("stroke", "The brush-stroke mask (IV.4.4)", [&] {
        v.real("stroke_fullness", p.stroke_fullness, {0, 1}, "",
               "Bias of the rounded edge mask: higher fills more of the sprite (Fig. 20).");
        v.real("stroke_feather_min", p.stroke_feather_min, {0, 1}, "",
               "Lower smoothstep threshold on noise x edge mask: below it, transparent.");
        v.real("stroke_feather_max", p.stroke_feather_max, {0, 1}, "",
               "Upper threshold: above it, opaque. The gap between the two is the feathering.");
        v.real("max_stroke_opacity", p.max_stroke_opacity, {0, 1}, "",
               "Opacity clamp, so every stroke lets a little of what is behind show through.");
        v.real("stroke_frequ", p.stroke_frequ, {0, 256}, "1/sprite",
               "Base frequency of the stroke noise across a sprite (not in the thesis, which "
               "fixed it in code).");
        v.real("center_frequ_factor", p.center_frequ_factor, {0, 256}, "1/sprite",
               "Frequency added in proportion to the distance from the tree's centre: outer "
               "strokes are smaller.");
        v.real("lightness_frequ_factor", p.lightness_frequ_factor, {0, 256}, "1/sprite",
               "Frequency added in proportion to lightness: lit strokes are smaller.");
        v.real("s_frequ_scale", p.s_frequ_scale, {0, 64}, "",
               "Frequency factor across the stroke (IV.7's separate s and t frequencies).");
        v.real("t_frequ_scale", p.t_frequ_scale, {0, 64}, "", "Frequency factor along the stroke.");
    });
    v.object("sub_stroke", "Colour variation inside a stroke (IV.4.3)", [&] {
        v.real("sub_stroke_frequ", p.sub_stroke_frequ, {0, 256}, "1/sprite",
               "Frequency of the noise that varies the palette lookup within a stroke.");
        v.real("sub_stroke_amt", p.sub_stroke_amt, {0, 1}, "lightness",
               "How far that noise moves the lookup (peak to peak); 0 turns it off.");
        v.real("sub_stroke_s_scale", p.sub_stroke_s_scale, {0, 64}, "",
               "That noise's frequency factor across the stroke: with a low t scale, streaks "
               "along the stroke, as a brush's bristles leave.");
        v.real("sub_stroke_t_scale", p.sub_stroke_t_scale, {0, 64}, "",
               "That noise's frequency factor along the stroke.");
    });
    v.object("lighting", "Lightness from the particle's place in the tree (IV.4.1)", [&] {
        v.real("outer_brighten", p.outer_brighten, {0, 1}, "",
               "How much leaves on the outside of the tree are lightened.");
        v.real("inner_darken", p.inner_darken, {0, 1}, "",
               "How much leaves near the centre are darkened (fades with LOD distance, IV.6).");
        v.real("center_gain", p.center_gain, {0, 1}, "",
               "Gain on the distance from the centre before it is used; limits the effect to the "
               "outermost and innermost leaves.");
        v.real("branch_gain", p.branch_gain, {0, 1}, "",
               "Gain on the distance along the implied branch, likewise.");
    });
    v.object("tint", "Per-tree tint (IV.5)", [&] {
        v.real("unique_tint_amt", p.unique_tint_amt, {0, 1}, "",
               "Amount of the tree's tint mixed into every colour; keep it small. 0 skips the "
               "pass.");
        v.color("tint_color1", p.tint_color1, "One end of the tint, picked by tree id.");
        v.color("tint_color2", p.tint_color2, "The other end.");
    });
    v.object("distance", "Atmospheric perspective (IV.6)", [&] {
        v.real("dist_curve_bias", p.dist_curve_bias, {0, 1}, "",
               "Bias on the 0..1 distance between the scene's near and far: low values keep the "
               "middle distance clear and grow the effect far away.");
        v.color("dist_hue_color", p.dist_hue_color, "Colour distant strokes shift towards.");
        v.real("dist_hue_strength", p.dist_hue_strength, {0, 1}, "",
               "How much of dist_hue_color is mixed in at the far distance.");
        v.real("dist_sat_limiter", p.dist_sat_limiter, {0, 1}, "",
               "Saturation removed at the far distance (the limit is 1 - this x distance).");
        v.real("dist_value_min", p.dist_value_min, {0, 1}, "sRGB",
               "Darkest value allowed at the far distance (raises the darks).");
        v.real("dist_value_max", p.dist_value_max, {0, 1}, "sRGB",
               "Lightest value allowed at the far distance (lowers the lights).");
    });
    v.object("sprite", "The sprite each particle becomes", [&] {
        v.real("sprite_size", p.sprite_size, {0, 1e4}, "tree units",
               "World size of a stroke (its width; its length is width x stroke_aspect).");
        v.real("size_jitter", p.size_jitter, {0, 1}, "", "Relative size variation, by label.");
        v.real("stroke_aspect", p.stroke_aspect, {0.05, 20}, "",
               "Length over width; bark strokes lie along their limb.");
        v.real("angle_jitter", p.angle_jitter, {0, 180}, "deg",
               "Rotation variation of the stroke on screen, by label.");
        v.real("stroke_angle", p.stroke_angle, {-180, 180}, "deg",
               "Direction on screen of the strokes that follow no surface or limb (leaves), "
               "counter-clockwise from upright: 0 stands them up, 90 lays them flat, as the "
               "foliage of Corot's Souvenir of Coubron, \"a mass of horizontal strokes\".");
        v.real("hanging_slope", p.hanging_slope, {0, 91}, "deg",
               "A leaf whose implied branch falls more steeply than this below horizontal has "
               "its stroke run down along that branch on screen instead of at stroke_angle: a "
               "willow's curtains in falling strokes among a crown's flat ones; 91: none.");
    });
    v.object("crown", "A crown seen up close (leaf strokes; ours, past the thesis)", [&] {
        v.real("sun_side", p.sun_side, {0, 1}, "",
               "How much a leaf's side of the crown (facing the sun or away, seen from the "
               "crown's centre locator) lightens or darkens it: lights gather on the sunlit "
               "side. 0: the leaf's own light only.");
        v.real("edge_shrink", p.edge_shrink, {0, 1}, "",
               "Strokes shrink towards the crown's edge, by up to this share of their size.");
        v.real("edge_break", p.edge_break, {0, 1}, "",
               "Strokes beyond half the centre distance break into dabs (their noise threshold "
               "rises), keeping down to 1 - this of their coverage at the edge.");
        v.real("holes", p.holes, {0, 1}, "",
               "About this share of the leaves at the crown's edge, fewer inwards and none "
               "within half the centre distance, left out in clustered holes the sky shows "
               "through. Their shadows stay.");
        v.real("hole_frequ", p.hole_frequ, {0, 100}, "1/tree unit",
               "Frequency of the noise that places those holes over the tree.");
    });
}

template <class P, class V>
void visit_surface_shader(P& p, V& v) {
    v.object(
        "surface", "The generalized stroke shader for surfaces (IV.7); surface materials only",
        [&] {
            v.real("random_normal_weight", p.random_normal_weight, {0, 1}, "",
                   "Lighting normal: 0 the surface's (aggregate) normal, 1 the particle's random "
                   "one (Peterson and Lee).");
            v.real("depth_darken", p.depth_darken, {0, 1}, "lightness",
                   "Lightness taken from the deepest strokes, so detail strokes show on top.");
            v.real("detail_threshold", p.detail_threshold, {0, 1}, "",
                   "Displacement height (0 deepest, 1 highest) above which a stroke is detail: its "
                   "own frequencies, and it fades with distance (\"Min Out for Fadeoff\").");
            v.real("base_frequ", p.base_frequ, {0, 256}, "1/sprite",
                   "Noise frequency of base strokes.");
            v.real("detail_frequ_add", p.detail_frequ_add, {0, 256}, "1/sprite",
                   "Frequency added for detail strokes.");
            v.real("base_s_frequ", p.base_s_frequ, {0, 64}, "", "Base strokes: factor across (s).");
            v.real("base_t_frequ", p.base_t_frequ, {0, 64}, "", "Base strokes: factor along (t).");
            v.real("detail_s_frequ", p.detail_s_frequ, {0, 64}, "",
                   "Detail strokes across: high for grass's thin vertical tufts.");
            v.real("detail_t_frequ", p.detail_t_frequ, {0, 64}, "", "Detail strokes along.");
            v.real("crest_shrink", p.crest_shrink, {0, 1}, "",
                   "Height lost by a sprite whose surface is edge-on to the view (Fig. 25), so "
                   "strokes do not stand above a ridge.");
            v.real("inside_growth", p.inside_growth, {0, 100}, "",
                   "Deepest sprites are 1 + this times the size of the top ones.");
            v.real("lay", p.lay, {0, 1}, "",
                   "Base strokes laid along the ground: 0 they stand (their length up the "
                   "world's y, as grass's tufts), 1 they lie across the slope (a brush "
                   "following the contour), or along lay_azimuth where the ground is level. "
                   "Detail strokes stand.");
            v.real("lay_azimuth", p.lay_azimuth, {-360, 360}, "deg",
                   "Where the ground is level, the direction lying strokes take: degrees about "
                   "+y from +x (90: towards -z, away from a camera looking down -z).");
            v.real("base_aspect", p.base_aspect, {0.1, 10}, "",
                   "Base strokes' length over width as a factor on sprite/stroke_aspect (1: the "
                   "tufts' shape): above 1 a long brush laid across the ground while the tufts "
                   "keep theirs.");
        });
}

}  // namespace

ShaderPreset parse_shader_preset(const std::string& text, const std::string& source,
                                 const std::vector<std::string>& overrides) {
    std::vector<Problem> problems;
    std::set<std::string> overridden;
    json doc = parse_document(text, source, overrides, problems, overridden);
    ShaderPreset out;
    std::set<std::string> plain;
    Reader reader(doc, problems, plain);
    reader.text("description", out.description, "");
    reader.text("palette", out.palette, "");
    visit_stroke_shader(out.params, reader);
    out.has_surface = doc.contains("surface");
    visit_surface_shader(out.surface, reader);
    reader.finish();
    const auto& p = out.params;
    if (p.dark_cutoff_start > p.dark_cutoff_end)
        problems.push_back({"/palette_cutoffs/dark_cutoff_end",
                            "must be >= dark_cutoff_start (" + format_number(p.dark_cutoff_start) +
                                "), got " + format_number(p.dark_cutoff_end)});
    if (p.dark_cutoff_end > p.mid_cutoff_start)
        problems.push_back({"/palette_cutoffs/mid_cutoff_start",
                            "must be >= dark_cutoff_end (" + format_number(p.dark_cutoff_end) +
                                "), got " + format_number(p.mid_cutoff_start)});
    if (p.mid_cutoff_start > p.mid_cutoff_end)
        problems.push_back({"/palette_cutoffs/mid_cutoff_end",
                            "must be >= mid_cutoff_start (" + format_number(p.mid_cutoff_start) +
                                "), got " + format_number(p.mid_cutoff_end)});
    if (p.stroke_feather_min > p.stroke_feather_max)
        problems.push_back({"/stroke/stroke_feather_max", "must be >= stroke_feather_min (" +
                                                              format_number(p.stroke_feather_min) +
                                                              "), got " +
                                                              format_number(p.stroke_feather_max)});
    if (p.dist_value_min > p.dist_value_max)
        problems.push_back({"/distance/dist_value_max",
                            "must be >= dist_value_min (" + format_number(p.dist_value_min) +
                                "), got " + format_number(p.dist_value_max)});
    mark_overrides(problems, overridden);
    if (!problems.empty()) throw InputError(source, problems);
    return out;
}

PaletteFile parse_palette(const std::string& text, const std::string& source) {
    std::vector<Problem> problems;
    std::set<std::string> overridden;
    json doc = parse_document(text, source, {}, problems, overridden);
    PaletteFile out;
    std::string basis = "linear";
    std::set<std::string> plain;
    Reader reader(doc, problems, plain);
    reader.text("description", out.description, "");
    reader.text("basis", basis, "");
    for (const char* key : {"dark", "mid", "light"}) reader.claim(key);  // read below
    reader.finish();
    SplineBasis b = SplineBasis::kLinear;
    if (basis == "catmull-rom")
        b = SplineBasis::kCatmullRom;
    else if (basis != "linear")
        problems.push_back(
            {"/basis", "expected \"linear\" or \"catmull-rom\", got \"" + basis + "\""});
    for (auto [key, spline] :
         {std::pair{"dark", &out.palette.dark}, std::pair{"mid", &out.palette.mid},
          std::pair{"light", &out.palette.light}}) {
        spline->basis = b;
        std::string ptr = std::string("/") + key;
        auto it = doc.find(key);
        if (it == doc.end()) {
            problems.push_back({ptr, "missing: a list of colours from dark to light"});
            continue;
        }
        if (!it->is_array() || it->empty()) {
            problems.push_back({ptr, "expected a non-empty list of colours, got " + describe(*it)});
            continue;
        }
        for (size_t i = 0; i < it->size(); ++i) {
            glm::vec3 c;
            if (!parse_color((*it)[i], c))
                problems.push_back({ptr + "/" + std::to_string(i),
                                    "expected a colour [r, g, b] in 0..1 or \"#rrggbb\", got " +
                                        describe((*it)[i])});
            else
                spline->colors.push_back(srgb_to_linear(c));
        }
    }
    if (!problems.empty()) throw InputError(source, problems);
    return out;
}

ShaderPreset load_shader_preset(const std::string& name, const std::string& source,
                                const std::string& pointer,
                                const std::vector<std::string>& overrides) {
    auto file = resolve_preset("shaders", name, source.empty() ? "--shader" : source, pointer);
    return parse_shader_preset(read_input_file(file), file.string(), overrides);
}

PaletteFile load_palette(const std::string& name, const std::string& source,
                         const std::string& pointer) {
    auto file = resolve_preset("palettes", name, source.empty() ? "--palette" : source, pointer);
    return parse_palette(read_input_file(file), file.string());
}

Palette shader_palette(const PaletteFile& file, const StrokeShaderParams& p) {
    Palette out = file.palette;
    out.dark_cutoff_start = p.dark_cutoff_start;
    out.dark_cutoff_end = p.dark_cutoff_end;
    out.mid_cutoff_start = p.mid_cutoff_start;
    out.mid_cutoff_end = p.mid_cutoff_end;
    return out;
}

std::string shader_key_catalog(const StrokeShaderParams& params) {
    Cataloguer c;
    visit_stroke_shader(params, c);
    return c.rows.dump();
}

std::string stroke_shader_reference() {
    Documenter d;
    d.out << "| key | default | range | unit | meaning |\n|---|---|---|---|---|\n";
    StrokeShaderParams defaults;
    visit_stroke_shader(defaults, d);
    SurfaceShaderParams surface;
    visit_surface_shader(surface, d);
    return d.out.str();
}

}  // namespace pleinair
