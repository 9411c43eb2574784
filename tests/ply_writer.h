// A PLY writer for tests and benchmarks: a vertex element of scalar properties in any of the
// three formats, and particle clouds in the attributes Houdini exports.
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace pleinair::test {

struct PlyColumn {
    std::string type;  // "float", "double", "uchar", "int", ...
    std::string name;
    std::vector<double> values;
};

// The bytes of a PLY file with one vertex element holding `columns` (of equal length);
// `format` is "ascii", "binary_little_endian" or "binary_big_endian". `count` overrides the
// header's count (a header that lies), when >= 0.
inline std::string write_ply(const std::vector<PlyColumn>& columns, const std::string& format,
                             long long count = -1) {
    const size_t n = columns.empty() ? 0 : columns[0].values.size();
    std::string out = "ply\nformat " + format + " 1.0\nelement vertex " +
                      std::to_string(count >= 0 ? static_cast<size_t>(count) : n) + "\n";
    for (const PlyColumn& c : columns) out += "property " + c.type + " " + c.name + "\n";
    out += "end_header\n";
    const bool big = format == "binary_big_endian";
    auto put = [&](const void* p, size_t size) {
        unsigned char b[8];
        std::memcpy(b, p, size);
        if (big != (std::endian::native == std::endian::big))
            for (size_t i = 0; i < size / 2; ++i) std::swap(b[i], b[size - 1 - i]);
        out.append(reinterpret_cast<const char*>(b), size);
    };
    for (size_t i = 0; i < n; ++i) {
        for (size_t k = 0; k < columns.size(); ++k) {
            const PlyColumn& c = columns[k];
            const double v = c.values[i];
            if (format == "ascii") {
                char buf[40];
                std::snprintf(buf, sizeof buf, "%.17g", v);
                out += buf;
                out += k + 1 == columns.size() ? "\n" : " ";
                continue;
            }
            if (c.type == "float") {
                const float f = static_cast<float>(v);
                put(&f, 4);
            } else if (c.type == "double") {
                put(&v, 8);
            } else if (c.type == "uchar") {
                const uint8_t x = static_cast<uint8_t>(v);
                put(&x, 1);
            } else if (c.type == "ushort") {
                const uint16_t x = static_cast<uint16_t>(v);
                put(&x, 2);
            } else {  // int
                const int32_t x = static_cast<int32_t>(v);
                put(&x, 4);
            }
        }
    }
    return out;
}

// A seeded cloud of `n` particles over a rolling field (x in [-30, 30], z in [-40, 5]), with
// Houdini's attributes: pscale, id, nx ny nz and red green blue (uchar).
inline std::vector<PlyColumn> particle_field(size_t n, uint64_t seed = 1) {
    std::vector<PlyColumn> c = {{"float", "x", {}},      {"float", "y", {}},   {"float", "z", {}},
                                {"float", "pscale", {}}, {"int", "id", {}},    {"float", "nx", {}},
                                {"float", "ny", {}},     {"float", "nz", {}},  {"uchar", "red", {}},
                                {"uchar", "green", {}},  {"uchar", "blue", {}}};
    uint64_t s = seed * 0x9e3779b97f4a7c15ull + 1;
    auto next = [&s] {  // splitmix64, as doubles in [0, 1)
        uint64_t z = (s += 0x9e3779b97f4a7c15ull);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        return static_cast<double>((z ^ (z >> 31)) >> 11) / 9007199254740992.0;
    };
    for (size_t i = 0; i < n; ++i) {
        const double x = -30 + 60 * next(), z = -40 + 45 * next();
        const double y = 0.8 * std::sin(0.2 * x) * std::cos(0.15 * z) + 0.3 * next();
        const double v[] = {x,
                            y,
                            z,
                            0.1 + 0.04 * next(),
                            static_cast<double>(i),
                            0,
                            1,
                            0,
                            70 + 40 * next(),
                            90 + 40 * next(),
                            50 + 20 * next()};
        for (size_t k = 0; k < c.size(); ++k) c[k].values.push_back(v[k]);
    }
    return c;
}

}  // namespace pleinair::test
