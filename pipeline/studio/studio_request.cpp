// The studio's change requests, parsed and checked (studio_request.h).
#include "pipeline/studio/studio_request.h"

#include <algorithm>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <system_error>

namespace pleinair {

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

// Whether `p` lies within `root`, both made canonical as far as they exist (so "..", and links
// out of the folder, count where they lead).
bool within(const fs::path& p, const fs::path& root) {
    std::error_code ec;
    const fs::path a = fs::weakly_canonical(p, ec);
    if (ec) return false;
    const fs::path r = fs::weakly_canonical(root, ec);
    if (ec) return false;
    auto ai = a.begin();
    for (auto ri = r.begin(); ri != r.end(); ++ri, ++ai)
        if (ai == a.end() || *ai != *ri) return false;
    return true;
}

// The first string in `v` naming a file outside `roots`, or "".
std::string file_outside(const json& v, const std::vector<fs::path>& roots,
                         const fs::path& scene_dir) {
    if (v.is_string()) {
        const std::string s = v.get<std::string>();
        const bool file = s.find('/') != std::string::npos || s.find('\\') != std::string::npos ||
                          s.ends_with(".json") || s.ends_with(".ply");
        if (!file) return "";
        const fs::path p = fs::path(s).is_absolute() ? fs::path(s) : scene_dir / s;
        for (const fs::path& r : roots)
            if (within(p, r)) return "";
        return s;
    }
    if (v.is_structured())
        for (const json& e : v)
            if (std::string f = file_outside(e, roots, scene_dir); !f.empty()) return f;
    return "";
}

// A pointer or value as one printable line: control characters escaped (\n, \xNN).
std::string printable(const std::string& s) {
    std::string out;
    for (unsigned char c : s) {
        if (c == '\n') {
            out += "\\n";
        } else if (c < 0x20 || c == 0x7f) {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\x%02X", c);
            out += buf;
        } else {
            out += static_cast<char>(c);
        }
    }
    return out;
}

// --set's VALUE text for a JSON value: a string as itself unless it would read as another
// JSON value (then quoted, so "true" stays a string), anything else as JSON.
std::string set_text(const json& v) {
    if (!v.is_string()) return v.dump();
    const std::string s = v.get<std::string>();
    const json parsed = json::parse(s, nullptr, false);
    return parsed.is_discarded() ? s : v.dump();
}

}  // namespace

StudioChange parse_studio_change(const std::string& body, const std::vector<fs::path>& readable,
                                 const fs::path& scene_dir) {
    // Depth-limited like every input: a hostile body cannot nest deep enough to exhaust the
    // stack of the recursive walk below.
    int depth = 0, deepest = 0;
    for (char c : body) {
        if (c == '[' || c == '{') deepest = std::max(deepest, ++depth);
        if (c == ']' || c == '}') --depth;
    }
    if (deepest > 64) throw RequestRefused("the request nests more than 64 levels deep", "");
    const json doc = json::parse(body, nullptr, false);
    if (doc.is_discarded() || !doc.is_object())
        throw RequestRefused("expected a JSON object {\"set\": {POINTER: VALUE}}", "");
    StudioChange out;
    for (const auto& [key, v] : doc.items()) {
        if (key == "set") {
            if (!v.is_object()) throw RequestRefused("\"set\": expected an object", "");
            for (const auto& [p, value] : v.items()) {
                // A change names presets by name, or files in the preset folders, the scene's
                // folder or --save-to: the page cannot make the studio read anything else.
                if (std::string f = file_outside(value, readable, scene_dir); !f.empty())
                    throw RequestRefused(printable(p) + ": \"" + printable(f) +
                                             "\": the studio reads files only from the preset "
                                             "folders, the scene's folder and --save-to",
                                         p);
                out.set.emplace_back(p, set_text(value));
            }
        } else if (key == "unset") {
            if (!v.is_array()) throw RequestRefused("\"unset\": expected pointers", "");
            for (const json& p : v) {
                if (!p.is_string()) throw RequestRefused("\"unset\": expected pointers", "");
                out.unset.push_back(p.get<std::string>());
            }
        } else {
            throw RequestRefused("\"" + printable(key) + "\": unknown key (set, unset)", "");
        }
    }
    return out;
}

}  // namespace pleinair
