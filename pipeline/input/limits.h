// What pleinair refuses before it starts work (input sizes, counts, image size, a job's memory)
// and how a user raises each: `--limit NAME=VALUE` on any command.
#pragma once

#include <cstdint>
#include <string>

namespace pleinair {

// Defaults are far past any shipped scene and well under what a 16 GB machine holds; each is
// checked before the work it bounds starts, with exit 2 and a line naming the limit.
struct Limits {
    uint64_t input_mb = 64;            // a JSON input file (preset, shader, palette, scene)
    uint64_t particle_file_mb = 4096;  // a particle (PLY) file
    uint64_t particles = 20'000'000;   // vertices in one particle file
    uint64_t trees = 20'000;           // trees in a scene, placed and scattered
    uint64_t members = 10'000;         // trees of a family or a contact sheet
    uint64_t memory_mb = 12288;        // a job's estimated memory; default: 3/4 of this machine's
};

// The process's limits: set once from the command line before any work, read everywhere.
Limits& limits();

// Sets one limit from "name=value" (a whole number > 0); an empty string on success, else why.
std::string set_limit(const std::string& assignment);

// "raise it with --limit NAME=N": the tail of every message about a limit.
std::string how_to_raise(const char* name);

// The names of the limits with their values, for --help and the README.
std::string describe_limits();

}  // namespace pleinair
