// What a change request from the studio's page asks for, parsed and checked before the
// workspace sees it: pointers to set (values as --set's text) and pointers to unset, naming no
// file outside the folders the studio may read. Pure, for the server and the fuzz target.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace pleinair {

struct StudioChange {
    std::vector<std::pair<std::string, std::string>> set;  // pointer, --set VALUE text
    std::vector<std::string> unset;
};

// A request the studio refuses (400): one line, and the pointer it concerns when there is one.
struct RequestRefused : std::runtime_error {
    RequestRefused(const std::string& message, std::string pointer_)
        : std::runtime_error(message), pointer(std::move(pointer_)) {}
    std::string pointer;
};

// Parses {"set": {POINTER: VALUE, ...}, "unset": [POINTER, ...]}. A string value that names a
// file (holding a "/" or "\", or ending in .json or .ply) must lie in one of `readable`
// (relative names are read from `scene_dir`, as scenes read them). Throws RequestRefused.
StudioChange parse_studio_change(const std::string& body,
                                 const std::vector<std::filesystem::path>& readable,
                                 const std::filesystem::path& scene_dir);

}  // namespace pleinair
