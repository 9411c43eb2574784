// Sobel gradients over a masked region, each edge's direction weighed by its strength: the share
// running near horizontal and how far all of them agree.
#include "pipeline/bench/grain_look.h"

#include <cmath>

#include "shading/portable_math.h"

namespace pleinair {

GrainLook grain_look(const std::vector<float>& l, int w, int h, const std::vector<uint8_t>& mask) {
    GrainLook out;
    if (w < 3 || h < 3 || l.size() != static_cast<size_t>(w) * h || mask.size() != l.size())
        return out;
    // An edge is within the tolerance of horizontal when its gradient is within it of vertical:
    // |gx| <= tan(tolerance) |gy|.
    const double tan_tol = pmath::tan(kGrainTolerance * M_PI / 180.0);
    double total = 0, flat = 0, c2 = 0, s2 = 0;
    auto at = [&](int x, int y) { return static_cast<double>(l[static_cast<size_t>(y) * w + x]); };
    for (int y = 1; y + 1 < h; ++y)
        for (int x = 1; x + 1 < w; ++x) {
            bool inside = true;
            for (int j = -1; j <= 1 && inside; ++j)
                for (int i = -1; i <= 1; ++i)
                    if (!mask[static_cast<size_t>(y + j) * w + x + i]) {
                        inside = false;
                        break;
                    }
            if (!inside) continue;
            ++out.pixels;
            const double gx = (at(x + 1, y - 1) + 2 * at(x + 1, y) + at(x + 1, y + 1)) -
                              (at(x - 1, y - 1) + 2 * at(x - 1, y) + at(x - 1, y + 1));
            // Image rows run down; up is positive here, so angles turn counter-clockwise.
            const double gy = (at(x - 1, y - 1) + 2 * at(x, y - 1) + at(x + 1, y - 1)) -
                              (at(x - 1, y + 1) + 2 * at(x, y + 1) + at(x + 1, y + 1));
            const double g2 = gx * gx + gy * gy;
            if (!(g2 > 0)) continue;
            const double g = std::sqrt(g2);
            total += g;
            if (std::abs(gx) <= tan_tol * std::abs(gy)) flat += g;
            // The edge runs across the gradient: its doubled angle is the gradient's plus 180
            // degrees, so cos and sin of it change sign. cos 2a = (gx^2 - gy^2) / g^2 and
            // sin 2a = 2 gx gy / g^2 for the gradient's angle a; weighed by g.
            c2 -= (gx * gx - gy * gy) / g;
            s2 -= 2 * gx * gy / g;
        }
    if (!(total > 0)) return out;
    out.horizontal = flat / total;
    out.coherence = pmath::hypot(c2, s2) / total;
    out.angle = 0.5 * pmath::atan2(s2, c2) * 180.0 / M_PI;
    return out;
}

}  // namespace pleinair
