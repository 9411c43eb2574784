// A height map: heights in world units on a grid of samples spanning a terrain's extent, read
// bilinearly between them (pipeline/input/height_map_io reads one from an image).
#pragma once

#include <vector>

namespace pleinair {

// Sample (i, j) is heights[j * width + i]; column 0 lies at the terrain's min x and the last at
// its max x, row 0 at its min z and the last at its max z (an image seen from above with +x to
// the right and -z up, as Blender's top view shows a glTF scene).
struct HeightMap {
    int width = 0, height = 0;
    std::vector<float> heights;

    // Bilinear at (u, v) in [0, 1]^2 (clamped): u along x, v along z.
    double at(double u, double v) const;
};

}  // namespace pleinair
