// The JSON side of the key-table visitors (Reader, Writer, Documenter) shared by every preset
// and scene parser. Internal to pipeline/*.cpp: it includes nlohmann/json, so no public header
// may include it.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <iterator>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "generators/tree_params.h"
#include "pipeline/input/error.h"

namespace pleinair::json_detail {

using json = nlohmann::json;
using ordered_json = nlohmann::ordered_json;

inline std::string describe(const json& v) {
    // Invalid UTF-8 cannot reach a value (files and --set are checked), but a message must
    // never throw while it is being built.
    std::string s = v.dump(-1, ' ', false, json::error_handler_t::replace);
    if (s.size() > 40) s = s.substr(0, 37) + "...";
    return s;
}

// [r, g, b] with each in 0..1, or "#rrggbb"; false for anything else.
inline bool parse_color(const json& v, glm::vec3& out) {
    if (v.is_string()) {
        const std::string& t = v.get_ref<const std::string&>();
        if (t.size() != 7 || t[0] != '#') return false;
        unsigned rgb[3];
        for (int i = 0; i < 3; ++i) {
            unsigned x = 0;
            for (int j = 0; j < 2; ++j) {
                char c = t[1 + 2 * i + j];
                int d = c >= '0' && c <= '9'   ? c - '0'
                        : c >= 'a' && c <= 'f' ? c - 'a' + 10
                        : c >= 'A' && c <= 'F' ? c - 'A' + 10
                                               : -1;
                if (d < 0) return false;
                x = x * 16 + static_cast<unsigned>(d);
            }
            rgb[i] = x;
        }
        out = glm::vec3(rgb[0], rgb[1], rgb[2]) / 255.0f;
        return true;
    }
    if (!v.is_array() || v.size() != 3) return false;
    glm::vec3 c;
    for (int i = 0; i < 3; ++i) {
        if (!v[i].is_number()) return false;
        double d = v[i].get<double>();
        if (!(d >= 0.0 && d <= 1.0)) return false;
        c[i] = static_cast<float>(d);
    }
    out = c;
    return true;
}

inline size_t edit_distance(const std::string& a, const std::string& b) {
    std::vector<size_t> row(b.size() + 1);
    for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (size_t i = 1; i <= a.size(); ++i) {
        size_t diag = row[0];
        row[0] = i;
        for (size_t j = 1; j <= b.size(); ++j) {
            size_t up = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] != b[j - 1])});
            diag = up;
        }
    }
    return row[b.size()];
}

// "\"a\", \"b\" or \"c\"": the names of a choice, for messages and the reference.
template <class Names>
std::string choice_list(const Names& names) {
    std::string out;
    size_t i = 0, n = std::size(names);
    for (const auto& [value, name] : names) {
        if (i > 0) out += i + 1 == n ? " or " : ", ";
        out += json(name).dump();
        ++i;
    }
    return out;
}

// The name of `x` in a choice's names.
template <class E, class Names>
std::string choice_name(E x, const Names& names) {
    for (const auto& [value, name] : names)
        if (value == x) return name;
    return "";
}

// Reads the keys the table asks for; what the table never asked for is an unknown key.
class Reader {
  public:
    // `prefix` is the JSON pointer of `root` in its file, for objects inside arrays.
    Reader(const json& root, std::vector<Problem>& problems, std::set<std::string>& plain_params,
           std::string prefix = "")
        : problems_(problems), plain_(plain_params) {
        frames_.push_back({&root, std::move(prefix), {}});
    }
    void finish() { report_unknown(); }
    // Marks a key of the current object as known, for keys the caller reads itself.
    void claim(const char* key) { find(key); }

    template <class Fn>
    void object(const char* key, const char*, Fn&& fn) {
        const json* v = find(key);
        if (!v) return;
        if (!v->is_object()) return fail(key, "expected an object, got " + describe(*v));
        frames_.push_back({v, pointer(key), {}});
        fn();
        report_unknown();
        frames_.pop_back();
    }
    void param(const char* key, Param& p, const char*, const char*) {
        const json* v = find(key);
        if (!v) return;
        if (v->is_number()) {
            p.base = v->get<double>();
            p.var = 0;
            plain_.insert(pointer(key));
            return;
        }
        if (!v->is_object())
            return fail(key, "expected a number or {\"base\": b, \"var\": v}, got " + describe(*v));
        for (const auto& [k, x] : v->items()) {
            std::string ptr = pointer(key) + "/" + pointer_token(k);
            if (k != "base" && k != "var")
                problems_.push_back(
                    {ptr, "unknown key (a varied number has \"base\" and \"var\")"});
            else if (!x.is_number())
                problems_.push_back({ptr, "expected a number, got " + describe(x)});
            else
                (k == "base" ? p.base : p.var) = x.get<double>();
        }
    }
    void number(const char* key, double& x, Range r, const char*, const char*) {
        const json* v = find(key);
        if (!v) return;
        if (!v->is_number()) return fail(key, "expected a number, got " + describe(*v));
        const double d = v->get<double>();
        if (check_ranges_ && !(d >= r.lo && d <= r.hi))
            return fail(key, "must be in " + format_range(r.lo, r.hi) + ", got " + describe(*v));
        x = d;
    }
    // Numbers are checked against their ranges here (scenes); tree presets leave that to
    // their validator, which knows the per-step ranges.
    void check_ranges() { check_ranges_ = true; }
    void integer(const char* key, int& x, Range r, const char*) {
        const json* v = find(key);
        if (!v) return;
        double d = v->is_number() ? v->get<double>() : NAN;
        if (!v->is_number() || d != std::floor(d))
            return fail(key, "expected an integer, got " + describe(*v));
        // Checked here, not by the validator: an int cannot hold every JSON integer.
        if (d < r.lo || d > r.hi)
            return fail(key, "must be in " + format_range(r.lo, r.hi) + ", got " + describe(*v));
        x = static_cast<int>(d);
    }
    void boolean(const char* key, bool& x, const char*) {
        const json* v = find(key);
        if (!v) return;
        if (!v->is_boolean()) return fail(key, "expected true or false, got " + describe(*v));
        x = v->get<bool>();
    }
    void vector(const char* key, glm::dvec3& x, const char*, const char*) {
        const json* v = find(key);
        if (!v) return;
        if (!v->is_array() || v->size() != 3 || !(*v)[0].is_number() || !(*v)[1].is_number() ||
            !(*v)[2].is_number())
            return fail(key, "expected three numbers [x, y, z], got " + describe(*v));
        x = {(*v)[0].get<double>(), (*v)[1].get<double>(), (*v)[2].get<double>()};
    }
    void seed(const char* key, uint64_t& x, const char*) {
        const json* v = find(key);
        if (!v) return;
        if (!v->is_number_unsigned() && !(v->is_number_integer() && v->get<int64_t>() >= 0))
            return fail(key, "expected a whole number >= 0, got " + describe(*v));
        x = v->get<uint64_t>();
    }
    void vector2(const char* key, glm::dvec2& x, const char*, const char*) {
        const json* v = find(key);
        if (!v) return;
        if (!v->is_array() || v->size() != 2 || !(*v)[0].is_number() || !(*v)[1].is_number())
            return fail(key, "expected two numbers [x, z], got " + describe(*v));
        x = {(*v)[0].get<double>(), (*v)[1].get<double>()};
    }
    // A float checked against its range here (shader and scene tables have no separate
    // validator).
    void real(const char* key, float& x, Range r, const char*, const char*) {
        const json* v = find(key);
        if (!v) return;
        if (!v->is_number()) return fail(key, "expected a number, got " + describe(*v));
        double d = v->get<double>();
        if (!(d >= r.lo && d <= r.hi))
            return fail(key, "must be in " + format_range(r.lo, r.hi) + ", got " + describe(*v));
        x = static_cast<float>(d);
    }
    // An sRGB colour: [r, g, b] in 0..1 or "#rrggbb".
    void color(const char* key, glm::vec3& x, const char*) {
        const json* v = find(key);
        if (!v) return;
        if (!parse_color(*v, x))
            return fail(key,
                        "expected a colour [r, g, b] in 0..1 or \"#rrggbb\", got " + describe(*v));
    }
    void text(const char* key, std::string& x, const char*) {
        const json* v = find(key);
        if (!v) return;
        if (!v->is_string()) return fail(key, "expected a string, got " + describe(*v));
        x = v->get<std::string>();
    }
    // One of a fixed set of names (pairs of value and name), read once into its enum.
    template <class E, class Names>
    void choice(const char* key, E& x, const Names& names, const char*) {
        const json* v = find(key);
        if (!v) return;
        if (v->is_string())
            for (const auto& [value, name] : names)
                if (v->get_ref<const std::string&>() == name) {
                    x = value;
                    return;
                }
        fail(key, "expected " + choice_list(names) + ", got " + describe(*v));
    }
    // The key must be present in the current object (read by the call that follows).
    void require(const char* key) {
        if (!frames_.back().obj->contains(key)) fail(key, "missing: this key is required");
    }

  private:
    struct Frame {
        const json* obj;
        std::string path;
        std::vector<std::string> asked;
    };
    std::vector<Frame> frames_;
    bool check_ranges_ = false;
    std::vector<Problem>& problems_;
    std::set<std::string>& plain_;

    std::string pointer(const char* key) const { return frames_.back().path + "/" + key; }
    const json* find(const char* key) {
        Frame& f = frames_.back();
        f.asked.push_back(key);
        auto it = f.obj->find(key);
        return it == f.obj->end() ? nullptr : &*it;
    }
    void fail(const char* key, std::string message) {
        problems_.push_back({pointer(key), std::move(message)});
    }
    void report_unknown() {
        const Frame& f = frames_.back();
        for (const auto& [k, v] : f.obj->items()) {
            if (std::find(f.asked.begin(), f.asked.end(), k) != f.asked.end()) continue;
            std::string msg = "unknown key";
            const std::string* best = nullptr;
            size_t best_d = 3;
            for (const auto& a : f.asked)
                if (size_t d = edit_distance(k, a); d < best_d) best_d = d, best = &a;
            if (best) msg += " (did you mean \"" + *best + "\"?)";
            problems_.push_back({f.path + "/" + pointer_token(k), msg});
        }
    }
};

// A list of objects under `key` of `parent` (absent: nothing): each element gets a reader at
// its own pointer, checked against the key table `read` visits, unknown keys reported.
template <class Fn>
inline void read_list(const json& parent, const char* key, const std::string& ptr,
                      std::vector<Problem>& problems, std::set<std::string>& plain, Fn&& read) {
    auto it = parent.find(key);
    if (it == parent.end()) return;
    if (!it->is_array()) {
        problems.push_back({ptr, "expected a list, got " + describe(*it)});
        return;
    }
    for (size_t i = 0; i < it->size(); ++i) {
        const std::string elem = ptr + "/" + std::to_string(i);
        const json& j = (*it)[i];
        if (!j.is_object()) {
            problems.push_back({elem, "expected an object, got " + describe(j)});
            continue;
        }
        Reader r(j, problems, plain, elem);
        r.check_ranges();
        read(j, r, elem);
        r.finish();
    }
}

class Writer {
  public:
    ordered_json root = ordered_json::object();
    Writer() { stack_.push_back(&root); }

    template <class Fn>
    void object(const char* key, const char*, Fn&& fn) {
        ordered_json& child = (*stack_.back())[key] = ordered_json::object();
        stack_.push_back(&child);
        fn();
        stack_.pop_back();
    }
    void param(const char* key, const Param& p, const char*, const char*) {
        (*stack_.back())[key] = {{"base", p.base}, {"var", p.var}};
    }
    void number(const char* key, double x, Range, const char*, const char*) {
        (*stack_.back())[key] = x;
    }
    void integer(const char* key, int x, Range, const char*) { (*stack_.back())[key] = x; }
    void boolean(const char* key, bool x, const char*) { (*stack_.back())[key] = x; }
    void vector(const char* key, const glm::dvec3& x, const char*, const char*) {
        (*stack_.back())[key] = {x.x, x.y, x.z};
    }
    void vector2(const char* key, const glm::dvec2& x, const char*, const char*) {
        (*stack_.back())[key] = {x.x, x.y};
    }
    void seed(const char* key, uint64_t x, const char*) { (*stack_.back())[key] = x; }
    void claim(const char*) {}
    void text(const char* key, const std::string& x, const char*) { (*stack_.back())[key] = x; }
    void real(const char* key, float x, Range, const char*, const char*) {
        (*stack_.back())[key] = x;
    }
    void color(const char* key, const glm::vec3& x, const char*) {
        (*stack_.back())[key] = {x.x, x.y, x.z};
    }
    template <class E, class Names>
    void choice(const char* key, E x, const Names& names, const char*) {
        (*stack_.back())[key] = choice_name(x, names);
    }
    void require(const char*) {}

  private:
    std::vector<ordered_json*> stack_;
};

class Documenter {
  public:
    std::ostringstream out;

    template <class Fn>
    void object(const char* key, const char* doc, Fn&& fn) {
        path_.push_back(key);
        row(here(), "", "", "", std::string("**") + doc + "**");
        fn();
        path_.pop_back();
    }
    void param(const char* key, const Param& p, const char* unit, const char* doc) {
        row(here() + "/" + key,
            "{\"base\": " + format_number(p.base) + ", \"var\": " + format_number(p.var) + "}",
            format_range(p.lo, p.hi), unit, doc);
    }
    void number(const char* key, double x, Range r, const char* unit, const char* doc) {
        row(here() + "/" + key, format_number(x), format_range(r.lo, r.hi), unit, doc);
    }
    void integer(const char* key, int x, Range r, const char* doc) {
        row(here() + "/" + key, std::to_string(x), format_range(r.lo, r.hi), "", doc);
    }
    void boolean(const char* key, bool x, const char* doc) {
        row(here() + "/" + key, x ? "true" : "false", "", "", doc);
    }
    void vector(const char* key, const glm::dvec3& x, const char* unit, const char* doc) {
        row(here() + "/" + key, format_vector(x.x, x.y, x.z), "", unit, doc);
    }
    void seed(const char* key, uint64_t x, const char* doc) {
        row(here() + "/" + key, std::to_string(x), "whole number >= 0", "", doc);
    }
    void claim(const char*) {}
    // A row for a key the caller parses itself.
    void note(const std::string& key, const std::string& def, const char* doc) {
        row(here() + "/" + key, def, "", "", doc);
    }
    void vector2(const char* key, const glm::dvec2& x, const char* unit, const char* doc) {
        row(here() + "/" + key, "[" + format_number(x.x) + ", " + format_number(x.y) + "]", "",
            unit, doc);
    }
    void text(const char* key, const std::string& x, const char* doc) {
        row(here() + "/" + key, json(x).dump(), "", "", doc);
    }
    void real(const char* key, float x, Range r, const char* unit, const char* doc) {
        row(here() + "/" + key, format_number(x), format_range(r.lo, r.hi), unit, doc);
    }
    void color(const char* key, const glm::vec3& x, const char* doc) {
        row(here() + "/" + key, format_vector(x.x, x.y, x.z), "[0, 1]", "sRGB", doc);
    }
    template <class E, class Names>
    void choice(const char* key, E x, const Names& names, const char* doc) {
        row(here() + "/" + key, json(choice_name(x, names)).dump(), choice_list(names), "", doc);
    }
    // The next row is of a required key: "required" stands for its default.
    void require(const char* key) { required_ = here() + "/" + key; }

  private:
    std::vector<std::string> path_;
    std::string required_;
    std::string here() const {
        std::string ptr;
        for (const auto& p : path_) ptr += "/" + p;
        return ptr;
    }
    void row(const std::string& ptr, const std::string& def, const std::string& range,
             const std::string& unit, const std::string& doc) {
        const bool required = ptr == required_;
        if (required) required_.clear();
        out << "| `" << ptr << "` | "
            << (required      ? "required"
                : def.empty() ? ""
                              : "`" + def + "`")
            << " | " << range << " | " << unit << " | " << doc << " |\n";
    }
};

// The key table as data, for a page of controls (the studio): one row per key with its
// pointer, kind, current value, range, unit and documentation, and one row per object (kind
// "group") in table order. The same table writes the reference and --save-preset, so a key
// added there is a control with no other code.
class Cataloguer {
  public:
    ordered_json rows = ordered_json::array();

    template <class Fn>
    void object(const char* key, const char* doc, Fn&& fn) {
        path_.push_back(key);
        rows.push_back({{"pointer", here()}, {"kind", "group"}, {"doc", doc}});
        fn();
        path_.pop_back();
    }
    void param(const char* key, const Param& p, const char* unit, const char* doc) {
        add(key, "param", {{"base", p.base}, {"var", p.var}}, p.lo, p.hi, unit, doc)["whole"] =
            p.whole;
    }
    void number(const char* key, double x, Range r, const char* unit, const char* doc) {
        add(key, "number", x, r.lo, r.hi, unit, doc);
    }
    void integer(const char* key, int x, Range r, const char* doc) {
        add(key, "integer", x, r.lo, r.hi, "", doc);
    }
    void boolean(const char* key, bool x, const char* doc) { add(key, "boolean", x, doc); }
    void vector(const char* key, const glm::dvec3& x, const char* unit, const char* doc) {
        add(key, "vector", {x.x, x.y, x.z}, doc)["unit"] = unit;
    }
    void vector2(const char* key, const glm::dvec2& x, const char* unit, const char* doc) {
        add(key, "vector", {x.x, x.y}, doc)["unit"] = unit;
    }
    void seed(const char* key, uint64_t x, const char* doc) { add(key, "seed", x, doc); }
    void claim(const char*) {}
    void text(const char* key, const std::string& x, const char* doc) { add(key, "text", x, doc); }
    void real(const char* key, float x, Range r, const char* unit, const char* doc) {
        add(key, "number", x, r.lo, r.hi, unit, doc);
    }
    void color(const char* key, const glm::vec3& x, const char* doc) {
        add(key, "color", {x.x, x.y, x.z}, doc);
    }
    template <class E, class Names>
    void choice(const char* key, E x, const Names& names, const char* doc) {
        ordered_json& row = add(key, "choice", choice_name(x, names), doc);
        row["choices"] = ordered_json::array();
        for (const auto& [value, name] : names) row["choices"].push_back(name);
    }
    void require(const char*) {}

  private:
    std::vector<std::string> path_;
    std::string here() const {
        std::string ptr;
        for (const auto& p : path_) ptr += "/" + p;
        return ptr;
    }
    ordered_json& add(const char* key, const char* kind, ordered_json value, const char* doc) {
        rows.push_back({{"pointer", here() + "/" + key},
                        {"kind", kind},
                        {"value", std::move(value)},
                        {"doc", doc}});
        return rows.back();
    }
    ordered_json& add(const char* key, const char* kind, ordered_json value, double lo, double hi,
                      const char* unit, const char* doc) {
        ordered_json& row = add(key, kind, std::move(value), doc);
        // Open ends (+-infinity) have no JSON number: left out.
        if (std::isfinite(lo)) row["lo"] = lo;
        if (std::isfinite(hi)) row["hi"] = hi;
        row["unit"] = unit;
        return row;
    }
};

inline void apply_overrides(json& doc, const std::vector<std::string>& overrides,
                            std::vector<Problem>& problems, std::set<std::string>& overridden);

// The deepest nesting of arrays and objects an input may have. Presets and scenes nest about
// six deep; the limit keeps a hostile file (100,000 levels) from overflowing the stack in the
// recursive code that prints and copies JSON values. Fixed: no real input comes near it.
inline constexpr int kMaxJsonDepth = 64;

// The line where `text` first nests deeper than kMaxJsonDepth, or 0. Brackets in strings and
// comments do not count.
inline size_t too_deep_at(const std::string& text) {
    int depth = 0;
    size_t line = 1;
    const size_t n = text.size();
    for (size_t i = 0; i < n; ++i) {
        const char c = text[i];
        if (c == '\n') {
            ++line;
        } else if (c == '"') {
            for (++i; i < n && text[i] != '"'; ++i) {
                if (text[i] == '\\')
                    ++i;
                else if (text[i] == '\n')
                    ++line;
            }
        } else if (c == '/' && i + 1 < n && text[i + 1] == '/') {
            while (i + 1 < n && text[i + 1] != '\n') ++i;
        } else if (c == '/' && i + 1 < n && text[i + 1] == '*') {
            for (i += 2; i + 1 < n && !(text[i] == '*' && text[i + 1] == '/'); ++i)
                if (text[i] == '\n') ++line;
            ++i;
        } else if (c == '[' || c == '{') {
            if (++depth > kMaxJsonDepth) return line;
        } else if (c == ']' || c == '}') {
            --depth;
        }
    }
    return 0;
}

inline std::string too_deep_message(size_t line) {
    return "line " + std::to_string(line) + ": nested more than " + std::to_string(kMaxJsonDepth) +
           " levels deep (the limit for every input)";
}

// Parses text (comments allowed) into a JSON object and applies "POINTER=VALUE" overrides
// (VALUE parsed as JSON, else taken as a string), recording their pointers in `overridden` and
// their problems in `problems`. Throws InputError on a syntax error or a non-object.
inline json parse_document(const std::string& text, const std::string& source,
                           const std::vector<std::string>& overrides,
                           std::vector<Problem>& problems, std::set<std::string>& overridden) {
    json doc;
    // A key given twice in one object: JSON parsers keep the last, silently; a typo or a
    // pasted block must not pass unnoticed, so each is a problem of its own.
    struct Frame {
        bool array = false;
        size_t index = 0;
        std::string key;
        std::set<std::string> seen;
    };
    std::vector<Frame> frames;
    auto here = [&] {
        std::string ptr;
        for (size_t i = 0; i + 1 < frames.size(); ++i) {
            ptr.push_back('/');
            ptr.append(frames[i].array ? std::to_string(frames[i].index)
                                       : pointer_token(frames[i].key));
        }
        return ptr;
    };
    auto element_done = [&] {
        if (!frames.empty() && frames.back().array) ++frames.back().index;
    };
    json::parser_callback_t check = [&](int, json::parse_event_t event, json& parsed) {
        switch (event) {
            case json::parse_event_t::object_start:
                frames.push_back({false, 0, "", {}});
                break;
            case json::parse_event_t::array_start:
                frames.push_back({true, 0, "", {}});
                break;
            case json::parse_event_t::key: {
                Frame& f = frames.back();
                f.key = parsed.get<std::string>();
                if (!f.seen.insert(f.key).second) {
                    frames.push_back({});  // so here() includes this object's own key
                    problems.push_back({here(), "duplicate key: given twice in one object"});
                    frames.pop_back();
                }
                break;
            }
            case json::parse_event_t::object_end:
            case json::parse_event_t::array_end:
                frames.pop_back();
                element_done();
                break;
            case json::parse_event_t::value:
                element_done();
                break;
        }
        return true;
    };
    if (const size_t line = too_deep_at(text)) throw InputError(source, "", too_deep_message(line));
    // Where the parser is: the pointer of the value it is reading.
    auto at = [&] {
        std::string ptr;
        for (const Frame& f : frames) {
            ptr.push_back('/');
            ptr.append(f.array ? std::to_string(f.index) : pointer_token(f.key));
        }
        return ptr;
    };
    try {
        doc = json::parse(text, check, true, /*ignore_comments=*/true);
    } catch (const json::parse_error& e) {
        std::string what = e.what();
        auto pos = what.find("] ");
        throw InputError(source, "", pos == std::string::npos ? what : what.substr(pos + 2));
    } catch (const json::out_of_range& e) {
        // A number a double cannot hold (1e400): the parser names it, not where it is.
        std::string what = e.what();
        const auto q = what.find('\'');
        const std::string number =
            q == std::string::npos ? "" : what.substr(q + 1, what.rfind('\'') - q - 1);
        throw InputError(
            source, at(),
            "number out of range: " + number + " (a double holds magnitudes up to about 1.8e308)");
    } catch (const json::exception& e) {
        throw InputError(source, at(), e.what());
    }
    if (!doc.is_object())
        throw InputError(source, "", "expected a JSON object, got " + describe(doc));
    apply_overrides(doc, overrides, problems, overridden);
    return doc;
}

// A JSON pointer's tokens, unescaped.
inline std::vector<std::string> pointer_tokens(json::json_pointer p) {
    std::vector<std::string> tokens;
    for (; !p.empty(); p.pop_back()) tokens.push_back(p.back());
    std::reverse(tokens.begin(), tokens.end());
    return tokens;
}

// Why --set may not write at `pointer` in `doc`, or "". Writing there creates what is missing,
// and an array index pads the array with nulls up to it: an index past an array's end (or
// into an array that does not exist yet, other than 0) would allocate without bound.
inline std::string override_path_problem(const json& doc, const json::json_pointer& pointer) {
    const json* cur = &doc;
    std::string path;
    for (const std::string& token : pointer_tokens(pointer)) {
        const bool index =
            !token.empty() && token.find_first_not_of("0123456789") == std::string::npos;
        if (cur && cur->is_array()) {
            if (token == "-") return "";  // appends
            if (!index) return "\"" + token + "\" is not an index of the array " + path;
            const size_t size = cur->size();
            const size_t at = token.size() > 18 ? SIZE_MAX : std::stoull(token);
            if (at > size)
                return "index " + token + " is past the end of " + (path.empty() ? "/" : path) +
                       ", which has " + std::to_string(size) +
                       (size == 1 ? " element" : " elements");
            cur = at < size ? &(*cur)[at] : nullptr;
        } else if (cur && cur->is_object()) {
            const auto it = cur->find(token);
            cur = it == cur->end() ? nullptr : &*it;
        } else if (cur && !cur->is_null()) {
            return (path.empty() ? "/" : path) + " holds a " + cur->type_name() +
                   ", which has no \"" + token + "\"";
        } else {
            // Created by the write: an index makes an array, padded up to it.
            if (index && token != "0")
                return path + " does not exist, so only index 0 can start it";
            cur = nullptr;
        }
        path.push_back('/');
        path.append(pointer_token(token));
    }
    return "";
}

// Whether `s` is well-formed UTF-8 (RFC 3629: no overlongs, surrogates or code points past
// U+10FFFF), as every JSON text must be.
inline bool valid_utf8(const std::string& s) {
    const auto* p = reinterpret_cast<const unsigned char*>(s.data());
    const size_t n = s.size();
    for (size_t i = 0; i < n;) {
        const unsigned char c = p[i];
        size_t len = c < 0x80           ? 1
                     : (c >> 5) == 0x6  ? 2
                     : (c >> 4) == 0xe  ? 3
                     : (c >> 3) == 0x1e ? 4
                                        : 0;
        if (len == 0 || i + len > n) return false;
        uint32_t cp = len == 1 ? c : c & (0x7f >> len);
        for (size_t k = 1; k < len; ++k) {
            if ((p[i + k] & 0xc0) != 0x80) return false;
            cp = (cp << 6) | (p[i + k] & 0x3f);
        }
        static constexpr uint32_t kLeast[] = {0, 0, 0x80, 0x800, 0x10000};
        if (cp < kLeast[len] || cp > 0x10ffff || (cp >= 0xd800 && cp <= 0xdfff)) return false;
        i += len;
    }
    return true;
}

// Applies "POINTER=VALUE" overrides (VALUE parsed as JSON, else taken as a string), recording
// their pointers in `overridden` and their problems in `problems`.
inline void apply_overrides(json& doc, const std::vector<std::string>& overrides,
                            std::vector<Problem>& problems, std::set<std::string>& overridden) {
    for (const auto& o : overrides) {
        auto eq = o.find('=');
        std::string ptr = o.substr(0, eq);
        if (eq == std::string::npos || ptr.empty() || ptr[0] != '/') {
            problems.push_back(
                {"--set " + o, "expected POINTER=VALUE, e.g. /trunk/taper/base=0.9"});
            continue;
        }
        if (!valid_utf8(o)) {
            problems.push_back({"--set", "not valid UTF-8 (a JSON text must be)"});
            continue;
        }
        std::string value = o.substr(eq + 1);
        if (const size_t line = too_deep_at(value)) {
            problems.push_back({ptr, "--set value " + too_deep_message(line)});
            continue;
        }
        json v = json::parse(value, nullptr, false);
        if (v.is_discarded()) v = value;
        try {
            const json::json_pointer pointer(ptr);
            if (std::string why = override_path_problem(doc, pointer); !why.empty()) {
                problems.push_back({ptr, "--set cannot place a value here: " + why});
                continue;
            }
            doc[pointer] = v;
            overridden.insert(ptr);
        } catch (const json::exception&) {
            problems.push_back({ptr, "--set cannot place a value here"});
        }
    }
}

// Appends " (set by --set)" to problems under an overridden pointer.
inline void mark_overrides(std::vector<Problem>& problems,
                           const std::set<std::string>& overridden) {
    for (auto& p : problems)
        for (const auto& o : overridden)
            if (p.pointer.starts_with(o)) p.message += " (set by --set)";
}

}  // namespace pleinair::json_detail
