// Height maps in through OpenImageIO: a 16-bit PNG or TIFF, or a float EXR or TIFF, read as a
// terrain's heights (/terrain/height_map). pipeline/output/height_map_writer writes them.
#pragma once

#include <filesystem>
#include <string>

#include "generators/height_map.h"

namespace pleinair {

// Reads `path` (one channel) as heights low + v (high - low), v the sample's value: a 16-bit
// integer's as 0..1 (65535 is 1), a float's as stored (with low 0 and high 1, an EXR's metres
// are kept). Row 0 of the image is the terrain's min z (HeightMap). Throws InputError naming
// `source` and `pointer` for a missing or unreadable file, an 8-bit or other integer type (256
// steps terrace the ground), more than one channel, fewer than 2 or more than 8193 samples a
// side, or a sample that is not finite (with its place).
HeightMap read_height_map(const std::filesystem::path& path, double low, double high,
                          const std::string& source, const std::string& pointer);

}  // namespace pleinair
