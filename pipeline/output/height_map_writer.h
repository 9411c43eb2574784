// A terrain written as a height map (the other way from pipeline/input/height_map_io): what a
// survey tool or a sculpting program reads, and what /terrain/height_map reads back.
#pragma once

#include <filesystem>

#include "generators/terrain.h"

namespace pleinair {

// The grid's heights (its y) as a one-channel image: 16-bit in PNG and TIFF, the heights
// mapped from [low, high] to 0..65535 (clamped); float metres in EXR (low and high unused).
// Row 0 is the grid's first row (min z). Written whole or not at all (write_file_atomic).
void write_height_map(const std::filesystem::path& path, const GridSurface& grid, double low,
                      double high);

}  // namespace pleinair
