// The process's limits and their command-line form.
#include "pipeline/input/limits.h"

#include <unistd.h>

#include <charconv>
#include <utility>

namespace pleinair {

namespace {

struct Entry {
    const char* name;
    uint64_t Limits::*field;
    const char* what;
};

constexpr Entry kEntries[] = {
    {"input_mb", &Limits::input_mb, "megabytes in a JSON input file"},
    {"particle_file_mb", &Limits::particle_file_mb, "megabytes in a particle file"},
    {"particles", &Limits::particles, "vertices in a particle file"},
    {"trees", &Limits::trees, "trees in a scene"},
    {"members", &Limits::members, "trees of a family or a contact sheet"},
    {"memory_mb", &Limits::memory_mb, "megabytes a job is estimated to need"},
};

}  // namespace

Limits& limits() {
    static Limits l = [] {
        Limits d;
        // Three quarters of this machine's memory, leaving the rest to the system.
        const long pages = sysconf(_SC_PHYS_PAGES), size = sysconf(_SC_PAGE_SIZE);
        if (pages > 0 && size > 0)
            d.memory_mb = static_cast<uint64_t>(pages) * static_cast<uint64_t>(size) / 4 * 3 >> 20;
        return d;
    }();
    return l;
}

std::string set_limit(const std::string& assignment) {
    const size_t eq = assignment.find('=');
    std::string names;
    for (const Entry& e : kEntries) names += (names.empty() ? "" : ", ") + std::string(e.name);
    if (eq == std::string::npos)
        return "expected NAME=VALUE with NAME one of " + names + ", got \"" + assignment + "\"";
    const std::string name = assignment.substr(0, eq), value = assignment.substr(eq + 1);
    for (const Entry& e : kEntries) {
        if (name != e.name) continue;
        uint64_t v = 0;
        const char* end = value.data() + value.size();
        auto [p, ec] = std::from_chars(value.data(), end, v);
        if (ec != std::errc() || p != end || v == 0)
            return "--limit " + name + " expects a whole number > 0, got \"" + value + "\"";
        limits().*e.field = v;
        return "";
    }
    return "no limit \"" + name + "\" (have: " + names + ")";
}

std::string how_to_raise(const char* name) {
    return "raise it with --limit " + std::string(name) + "=N";
}

std::string describe_limits() {
    std::string out;
    for (const Entry& e : kEntries)
        out +=
            std::string(e.name) + "=" + std::to_string(limits().*e.field) + " (" + e.what + ")\n";
    return out;
}

}  // namespace pleinair
