// Signed-area accumulation: each edge, walked scanline by scanline, adds to each cell the share
// of that scanline's height it crosses, split between the cells its span covers by the area
// left of it; a running sum along the row is then the winding-weighted coverage. Edges are cut
// at the buffer's left and right sides, so shapes clipped by the patch keep exact coverage.
#include "pipeline/shot/graftal_raster.h"

#include <algorithm>
#include <cmath>

namespace pleinair {

CoverageRaster::CoverageRaster(int width, int height)
    : w_(std::max(width, 0)),
      h_(std::max(height, 0)),
      acc_(static_cast<size_t>(w_ + 2) * static_cast<size_t>(h_), 0.0f) {}

void CoverageRaster::clear() { std::fill(acc_.begin(), acc_.end(), 0.0f); }

void CoverageRaster::polygon(const std::vector<glm::dvec2>& pts) {
    for (size_t i = 0; i < pts.size(); ++i) line(pts[i], pts[(i + 1) % pts.size()]);
}

void CoverageRaster::line(glm::dvec2 p0, glm::dvec2 p1) {
    if (!(std::isfinite(p0.x) && std::isfinite(p0.y) && std::isfinite(p1.x) && std::isfinite(p1.y)))
        return;
    if (p0.y == p1.y) return;  // a horizontal edge sweeps no area
    // An edge crossing x = 0 or x = W is split there, so each piece lies on one side: left of
    // the buffer a piece still counts for every pixel to its right (it becomes a vertical edge
    // at x = 0), right of it for none (a vertical edge in the extra cell).
    const double W = w_;
    for (double X : {0.0, W})
        if ((p0.x < X && p1.x > X) || (p0.x > X && p1.x < X)) {
            const double t = (X - p0.x) / (p1.x - p0.x);
            const glm::dvec2 mid(X, p0.y + t * (p1.y - p0.y));
            line(p0, mid);
            line(mid, p1);
            return;
        }
    p0.x = std::clamp(p0.x, 0.0, W), p1.x = std::clamp(p1.x, 0.0, W);
    double dir = 1;
    if (p0.y > p1.y) std::swap(p0, p1), dir = -1;
    const double dxdy = (p1.x - p0.x) / (p1.y - p0.y);
    if (!std::isfinite(dxdy)) return;  // a sliver too thin to sweep any area
    const size_t stride = static_cast<size_t>(w_) + 2;
    // Rows in [0, h), the bounds taken in double before they become ints.
    const int y_start = static_cast<int>(std::clamp(std::floor(p0.y), 0.0, double(h_)));
    const int y_end = static_cast<int>(std::clamp(std::ceil(p1.y), 0.0, double(h_)));
    for (int y = y_start; y < y_end; ++y) {
        const double ya = std::max<double>(y, p0.y), yb = std::min<double>(y + 1, p1.y);
        const double dy = yb - ya;
        if (!(dy > 0)) continue;
        const double xa = std::clamp(p0.x + (ya - p0.y) * dxdy, 0.0, W);
        const double xb = std::clamp(p0.x + (yb - p0.y) * dxdy, 0.0, W);
        const double d = dy * dir;
        float* row = &acc_[static_cast<size_t>(y) * stride];
        const double x0 = std::min(xa, xb), x1 = std::max(xa, xb);
        const double x0f = std::floor(x0);
        const int x0i = static_cast<int>(x0f);
        const int x1i = static_cast<int>(std::ceil(x1));
        if (x1i <= x0i + 1) {
            // Within one cell: its share right of the edge's mean x goes to the next cell.
            const double xm = 0.5 * (xa + xb) - x0f;
            row[x0i] += static_cast<float>(d * (1 - xm));
            row[x0i + 1] += static_cast<float>(d * xm);
        } else {
            // Across cells: the coverage ramps linearly from x0 to x1.
            const double s = 1.0 / (x1 - x0);
            const double fx0 = x0 - x0f;
            const double a0 = 0.5 * s * (1 - fx0) * (1 - fx0);
            const double fx1 = x1 - std::ceil(x1) + 1;
            const double am = 0.5 * s * fx1 * fx1;
            row[x0i] += static_cast<float>(d * a0);
            if (x1i == x0i + 2) {
                row[x0i + 1] += static_cast<float>(d * (1 - a0 - am));
            } else {
                const double a1 = s * (1.5 - fx0);
                row[x0i + 1] += static_cast<float>(d * (a1 - a0));
                for (int xi = x0i + 2; xi < x1i - 1; ++xi) row[xi] += static_cast<float>(d * s);
                const double a2 = a1 + (x1i - x0i - 3) * s;
                row[x1i - 1] += static_cast<float>(d * (1 - a2 - am));
            }
            row[x1i] += static_cast<float>(d * am);
        }
    }
}

void CoverageRaster::coverage(std::vector<float>& out) const {
    out.resize(static_cast<size_t>(w_) * h_);
    const size_t stride = static_cast<size_t>(w_) + 2;
    for (int y = 0; y < h_; ++y) {
        const float* row = &acc_[static_cast<size_t>(y) * stride];
        float* o = &out[static_cast<size_t>(y) * w_];
        float sum = 0;
        for (int x = 0; x < w_; ++x) {
            sum += row[x];
            o[x] = std::min(1.0f, std::abs(sum));
        }
    }
}

}  // namespace pleinair
