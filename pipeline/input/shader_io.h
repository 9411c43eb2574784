// Stroke-shader and palette presets (presets/shaders, presets/palettes): parsing with one error
// line per problem, unknown keys rejected, and the documented reference of every shader key.
#pragma once

#include <string>
#include <vector>

#include "shading/stroke_shader.h"
#include "shading/surface_shader.h"

namespace pleinair {

struct ShaderPreset {
    std::string description;
    std::string palette;  // name or file of the palette whose splines this shader reads
    StrokeShaderParams params;
    // IV.7's generalized stroke shader (grass, rock, ground, water): read from the preset's
    // optional "surface" section; only surface materials use it.
    SurfaceShaderParams surface;
    bool has_surface = false;
};

// Starts from StrokeShaderParams' defaults and overrides the keys present. Throws InputError.
ShaderPreset parse_shader_preset(const std::string& text, const std::string& source,
                                 const std::vector<std::string>& overrides = {});

// A palette's three splines (colours sRGB in the file, linear in the result); the cut-offs are
// the shader's and are left at their defaults. Throws InputError.
struct PaletteFile {
    std::string description;
    Palette palette;
};
PaletteFile parse_palette(const std::string& text, const std::string& source);

// Loads by name (presets/shaders/NAME.json) or path; `source`/`pointer` name who asked, for the
// error when nothing matches.
ShaderPreset load_shader_preset(const std::string& name_or_file, const std::string& source = "",
                                const std::string& pointer = "",
                                const std::vector<std::string>& overrides = {});
PaletteFile load_palette(const std::string& name_or_file, const std::string& source = "",
                         const std::string& pointer = "");

// The palette with the shader's cut-offs applied.
Palette shader_palette(const PaletteFile& file, const StrokeShaderParams& params);

// Markdown table of every shader key: pointer, default, range, unit and meaning.
std::string stroke_shader_reference();

// The stroke shader's keys (not the surface section) as a JSON array of rows, as
// tree_key_catalog (json_params.h) gives the tree's.
std::string shader_key_catalog(const StrokeShaderParams& params);

}  // namespace pleinair
