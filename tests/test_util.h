// Helpers shared by the tests: shipped presets, tree hashes, a binary PLY reader and a way to
// run the pleinair binary.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "generators/tree.h"

namespace pleinair::test {

// Whether this build runs under AddressSanitizer (GCC says so by a macro, clang by a feature):
// tests whose every repetition costs minutes there do less of it.
#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kAddressSanitizer = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
inline constexpr bool kAddressSanitizer = true;
#else
inline constexpr bool kAddressSanitizer = false;
#endif
#else
inline constexpr bool kAddressSanitizer = false;
#endif

std::filesystem::path source_dir();
TreeParams preset(const std::string& name);
std::vector<std::string> shipped_tree_presets();

// FNV-1a over every array of the tree, in a fixed order.
uint64_t hash_tree(const Tree& tree);
uint64_t hash_bytes(const void* data, size_t size, uint64_t h = 1469598103934665603ull);

// A PLY file's vertex element: property names in order, and their values per vertex.
struct Ply {
    std::string format;
    size_t vertex_count = 0;
    size_t face_count = 0;
    std::vector<std::string> vertex_properties;
    std::map<std::string, std::vector<double>> columns;
};
Ply parse_ply(const std::string& bytes);

std::string read_file(const std::filesystem::path& path);

struct RunResult {
    int exit_code = -1;
    std::string out, err;
};
// Runs the pleinair binary with `args` (shell words) from the source directory.
RunResult run_pleinair(const std::string& args);

// Starts the pleinair binary with `args` (no shell), output discarded; returns its PID, or -1.
int spawn_pleinair(const std::vector<std::string>& args);

// The unit cube centred at the origin, corners counter-clockwise seen from outside; vertex i
// has x, y, z = +0.5 where bit 0, 1, 2 of i is set.
QuadMesh unit_cube();

// A fresh empty directory under the system's temporary folder.
std::filesystem::path temp_dir(const std::string& name);

// How two 8-bit images of one size differ: the RMS in levels, and how many values differ.
struct ByteDiff {
    double rms = 0;
    size_t differ = 0;
};
ByteDiff byte_diff(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b);

}  // namespace pleinair::test
