// Binary masks of a painted frame's pixels and the few operations the look's measures share:
// closing, erosion, 8-connected regions, an outline with what it encloses, and a boundary's
// length.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace pleinair {

// Row-major, one byte a pixel, nonzero inside.
using Mask = std::vector<uint8_t>;

// The mask closed (dilated, then eroded) by a square of side 2r + 1, padded by r so the frame's
// edge does not cut the closing short (OpenImageIO's dilate and erode).
Mask closed(const Mask& m, int w, int h, int r);

// The mask eroded by a square of side 2r + 1; the frame's edge erodes nothing (a shape the frame
// cuts keeps its cut side).
Mask eroded(const Mask& m, int w, int h, int r);

// Visits the 8-connected region of pixels equal to `value` (zero or not) from `start`, marking
// `seen`; returns its size.
size_t flood(const Mask& m, int w, int h, size_t start, uint8_t value, std::vector<bool>& seen);

// The outline of a shape: the mask closed by `r` and every gap it then encloses (not reached
// from the frame's edge) filled.
Mask outline(const Mask& m, int w, int h, int r);

// The length of the mask's boundary in pixel edges: the sides between a pixel inside and one
// outside (not the frame's edge, where the frame cuts the shape). A disc of radius R measures about
// 8R (a square grid's edges along a curve), so length / sqrt(area) is about 4.5 for a disc and
// grows as the edge breaks.
size_t boundary_length(const Mask& m, int w, int h);

}  // namespace pleinair
