// Paint that mixes like paint (issue 13 §3): a colour as a latent pigment mixture after
// Sochorová and Jamriška (2021, "Practical pigment mixing for digital painting"), written from
// the paper: four Kubelka-Munk pigments, a colour encoded as their concentrations plus the RGB
// residual the mixture misses, mixing as linear interpolation of those seven numbers, decoding
// as the Kubelka-Munk mixture's colour plus the residual. A colour over itself is itself, and
// a thin yellow over a blue is green where linear RGB makes it grey.
#pragma once

#include <array>
#include <vector>

#include "shading/color.h"

namespace pleinair {

// Concentrations of the four pigments (summing to 1) and the residual, linear RGB.
struct PigmentLatent {
    std::array<float, 4> c{};
    Color residual{0.0f};
};

// The pigments, sampled at kPigmentBands wavelengths from 400 to 700 nm: each as K/S, the
// ratio of absorption to scattering of its masstone (single-constant Kubelka-Munk), from a
// smooth reflectance curve shaped after the artists' pigment it is named for.
inline constexpr int kPigmentBands = 16;
enum class Pigment { kTitaniumWhite, kHansaYellow, kPhthaloBlue, kQuinacridoneMagenta };

// Linear RGB of a mixture of the pigments (c: concentrations, any non-negative weights; they
// are normalised). The Kubelka-Munk reflectance of the mixture's K/S per band, integrated
// against the CIE 1931 observer (Wyman, Sloan and Shirley's fit) under an equal-energy light,
// white balanced so a perfect white reflector is (1, 1, 1).
Color pigment_mix_rgb(const std::array<float, 4>& c);

// The encoder and decoder. Encoding reads a table over sRGB-encoded colour (kPigmentGrid
// points a side) of the concentrations whose Kubelka-Munk mixture comes nearest each colour,
// found once per process by projected Gauss-Newton steps from the neighbouring point's answer;
// the residual is what the mixture misses. The mixture itself is read from a second table over
// the concentrations (kMixGrid points a side), in encoding and decoding alike, so a colour
// encoded and decoded is itself whatever the tables' resolution.
inline constexpr int kPigmentGrid = 33;
inline constexpr int kMixGrid = 33;
class PigmentTable {
  public:
    PigmentTable();
    // The latent of a linear colour (channels clamped to 0..1).
    PigmentLatent encode(Color linear) const;
    // The colour of a latent: its tabulated mixture plus its residual, clamped to 0..1 (a
    // mixture of valid colours stays valid; the clamp guards rounding).
    Color decode(const PigmentLatent& z) const;
    // The tabulated mixture of concentrations (the first pigment's is the rest of 1).
    Color mixture(const std::array<float, 4>& c) const;
    // Building takes about a second; the one table every caller shares.
    static const PigmentTable& shared();

  private:
    std::vector<float> table_;  // 4 concentrations per colour grid point, red fastest
    std::vector<float> mix_;    // linear RGB per concentration grid point
};

// Mixing by paint: `top` over `bottom` at opacity a, through the latent space.
Color pigment_over(const PigmentTable& t, Color top, Color bottom, float a);

}  // namespace pleinair
