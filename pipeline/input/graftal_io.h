// Graftal description files (presets/graftals/NAME.json): read, checked key by key (every
// problem named by its JSON pointer, exit 2 through InputError), and documented.
#pragma once

#include <string>
#include <vector>

#include "pipeline/input/graftal_desc.h"

namespace pleinair {

// `source` names the text in messages; `overrides` are --set POINTER=VALUE edits.
GraftalDesc parse_graftal(const std::string& text, const std::string& source,
                          const std::vector<std::string>& overrides = {});

// A name from presets/graftals or a path to a JSON file; `source` and `pointer` name the key
// that asked for it in messages.
GraftalDesc load_graftal(const std::string& name_or_file, const std::string& source = "",
                         const std::string& pointer = "");

// The Markdown table of every key of a graftal description, with defaults and ranges.
std::string graftal_reference();

}  // namespace pleinair
