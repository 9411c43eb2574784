// Height maps out through image_io's one-channel writer.
#include "pipeline/output/height_map_writer.h"

#include <algorithm>
#include <string>
#include <vector>

#include "pipeline/input/error.h"
#include "pipeline/output/image_io.h"

namespace pleinair {

namespace fs = std::filesystem;

void write_height_map(const fs::path& path, const GridSurface& grid, double low, double high) {
    const std::string ext = lower_ext(path);
    const bool exr = ext == ".exr";
    if (!exr && ext != ".png" && ext != ".tif" && ext != ".tiff")
        throw InputError("-o", "", path.string() + ": a height map is .png, .tif or .exr");
    std::vector<float> values(grid.positions.size());
    for (size_t k = 0; k < values.size(); ++k) {
        const double y = grid.positions[k].y;
        values[k] = exr ? static_cast<float>(y)
                        : static_cast<float>(
                              std::clamp(high > low ? (y - low) / (high - low) : 0.0, 0.0, 1.0));
    }
    write_channel_image(path, values, grid.nu, grid.nv);
}

}  // namespace pleinair
