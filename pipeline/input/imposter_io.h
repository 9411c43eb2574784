// Graftal imposter descriptions (presets/imposters/NAME.json): read, checked key by key (every
// problem named by its JSON pointer, exit 2 through InputError), their textures and atlas loaded,
// and documented.
#pragma once

#include <string>
#include <vector>

#include "pipeline/input/imposter_desc.h"

namespace pleinair {

// `source` names the text in messages and is the folder images and graftal files are looked up
// near; `overrides` are --set POINTER=VALUE edits.
ImposterDesc parse_imposter(const std::string& text, const std::string& source,
                            const std::vector<std::string>& overrides = {});

// A name from presets/imposters or a path to a JSON file; `source` and `pointer` name the key
// that asked for it in messages.
ImposterDesc load_imposter(const std::string& name_or_file, const std::string& source = "",
                           const std::string& pointer = "");

// An image file as RGBA floats (grey and RGB files opaque), or InputError at (source, pointer).
ImposterImage read_imposter_image(const std::string& path, const std::string& source,
                                  const std::string& pointer);

// The Markdown table of every key of an imposter description, with defaults and ranges.
std::string imposter_reference();

}  // namespace pleinair
