// Preset lookup, listing and loading.
#include "pipeline/input/presets.h"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string_view>

#include "pipeline/input/error.h"
#include "pipeline/input/json_params.h"
#include "pipeline/input/limits.h"

namespace pleinair {

namespace fs = std::filesystem;

fs::path preset_root() {
    if (const char* env = std::getenv("PLEINAIR_PRESETS"); env && *env) return env;
    if (fs::is_directory("presets/trees")) return "presets";
    return PLEINAIR_PRESET_DIR;
}

std::vector<std::string> preset_names(const std::string& kind) {
    std::vector<std::string> names;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(preset_root() / kind, ec))
        if (e.path().extension() == ".json") names.push_back(e.path().stem().string());
    std::sort(names.begin(), names.end());
    return names;
}

fs::path resolve_preset(const std::string& kind, const std::string& s, const std::string& source,
                        const std::string& pointer) {
    if (s.find('/') != std::string::npos || s.ends_with(".json")) return s;
    fs::path file = preset_root() / kind / (s + ".json");
    if (fs::is_regular_file(file)) return file;
    std::string available;
    for (const auto& n : preset_names(kind)) available += (available.empty() ? "" : ", ") + n;
    std::string what = kind == "trees" ? "tree" : kind.substr(0, kind.size() - 1);
    throw InputError(source, pointer,
                     "no " + what + " preset \"" + s + "\" in " + (preset_root() / kind).string() +
                         " (available: " + available + ")");
}

fs::path resolve_tree_preset(const std::string& s, const std::string& source) {
    return resolve_preset("trees", s, source);
}

std::string read_input_file(const fs::path& file, const char* limit) {
    std::ifstream in(file, std::ios::binary);
    if (!in || fs::is_directory(file))
        throw InputError(file.string(), "", "cannot read the file (missing or not a file)");
    const bool particles = limit && std::string_view(limit) == "particle_file_mb";
    const uint64_t max_mb = particles ? limits().particle_file_mb : limits().input_mb;
    // Read in blocks up to the limit, so a pipe or a growing file cannot exhaust memory either.
    std::string text;
    std::error_code ec;
    if (const uintmax_t size = fs::file_size(file, ec); !ec && (size >> 20) < max_mb)
        text.reserve(static_cast<size_t>(size));
    char block[1 << 16];
    while (in.read(block, sizeof block) || in.gcount() > 0) {
        text.append(block, static_cast<size_t>(in.gcount()));
        if (text.size() > (max_mb << 20))
            throw InputError(file.string(), "",
                             "larger than the limit of " + std::to_string(max_mb) + " MB for " +
                                 (particles ? "a particle file" : "an input file") + "; " +
                                 how_to_raise(particles ? "particle_file_mb" : "input_mb"));
    }
    return text;
}

TreeParams load_tree_preset(const fs::path& file, const std::vector<std::string>& overrides) {
    return parse_tree_params(read_input_file(file), file.string(), overrides);
}

std::vector<PresetInfo> list_tree_presets() {
    std::vector<PresetInfo> out;
    for (const auto& name : preset_names("trees")) {
        fs::path file = preset_root() / "trees" / (name + ".json");
        TreeParams p = load_tree_preset(file);
        out.push_back({name, p.description, file});
    }
    return out;
}

}  // namespace pleinair
