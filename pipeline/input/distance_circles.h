// Distance circles (thesis IV.6): distances along the camera's view axis, carried by the camera,
// that say what is foreground (full detail) and what is background (least detail).
#pragma once

#include <string>
#include <vector>

#include "pipeline/input/error.h"

namespace pleinair {

// World distances from the plane through the camera perpendicular to its view. A pair is set
// when its far circle is (> 0); its near circle may then be 0 (full detail only at the camera).
struct DistanceCircles {
    double leaf_near = 0, leaf_far = 0;    // leaves and surface detail strokes
    double trunk_near = 0, trunk_far = 0;  // bark strokes: the low-detail model takes over
    // The innermost circle: nearer than this, foliage opens into separate strokes (V.3); 0: off.
    double near_field = 0;

    bool leaves() const { return leaf_far > 0; }
    bool trunks() const { return trunk_far > 0; }
    bool any() const { return leaves() || trunks() || near_field > 0; }
};

// The distance value of a depth: 0 at or inside the near circle, 1 at or beyond the far one,
// linear between. Swapped circles are taken in order; equal ones step at their distance (1 from
// there on). Not finite depths count as far.
float circle_value(double depth, double near, double far);

// How far into the near field a depth is: 0 at or beyond the near-field circle, 1 at the camera
// (or behind it), linear between; 0 when near_field is 0.
float near_field_value(double depth, double near_field);

// Non-negative finite distances, near <= far, a near circle without its far one. Pointers are
// `pointer` + "/leaf_near" and so on.
std::vector<Problem> validate_circles(const DistanceCircles& c, const std::string& pointer);

}  // namespace pleinair
