// A grown tree's leaves as the level of detail reads them every frame, in what no frame changes:
// each leaf's lightness with and without the interior darkening and its place about the
// crown's centre in direction bins, computed once per member instead of per tree and frame.
#pragma once

#include <glm/vec3.hpp>
#include <vector>

#include "generators/tree.h"
#include "shading/stroke_shader.h"

namespace pleinair {

// The survivors' spread (lod.h) works per bin of directions from the crown's centre.
constexpr int kElevationBins = 6, kAzimuthBins = 12;

// A direction v (of length r > 0) as continuous bin coordinates: elevation and azimuth, each in
// bin units.
void direction_bins(const glm::vec3& v, float r, float& e, float& a);

struct LeafBasis {
    // stroke_lightness at N.L 1/2 with the interior darkening whole (lod_distance 0) and gone
    // (1): the two ends the level of detail weighs to keep a crown's mean lightness.
    std::vector<float> light0, light1;
    // Distance from the tree's centre locator (0: at it, no direction) and direction bins.
    std::vector<float> r, e, a;
    size_t size() const { return r.size(); }
};

// The leaves of `tree` painted with `leaf_shader`.
LeafBasis leaf_basis(const Tree& tree, const StrokeShaderParams& leaf_shader);

}  // namespace pleinair
