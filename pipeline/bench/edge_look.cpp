// Edges found where the gradient peaks across them and measured by walking their profile:
// a width in pixels, which is what a viewer judges as crisp or soft, independent of contrast.
#include "pipeline/bench/edge_look.h"

#include <algorithm>
#include <cmath>

#include "shading/portable_math.h"

namespace pleinair {

namespace {

// L* at (x, y), bilinear, clamped at the frame's edges.
float sample(const std::vector<float>& l, int w, int h, double x, double y) {
    x = std::clamp(x, 0.0, w - 1.0), y = std::clamp(y, 0.0, h - 1.0);
    const int x0 = std::min(static_cast<int>(x), w - 2 < 0 ? 0 : w - 2);
    const int y0 = std::min(static_cast<int>(y), h - 2 < 0 ? 0 : h - 2);
    const int x1 = std::min(x0 + 1, w - 1), y1 = std::min(y0 + 1, h - 1);
    const double fx = x - x0, fy = y - y0;
    auto at = [&](int i, int j) { return static_cast<double>(l[static_cast<size_t>(j) * w + i]); };
    return static_cast<float>((at(x0, y0) * (1 - fx) + at(x1, y0) * fx) * (1 - fy) +
                              (at(x0, y1) * (1 - fx) + at(x1, y1) * fx) * fy);
}

// The 10%-90% width of the profile through (x, y) along the unit direction (dx, dy), in which
// L* rises; 0 when the edge spans less than kEdgeMinContrast.
double edge_width(const std::vector<float>& l, int w, int h, int x, int y, double dx, double dy) {
    // Walk down (backwards) and up (forwards) while L* keeps going the same way.
    std::vector<double> profile;
    double prev = sample(l, w, h, x, y);
    int back = 0;
    for (int k = 1; k <= kEdgeReach; ++k) {
        const double v = sample(l, w, h, x - k * dx, y - k * dy);
        if (v > prev - 0.05) break;
        prev = v, back = k;
    }
    prev = sample(l, w, h, x, y);
    int ahead = 0;
    for (int k = 1; k <= kEdgeReach; ++k) {
        const double v = sample(l, w, h, x + k * dx, y + k * dy);
        if (v < prev + 0.05) break;
        prev = v, ahead = k;
    }
    for (int k = -back; k <= ahead; ++k) profile.push_back(sample(l, w, h, x + k * dx, y + k * dy));
    const double lo = profile.front(), hi = profile.back();
    if (hi - lo < kEdgeMinContrast) return 0;
    // Where the profile first crosses a level, interpolated between samples.
    auto cross = [&](double level) {
        for (size_t i = 1; i < profile.size(); ++i)
            if (profile[i] >= level) {
                const double span = profile[i] - profile[i - 1];
                return static_cast<double>(i - 1) +
                       (span > 0 ? (level - profile[i - 1]) / span : 0);
            }
        return static_cast<double>(profile.size() - 1);
    };
    return std::max(cross(lo + 0.9 * (hi - lo)) - cross(lo + 0.1 * (hi - lo)), 1e-3);
}

}  // namespace

EdgeLook edge_look(const std::vector<float>& l, int w, int h, const std::vector<uint8_t>& mask) {
    EdgeLook out;
    if (w < 3 || h < 3) return out;
    auto at = [&](int x, int y) { return static_cast<double>(l[static_cast<size_t>(y) * w + x]); };
    std::vector<double> widths;
    uint64_t blurred = 0;
    for (int y = 1; y + 1 < h; ++y)
        for (int x = 1; x + 1 < w; ++x) {
            if (!mask[static_cast<size_t>(y) * w + x]) continue;
            const double gx = 0.5 * (at(x + 1, y) - at(x - 1, y));
            const double gy = 0.5 * (at(x, y + 1) - at(x, y - 1));
            const double g = pmath::hypot(gx, gy);
            if (!(g > 0.5)) continue;
            const double dx = gx / g, dy = gy / g;
            // The gradient's peak across the edge: no larger one a pixel either way along it.
            auto grad = [&](double px, double py) {
                const double ax = 0.5 * (sample(l, w, h, px + 1, py) - sample(l, w, h, px - 1, py));
                const double ay = 0.5 * (sample(l, w, h, px, py + 1) - sample(l, w, h, px, py - 1));
                return pmath::hypot(ax, ay);
            };
            if (grad(x + dx, y + dy) > g || grad(x - dx, y - dy) >= g) continue;
            const double wd = edge_width(l, w, h, x, y, dx, dy);
            if (!(wd > 0)) continue;
            widths.push_back(wd);
            if (wd > kBlurredWidth) ++blurred;
        }
    out.edges = widths.size();
    if (widths.empty()) return out;
    out.blurred_share = static_cast<double>(blurred) / static_cast<double>(widths.size());
    std::nth_element(widths.begin(),
                     widths.begin() + static_cast<std::ptrdiff_t>(widths.size() / 2), widths.end());
    out.median_width = widths[widths.size() / 2];
    return out;
}

}  // namespace pleinair
