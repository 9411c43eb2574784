// How much of a graftal to draw (Markosian et al. 2000, §2.2.3 and §2.3): σ from its size on
// screen, ρ from its orientation to the view, τ from its transition, λ from the three by the
// description's rule; and for tufts, the level chosen from λ, filtered over recent frames,
// switched with hysteresis, with levels growing in and fading out over time. The filter and the
// hysteresis depend on earlier frames, so a shot's tuft states are replayed from its first
// frame: frame N painted alone equals frame N painted in sequence (DESIGN.md).
#pragma once

#include <functional>
#include <glm/vec3.hpp>
#include <vector>

#include "pipeline/input/graftal_desc.h"

namespace pleinair {

// σ = W / D: W the graftal's world length, D the world diameter of a sphere that measures
// `preferred_px` pixels on screen at the graftal's distance from the eye, for a pinhole camera
// of focal length `focal_px` (pixels). 0 for a graftal at or behind the eye; never NaN.
float graftal_sigma(double world_length, double preferred_px, double distance, double focal_px);

// ρ by the description's rule, for unit normal n and unit view vector v (towards the eye);
// in [0, 1] even for vectors a little off unit length.
float graftal_rho(GraftalRho rule, const glm::vec3& n, const glm::vec3& v);

// λ by the description's rule; in [0, ∞), never NaN.
float graftal_lambda(GraftalLambda rule, float sigma, float rho, float tau);

// A primitive attribute's multiplier at λ (the ramp's start below it, its end above).
float lod_ramp(const LodRamp& ramp, float lambda);

// The local frame of a graftal: y along the normal, x by the rule, z = x cross y. Falls back
// to a fixed perpendicular where the rule's cross product vanishes (the eye straight above a
// graftal, a vertical normal for kUpright), so the axes are always unit and orthogonal.
struct GraftalAxes {
    glm::vec3 x, y, z;
};
GraftalAxes graftal_axes(GraftalFrame rule, const glm::vec3& n, const glm::vec3& v,
                         const glm::vec3& tangent);

// The highest level i whose λ_i <= λ (level 0 when λ is below them all).
int tuft_level(const std::vector<TuftLevel>& levels, float lambda);

// A tuft's state after a frame: the current level and each level's τ (1: fully in, 0: gone).
struct TuftState {
    int level = 0;            // i_c, after filtering and hysteresis
    float average = 0;        // u, the mean of the recent choices
    std::vector<float> tau;   // per level
    std::vector<int> recent;  // the last `queue` choices, oldest first
    bool started = false;
};

// Advances a tuft by one frame of `dt` seconds in which λ chose level `chosen`. The first frame
// starts with its levels fully in (a shot opens on a settled picture).
void step_tuft(TuftState& s, const TuftRules& rules, int chosen, double dt);

// The tuft's state at frame `frame` (0-based) of a shot at `fps`, replayed from frame 0 with
// λ at each frame given by `lambda_at`. Pure: the same arguments give the same state.
TuftState replay_tuft(const TuftRules& rules, const std::function<float(int)>& lambda_at, int frame,
                      double fps);

}  // namespace pleinair
