// Bilinear reads of a height map.
#include "generators/height_map.h"

#include <algorithm>

namespace pleinair {

double HeightMap::at(double u, double v) const {
    if (width < 1 || height < 1) return 0.0;
    const double x = std::clamp(u, 0.0, 1.0) * (width - 1),
                 y = std::clamp(v, 0.0, 1.0) * (height - 1);
    const int i = std::min(static_cast<int>(x), std::max(width - 2, 0));
    const int j = std::min(static_cast<int>(y), std::max(height - 2, 0));
    const int i1 = std::min(i + 1, width - 1), j1 = std::min(j + 1, height - 1);
    const double fx = x - i, fy = y - j;
    auto h = [&](int a, int b) { return static_cast<double>(heights[size_t(b) * width + a]); };
    return (1 - fy) * ((1 - fx) * h(i, j) + fx * h(i1, j)) +
           fy * ((1 - fx) * h(i, j1) + fx * h(i1, j1));
}

}  // namespace pleinair
