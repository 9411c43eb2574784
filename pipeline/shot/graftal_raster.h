// Antialiased coverage of closed polygons by signed-area accumulation (the method of font-rs and
// stb_truetype 2): each edge adds the area it sweeps to the cells it crosses, one prefix sum per
// row turns that into coverage. Written for graftal patches, where Cairo's per-shape setup
// outweighs the shapes themselves (BENCHMARKS.md, "Graftals"); measured against Cairo there.
#pragma once

#include <cstdint>
#include <glm/vec2.hpp>
#include <vector>

namespace pleinair {

// A coverage buffer of width x height pixels. Polygons are added edge by edge; overlapping
// polygons wound the same way add up, and coverage is |sum| clamped to 1 (the nonzero rule for
// shapes that do not overlap with opposite windings; where same-wound shapes overlap at an
// antialiased edge it over-counts by at most that edge's partial coverage).
class CoverageRaster {
  public:
    CoverageRaster(int width, int height);
    void clear();
    // A closed polygon (the last point joins the first), in pixel coordinates of the buffer.
    void polygon(const std::vector<glm::dvec2>& pts);
    void line(glm::dvec2 a, glm::dvec2 b);
    // Coverage in [0, 1] per pixel, row-major; reading it leaves the buffer as it is.
    void coverage(std::vector<float>& out) const;
    int width() const { return w_; }
    int height() const { return h_; }

  private:
    int w_, h_;
    std::vector<float> acc_;  // (w + 2) per row: an edge may add one cell past the last pixel
};

}  // namespace pleinair
