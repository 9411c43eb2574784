// Placement of graftals by a difference image (Kowalski et al.; file 004 of the seeds): a desire
// image says where detail is wanted, an ID image ties each pixel to the object seen there, and
// every graftal placed subtracts a blurred dot (the outer product of a row of Pascal's triangle)
// from the desire around it, until no desire above the threshold is left.
//
// Coherence between frames without any history: graftals are chosen from candidates fixed on
// the surfaces (leaf particles, surface points), each with a stable key, and the candidates are
// tried in the order of a hash of their keys, the same order in every frame. As the view moves
// the desire changes a little, and the same candidates keep winning where it does not change;
// a candidate reads the desire and lays its dot where it stands, between pixels, so a small
// motion changes what it leaves to the next a little, not by a dot jumping a pixel. A frame
// still depends on nothing but itself, so frame N alone is frame N in sequence.
#pragma once

#include <cstdint>
#include <glm/vec2.hpp>
#include <vector>

namespace pleinair {

struct DesireImage {
    int width = 0, height = 0;
    std::vector<float> desire;  // width * height, row-major; >= 0
    std::vector<uint32_t> id;   // the object seen at each pixel; empty: every pixel matches
};

// The blurred dot of Pascal's triangle row `row` (row + 1 pixels across): the outer product of
// the binomial coefficients, scaled so that its centre is 1. Row 0 is a single pixel.
std::vector<float> pascal_dot(int row);

struct DifferencePlacement {
    int dot_row = 6;         // the dot is dot_row + 1 pixels across
    float threshold = 0.5f;  // a graftal needs at least this desire where it stands
    float strength = 1.0f;   // each graftal subtracts strength x the dot
    size_t max_count = 1000000;
    // Soft placement: a candidate's weight eases from 0 at the threshold to 1 at threshold +
    // band (smoothstep), and it lays its dot times its weight, so every weight is a continuous
    // function of the candidates' positions and desires: a moving view fades tufts in and out
    // instead of popping them. 0: hard (weight 1 wherever the threshold is reached).
    float band = 0;
};

// A place a graftal may stand: its pixel, the object it belongs to, and a key that names it from
// frame to frame (a leaf's label, a surface point's index).
struct GraftalCandidate {
    glm::vec2 pixel{0.0f};
    uint32_t object = 0;
    uint64_t key = 0;
    // The desire at the candidate itself (the surface's, where it stands), less the dots placed
    // before it; negative: read the desire image there instead.
    float desire = -1;
};

// The candidates that get a graftal, as indices into `candidates`, in the order they were
// placed; `image`'s desire is left with their dots subtracted. A candidate is taken when it lies
// inside the image, on its own object, where the remaining desire reaches the threshold: the
// image's, bilinear at its position, or its own desire less the dots placed before it.
// `weights`, when given, receives each placed candidate's weight (1 unless params.band > 0).
std::vector<uint32_t> place_candidates(DesireImage& image,
                                       const std::vector<GraftalCandidate>& candidates,
                                       const DifferencePlacement& params,
                                       std::vector<float>* weights = nullptr);

// Without candidates: graftals at pixels, the most desired first (ties by position), until
// nothing above the threshold is left. Returns the pixels in the order they were placed.
std::vector<glm::ivec2> fill_by_difference(DesireImage& image, const DifferencePlacement& params);

}  // namespace pleinair
