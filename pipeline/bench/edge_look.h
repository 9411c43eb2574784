// Whether a picture's touches read as paint or as blurred dabs (issue 52 §2 and §7): the share of
// its marked edges that are soft, measured across each edge as a painter's eye runs over it.
#pragma once

#include <cstdint>
#include <vector>

namespace pleinair {

// The edges of a region and how many are blurred. An edge is a pixel where L* changes fastest
// along its own gradient (the gradient's local maximum across the edge); from it the profile is
// followed both ways while L* keeps rising or falling (at most kEdgeReach px each way), and the
// edge counts when it spans at least kEdgeMinContrast L* (a touch against its neighbour, not a
// bristle's ripple). Its width is the distance between the profile's 10% and 90% points: an
// anti-aliased crisp edge is 1-2 px wide, a Gaussian blur of sigma s about 2.56 s. An edge wider
// than kBlurredWidth px is blurred.
struct EdgeLook {
    double blurred_share = 0;  // blurred edges over all counted; 0 when none
    double median_width = 0;   // px
    uint64_t edges = 0;        // edge pixels counted
};
inline constexpr int kEdgeReach = 16;
inline constexpr double kEdgeMinContrast = 12.0;
inline constexpr double kBlurredWidth = 3.5;
EdgeLook edge_look(const std::vector<float>& lightness, int width, int height,
                   const std::vector<uint8_t>& mask);

}  // namespace pleinair
