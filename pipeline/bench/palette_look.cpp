// linear_srgb_to_lab, pixel_lab, pixel_chroma and palette_look.
#include "pipeline/bench/palette_look.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "shading/color.h"
#include "shading/portable_math.h"

namespace pleinair {

std::array<float, 3> linear_srgb_to_lab(float r, float g, float b) {
    r = clamp01(r), g = clamp01(g), b = clamp01(b);
    // sRGB primaries to XYZ, each row over the D65 white's component.
    const double x = (0.4124564 * r + 0.3575761 * g + 0.1804375 * b) / 0.95047;
    const double y = 0.2126729 * r + 0.7151522 * g + 0.0721750 * b;
    const double z = (0.0193339 * r + 0.1191920 * g + 0.9503041 * b) / 1.08883;
    auto f = [](double t) {
        return t > 216.0 / 24389.0 ? pmath::cbrt(t) : (24389.0 / 27.0 * t + 16.0) / 116.0;
    };
    const double fx = f(x), fy = f(y), fz = f(z);
    return {static_cast<float>(116.0 * fy - 16.0), static_cast<float>(500.0 * (fx - fy)),
            static_cast<float>(200.0 * (fy - fz))};
}

std::array<float, 3> pixel_lab(const Frame& f, size_t i) {
    // Premultiplied over the opaque background: alpha is 1 wherever the frame is painted.
    const float a = f.rgba[4 * i + 3], k = a > 0 ? 1.0f / a : 0.0f;
    return linear_srgb_to_lab(f.rgba[4 * i] * k, f.rgba[4 * i + 1] * k, f.rgba[4 * i + 2] * k);
}

float pixel_chroma(const Frame& f, size_t i) {
    const auto lab = pixel_lab(f, i);
    return pmath::hypot(lab[1], lab[2]);
}

PaletteLook palette_look(const Frame& f) {
    PaletteLook p;
    const size_t n = static_cast<size_t>(f.width) * f.height;
    if (n == 0) return p;
    std::vector<float> chroma(n), lightness(n);
    double sum = 0;
    size_t warm = 0;
    for (size_t i = 0; i < n; ++i) {
        const auto lab = pixel_lab(f, i);
        const float c = pmath::hypot(lab[1], lab[2]);
        chroma[i] = c, lightness[i] = lab[0];
        sum += c;
        float hue = pmath::atan2(lab[2], lab[1]) * 57.29578f - kWarmHueCentre;
        hue = std::remainder(hue, 360.0f);
        warm += c >= kWarmChroma && std::abs(hue) <= kWarmHue;
        const int bin = std::clamp(static_cast<int>(lab[0] / 20.0f), 0, 4);
        p.lightness[static_cast<size_t>(bin)] += 1.0;
    }
    for (double& s : p.lightness) s /= static_cast<double>(n);
    p.chroma_mean = sum / static_cast<double>(n);
    p.warm = static_cast<double>(warm) / static_cast<double>(n);
    auto quantile = [&](std::vector<float>& v, double q) {
        const size_t k = std::min(n - 1, static_cast<size_t>(q * static_cast<double>(n)));
        std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
        return static_cast<double>(v[k]);
    };
    p.chroma_p95 = quantile(chroma, 0.95);
    p.lightness_median = quantile(lightness, 0.5);
    return p;
}

}  // namespace pleinair
