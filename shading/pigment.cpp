// The pigments' spectra, the Kubelka-Munk mixture, and the encoder's table.
#include "shading/pigment.h"

#include <algorithm>
#include <cmath>

#include "shading/portable_math.h"

namespace pleinair {

namespace {

constexpr int kBands = kPigmentBands;

double wavelength(int band) { return 400.0 + 300.0 * band / (kBands - 1); }

// Wyman, Sloan and Shirley (2013): the CIE 1931 2-degree observer as piecewise Gaussians.
double lobe(double l, double mu, double s1, double s2) {
    const double t = (l - mu) / (l < mu ? s1 : s2);
    return pmath::exp(-0.5 * t * t);
}
double cie_x(double l) {
    return 1.056 * lobe(l, 599.8, 37.9, 31.0) + 0.362 * lobe(l, 442.0, 16.0, 26.7) -
           0.065 * lobe(l, 501.1, 20.4, 26.2);
}
double cie_y(double l) {
    return 0.821 * lobe(l, 568.8, 46.9, 40.5) + 0.286 * lobe(l, 530.9, 16.3, 31.1);
}
double cie_z(double l) {
    return 1.217 * lobe(l, 437.0, 11.8, 36.0) + 0.681 * lobe(l, 459.0, 26.0, 13.8);
}

double sigmoid(double x) { return 1.0 / (1.0 + pmath::exp(-x)); }

// A pigment's masstone reflectance at wavelength l (nm): smooth curves after the pigments'
// published reflectance, enough for their mixtures to go where paint goes.
double masstone(Pigment p, double l) {
    switch (p) {
        case Pigment::kTitaniumWhite:  // flat and high, a little warm
            return 0.90 + 0.03 * sigmoid((l - 450.0) / 20.0);
        case Pigment::kHansaYellow:  // absorbs blue, reflects from the green on
            return 0.04 + 0.86 * sigmoid((l - 505.0) / 13.0);
        case Pigment::kPhthaloBlue:  // reflects blue with a long tail into the green
            return 0.03 + 0.6 * lobe(l, 470.0, 35.0, 60.0) + 0.04 * sigmoid((l - 680.0) / 10.0);
        case Pigment::kQuinacridoneMagenta:  // absorbs the green, reflects red and some violet
            return 0.04 + 0.8 * sigmoid((l - 600.0) / 15.0) + 0.3 * lobe(l, 415.0, 20.0, 30.0);
    }
    return 0.5;
}

// Everything the mixture needs, tabulated once.
struct Spectra {
    double ks[4][kBands];   // K/S of each pigment's masstone
    double cmf[3][kBands];  // the observer, weighted for the band
    double to_rgb[3][3];    // XYZ to linear sRGB, white balanced to E
    Spectra() {
        for (int p = 0; p < 4; ++p)
            for (int b = 0; b < kBands; ++b) {
                const double r = masstone(static_cast<Pigment>(p), wavelength(b));
                ks[p][b] = (1.0 - r) * (1.0 - r) / (2.0 * r);
            }
        for (int b = 0; b < kBands; ++b) {
            const double l = wavelength(b);
            cmf[0][b] = cie_x(l), cmf[1][b] = cie_y(l), cmf[2][b] = cie_z(l);
        }
        static constexpr double m[3][3] = {{3.2404542, -1.5371385, -0.4985314},
                                           {-0.9692660, 1.8760108, 0.0415560},
                                           {0.0556434, -0.2040259, 1.0572252}};
        // A perfect reflector's XYZ maps to (1, 1, 1): each row scaled by its white's response.
        double w[3] = {0, 0, 0};
        for (int k = 0; k < 3; ++k)
            for (int b = 0; b < kBands; ++b) w[k] += cmf[k][b];
        for (int i = 0; i < 3; ++i) {
            double white = 0;
            for (int k = 0; k < 3; ++k) white += m[i][k] * w[k];
            for (int k = 0; k < 3; ++k) to_rgb[i][k] = m[i][k] / white;
        }
    }
};

const Spectra& spectra() {
    static const Spectra s;
    return s;
}

// The mixture's linear RGB, unclamped, in double.
void mix_rgb(const double c[4], double out[3]) {
    const Spectra& s = spectra();
    double sum = c[0] + c[1] + c[2] + c[3];
    if (!(sum > 1e-12)) sum = 1;  // no pigment at all: the bare white ground
    double xyz[3] = {0, 0, 0};
    for (int b = 0; b < kBands; ++b) {
        double ks = 0;
        for (int p = 0; p < 4; ++p) ks += std::max(c[p], 0.0) / sum * s.ks[p][b];
        const double r = 1.0 + ks - std::sqrt(ks * ks + 2.0 * ks);
        for (int k = 0; k < 3; ++k) xyz[k] += r * s.cmf[k][b];
    }
    for (int i = 0; i < 3; ++i)
        out[i] = s.to_rgb[i][0] * xyz[0] + s.to_rgb[i][1] * xyz[1] + s.to_rgb[i][2] * xyz[2];
}

// The error of concentrations c against a target, in sRGB-encoded units (perceptual enough for
// the search), and its Jacobian by central differences.
void residual_of(const double c[4], const double target[3], double e[3]) {
    double rgb[3];
    mix_rgb(c, rgb);
    for (int k = 0; k < 3; ++k)
        e[k] = linear_to_srgb(static_cast<float>(std::clamp(rgb[k], 0.0, 1.0))) - target[k] +
               (rgb[k] - std::clamp(rgb[k], 0.0, 1.0));
}

// Onto the simplex: each concentration >= 0, their sum 1 (Duchi et al.'s sort-based projection).
void project_simplex(double c[4]) {
    double u[4] = {c[0], c[1], c[2], c[3]};
    std::sort(u, u + 4, [](double a, double b) { return a > b; });
    double cum = 0, theta = 0;
    for (int i = 0; i < 4; ++i) {
        cum += u[i];
        const double t = (cum - 1.0) / (i + 1);
        if (u[i] - t > 0) theta = t;
    }
    for (int i = 0; i < 4; ++i) c[i] = std::max(c[i] - theta, 0.0);
}

// Concentrations nearest the sRGB-encoded target, from a start: damped Gauss-Newton steps
// projected onto the simplex.
void solve(const double target[3], double c[4]) {
    for (int it = 0; it < 8; ++it) {
        double e[3], J[3][4];
        residual_of(c, target, e);
        for (int p = 0; p < 4; ++p) {
            double a[4] = {c[0], c[1], c[2], c[3]}, b[4] = {c[0], c[1], c[2], c[3]};
            a[p] += 1e-4, b[p] -= 1e-4;
            double ea[3], eb[3];
            residual_of(a, target, ea);
            residual_of(b, target, eb);
            for (int k = 0; k < 3; ++k) J[k][p] = (ea[k] - eb[k]) / 2e-4;
        }
        // (J^T J + lambda I) d = -J^T e
        double A[4][5];
        for (int i = 0; i < 4; ++i) {
            for (int j = 0; j < 4; ++j) {
                double v = 0;
                for (int k = 0; k < 3; ++k) v += J[k][i] * J[k][j];
                A[i][j] = v + (i == j ? 1e-3 : 0.0);
            }
            double g = 0;
            for (int k = 0; k < 3; ++k) g += J[k][i] * e[k];
            A[i][4] = -g;
        }
        for (int i = 0; i < 4; ++i) {  // Gaussian elimination; the system is positive definite
            for (int r = i + 1; r < 4; ++r) {
                const double f = A[r][i] / A[i][i];
                for (int k = i; k < 5; ++k) A[r][k] -= f * A[i][k];
            }
        }
        double d[4];
        for (int i = 3; i >= 0; --i) {
            double v = A[i][4];
            for (int k = i + 1; k < 4; ++k) v -= A[i][k] * d[k];
            d[i] = v / A[i][i];
        }
        for (int p = 0; p < 4; ++p) c[p] += d[p];
        project_simplex(c);
    }
}

}  // namespace

Color pigment_mix_rgb(const std::array<float, 4>& c) {
    const double cd[4] = {c[0], c[1], c[2], c[3]};
    double rgb[3];
    mix_rgb(cd, rgb);
    return {static_cast<float>(rgb[0]), static_cast<float>(rgb[1]), static_cast<float>(rgb[2])};
}

PigmentTable::PigmentTable() {
    constexpr int n = kPigmentGrid;
    table_.assign(static_cast<size_t>(n) * n * n * 4, 0.0f);
    // Rows in a serpentine order so each point starts from its neighbour's answer: the table is
    // smooth where the answer is, and the same on every run.
    double c[4] = {0.25, 0.25, 0.25, 0.25};
    for (int b = 0; b < n; ++b)
        for (int gi = 0; gi < n; ++gi) {
            const int g = b % 2 ? n - 1 - gi : gi;
            for (int ri = 0; ri < n; ++ri) {
                const int r = (b * n + gi) % 2 ? n - 1 - ri : ri;
                // Grid points are evenly spaced in the square root of linear colour (near sRGB's
                // curve, and one sqrt a channel to find); the search measures in sRGB.
                auto enc = [&](int i) {
                    const double v = double(i) / (n - 1);
                    return double(linear_to_srgb(static_cast<float>(v * v)));
                };
                const double target[3] = {enc(r), enc(g), enc(b)};
                solve(target, c);
                float* o = &table_[((static_cast<size_t>(b) * n + g) * n + r) * 4];
                for (int p = 0; p < 4; ++p) o[p] = static_cast<float>(c[p]);
            }
        }
    // The mixture over the concentrations of the last three pigments (the first makes up the
    // rest; points past the simplex are scaled back onto it).
    mix_.assign(static_cast<size_t>(kMixGrid) * kMixGrid * kMixGrid * 3, 0.0f);
    for (int k3 = 0; k3 < kMixGrid; ++k3)
        for (int k2 = 0; k2 < kMixGrid; ++k2)
            for (int k1 = 0; k1 < kMixGrid; ++k1) {
                double cc[4] = {0, double(k1) / (kMixGrid - 1), double(k2) / (kMixGrid - 1),
                                double(k3) / (kMixGrid - 1)};
                const double rest = 1.0 - cc[1] - cc[2] - cc[3];
                cc[0] = std::max(rest, 0.0);
                double rgb[3];
                mix_rgb(cc, rgb);
                float* o = &mix_[((static_cast<size_t>(k3) * kMixGrid + k2) * kMixGrid + k1) * 3];
                for (int k = 0; k < 3; ++k) o[k] = static_cast<float>(rgb[k]);
            }
}

const PigmentTable& PigmentTable::shared() {
    static const PigmentTable t;
    return t;
}

namespace {
// W floats per point of a cube table n points a side (the first axis fastest), read
// trilinearly at u (each in 0..1 over the table).
template <int W>
void trilinear(const std::vector<float>& table, int n, const float u[3], float out[W]) {
    float f[3];
    int i0[3];
    for (int k = 0; k < 3; ++k) {
        const float x = clamp01(u[k]) * static_cast<float>(n - 1);
        i0[k] = std::min(static_cast<int>(x), n - 2);
        f[k] = x - static_cast<float>(i0[k]);
    }
    for (int j = 0; j < W; ++j) out[j] = 0;
    for (int corner = 0; corner < 8; ++corner) {
        float w = 1;
        int idx[3];
        for (int k = 0; k < 3; ++k) {
            const int bit = (corner >> k) & 1;
            idx[k] = i0[k] + bit;
            w *= bit ? f[k] : 1.0f - f[k];
        }
        const float* e = &table[((static_cast<size_t>(idx[2]) * n + idx[1]) * n + idx[0]) * W];
        for (int j = 0; j < W; ++j) out[j] += w * e[j];
    }
}
}  // namespace

PigmentLatent PigmentTable::encode(Color lin) const {
    const float u[3] = {std::sqrt(clamp01(lin.x)), std::sqrt(clamp01(lin.y)),
                        std::sqrt(clamp01(lin.z))};
    PigmentLatent out;
    trilinear<4>(table_, kPigmentGrid, u, out.c.data());
    // What the tabulated mixture misses of this colour: decoding adds it back to the same
    // mixture, so a colour encoded and decoded is itself to float rounding.
    out.residual = lin - mixture(out.c);
    return out;
}

Color PigmentTable::mixture(const std::array<float, 4>& c) const {
    const float u[3] = {c[1], c[2], c[3]};
    float rgb[3];
    trilinear<3>(mix_, kMixGrid, u, rgb);
    return {rgb[0], rgb[1], rgb[2]};
}

Color PigmentTable::decode(const PigmentLatent& z) const {
    const Color c = mixture(z.c) + z.residual;
    return {clamp01(c.x), clamp01(c.y), clamp01(c.z)};
}

Color pigment_over(const PigmentTable& t, Color top, Color bottom, float a) {
    const PigmentLatent zt = t.encode(top), zb = t.encode(bottom);
    PigmentLatent z;
    for (int p = 0; p < 4; ++p) z.c[p] = zb.c[p] + (zt.c[p] - zb.c[p]) * a;
    z.residual = zb.residual + (zt.residual - zb.residual) * a;
    return t.decode(z);
}

}  // namespace pleinair
