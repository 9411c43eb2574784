// Where presets live and how a name or a file becomes TreeParams.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "generators/tree_params.h"

namespace pleinair {

// The presets folder: $PLEINAIR_PRESETS if set, else ./presets if it holds trees/, else the
// source tree's presets/ the binary was built from.
std::filesystem::path preset_root();

struct PresetInfo {
    std::string name;
    std::string description;
    std::filesystem::path file;
};

// Names of the presets of one kind ("trees", "shaders", "palettes", "scenes"), sorted.
std::vector<std::string> preset_names(const std::string& kind);

// A path (contains '/' or ends in .json) is returned as is; a bare name is looked up in
// preset_root()/kind. Throws InputError(source, pointer, ...) naming what is available.
std::filesystem::path resolve_preset(const std::string& kind, const std::string& name_or_file,
                                     const std::string& source, const std::string& pointer = "");

// The whole file, or InputError naming it; a file past the limit named ("input_mb" or
// "particle_file_mb", pipeline/input/limits.h) is refused once that many bytes are read.
std::string read_input_file(const std::filesystem::path& file, const char* limit = "input_mb");

// Shipped tree presets, sorted by name. Throws InputError if one does not load.
std::vector<PresetInfo> list_tree_presets();

// A path (contains '/' or ends in .json) is read as is; a bare name is looked up in
// preset_root()/trees. Throws InputError naming what is available if nothing matches.
// `source` names where the name came from in an error (an option, or a command's argument).
std::filesystem::path resolve_tree_preset(const std::string& name_or_file,
                                          const std::string& source = "--preset");

// Reads, applies "POINTER=VALUE" overrides, validates. Throws InputError.
TreeParams load_tree_preset(const std::filesystem::path& file,
                            const std::vector<std::string>& overrides = {});

}  // namespace pleinair
