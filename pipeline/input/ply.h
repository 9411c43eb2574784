// A strict reader of the vertex element of PLY files (ASCII, binary little or big endian; any
// scalar type), as Blender, Houdini and MeshLab write them, for particle clouds.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace pleinair {

// The vertices of a PLY file, column by column: every scalar property as double (64-bit
// integers beyond 2^53 would round; no PLY type holds them). Lists on vertices are skipped.
struct PlyVertices {
    struct Column {
        std::string name;
        std::string type;  // as the header spells it ("float", "uchar", "float64", ...)
        bool integer = false;
        std::vector<double> values;
    };
    size_t count = 0;
    std::vector<Column> columns;

    // The column named `name`, or null.
    const Column* find(std::string_view name) const;
};

// A file past this many vertices is refused before anything is allocated (raise it with
// --limit particles=N; pipeline/input/limits.h).
// Throws InputError naming `source` and what is wrong: the header line, or the vertex (from 0)
// and property where the data ends, lies or holds a value that is not finite. Nothing is
// trusted: counts are checked against the bytes there are before any allocation.
PlyVertices read_ply_vertices(std::string_view bytes, const std::string& source);

}  // namespace pleinair
