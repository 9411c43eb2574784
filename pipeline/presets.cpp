// Preset lookup, listing and loading.
#include "pipeline/presets.h"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "pipeline/error.h"
#include "pipeline/json_params.h"

namespace pleinair {

namespace fs = std::filesystem;

fs::path preset_root() {
    if (const char* env = std::getenv("PLEINAIR_PRESETS"); env && *env) return env;
    if (fs::is_directory("presets/trees")) return "presets";
    return PLEINAIR_PRESET_DIR;
}

namespace {
std::vector<std::string> preset_names() {
    std::vector<std::string> names;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(preset_root() / "trees", ec))
        if (e.path().extension() == ".json") names.push_back(e.path().stem().string());
    std::sort(names.begin(), names.end());
    return names;
}
}  // namespace

fs::path resolve_tree_preset(const std::string& s) {
    if (s.find('/') != std::string::npos || s.ends_with(".json")) return s;
    fs::path file = preset_root() / "trees" / (s + ".json");
    if (fs::is_regular_file(file)) return file;
    std::string available;
    for (const auto& n : preset_names()) available += (available.empty() ? "" : ", ") + n;
    throw InputError("--preset", "",
                     "no tree preset \"" + s + "\" in " + (preset_root() / "trees").string() +
                         " (available: " + available + ")");
}

TreeParams load_tree_preset(const fs::path& file, const std::vector<std::string>& overrides) {
    std::ifstream in(file, std::ios::binary);
    if (!in || fs::is_directory(file))
        throw InputError(file.string(), "", "cannot read the file (missing or not a file)");
    std::ostringstream text;
    text << in.rdbuf();
    return parse_tree_params(text.str(), file.string(), overrides);
}

std::vector<PresetInfo> list_tree_presets() {
    std::vector<PresetInfo> out;
    for (const auto& name : preset_names()) {
        fs::path file = preset_root() / "trees" / (name + ".json");
        TreeParams p = load_tree_preset(file);
        out.push_back({name, p.description, file});
    }
    return out;
}

}  // namespace pleinair
