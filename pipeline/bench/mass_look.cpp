// texture_repeat, value_masses and blur_box3.
#include "pipeline/bench/mass_look.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace pleinair {

namespace {

// A region reduced by whole blocks: a block's mean L* over its pixels in the mask, kept when
// at least three quarters of it lies in the mask (a region's ragged edge is not its texture).
struct Reduced {
    int w = 0, h = 0, factor = 1;
    std::vector<float> l;
    std::vector<uint8_t> mask;
};

Reduced reduce(const std::vector<float>& l, int w, int h, const std::vector<uint8_t>& mask) {
    Reduced r;
    r.factor = std::max(1, w / kRepeatWidth);
    const int f = r.factor;
    r.w = w / f, r.h = h / f;
    r.l.assign(static_cast<size_t>(r.w) * r.h, 0.0f);
    r.mask.assign(r.l.size(), 0);
    for (int by = 0; by < r.h; ++by)
        for (int bx = 0; bx < r.w; ++bx) {
            double sum = 0;
            int n = 0;
            for (int y = by * f; y < (by + 1) * f; ++y)
                for (int x = bx * f; x < (bx + 1) * f; ++x) {
                    const size_t i = static_cast<size_t>(y) * w + x;
                    if (mask[i]) sum += l[i], ++n;
                }
            if (4 * n < 3 * f * f) continue;
            const size_t o = static_cast<size_t>(by) * r.w + bx;
            r.l[o] = static_cast<float>(sum / n);
            r.mask[o] = 1;
        }
    return r;
}

// Each masked value less the mean of the masked values in the (2 radius + 1)^2 box around it
// (summed-area tables): what is left is the texture, not the light's slow gradient across it.
std::vector<float> minus_local_mean(const Reduced& r, int radius) {
    const size_t W = static_cast<size_t>(r.w) + 1;
    std::vector<double> s(W * (r.h + 1), 0.0), n(s.size(), 0.0);
    for (int y = 0; y < r.h; ++y)
        for (int x = 0; x < r.w; ++x) {
            const size_t i = static_cast<size_t>(y) * r.w + x, o = (y + 1) * W + (x + 1);
            s[o] = (r.mask[i] ? r.l[i] : 0.0) + s[o - 1] + s[o - W] - s[o - W - 1];
            n[o] = r.mask[i] + n[o - 1] + n[o - W] - n[o - W - 1];
        }
    auto box = [&](const std::vector<double>& t, int x0, int y0, int x1, int y1) {
        return t[y1 * W + x1] - t[y0 * W + x1] - t[y1 * W + x0] + t[y0 * W + x0];
    };
    std::vector<float> a(r.l.size(), 0.0f);
    for (int y = 0; y < r.h; ++y)
        for (int x = 0; x < r.w; ++x) {
            const size_t i = static_cast<size_t>(y) * r.w + x;
            if (!r.mask[i]) continue;
            const int x0 = std::max(0, x - radius), x1 = std::min(r.w, x + radius + 1);
            const int y0 = std::max(0, y - radius), y1 = std::min(r.h, y + radius + 1);
            a[i] = static_cast<float>(r.l[i] - box(s, x0, y0, x1, y1) / box(n, x0, y0, x1, y1));
        }
    return a;
}

}  // namespace

RepeatLook texture_repeat(const std::vector<float>& l, int w, int h,
                          const std::vector<uint8_t>& mask) {
    RepeatLook out;
    const Reduced r = reduce(l, w, h, mask);
    uint64_t n = 0;
    for (uint8_t m : r.mask) n += m;
    out.pixels = n;
    if (n < 256) return out;
    const std::vector<float> a = minus_local_mean(r, std::max(3, r.w / 12));
    const int D = std::max(2, r.w / 4), Dy = std::max(2, r.h / 4);
    const int gw = 2 * D + 1, gh = 2 * Dy + 1;
    // Correlation per offset, NaN where the overlap is under half the region: a motif must recur
    // across half of it to be wallpaper, and thinner overlaps are too few pixels to say.
    std::vector<double> c(static_cast<size_t>(gw) * gh, std::nan(""));
    const uint64_t min_pairs = std::max<uint64_t>(64, n / 2);
    tbb::parallel_for(0, Dy + 1, [&](int dy) {
        for (int dx = -D; dx <= D; ++dx) {
            double ab = 0, aa = 0, bb = 0;
            uint64_t pairs = 0;
            for (int y = 0; y + dy < r.h; ++y) {
                const size_t row = static_cast<size_t>(y) * r.w, row2 = row + size_t(dy) * r.w;
                for (int x = std::max(0, -dx); x < std::min(r.w, r.w - dx); ++x) {
                    const size_t p = row + x, q = row2 + (x + dx);
                    if (!r.mask[p] || !r.mask[q]) continue;
                    ab += double(a[p]) * a[q], aa += double(a[p]) * a[p], bb += double(a[q]) * a[q];
                    ++pairs;
                }
            }
            if (pairs < min_pairs || !(aa > 0 && bb > 0)) continue;
            const double v = ab / std::sqrt(aa * bb);
            // The autocorrelation is symmetric: r(d) = r(-d).
            c[static_cast<size_t>(Dy + dy) * gw + (D + dx)] = v;
            c[static_cast<size_t>(Dy - dy) * gw + (D - dx)] = v;
        }
    });
    // The central lobe: offsets joined to zero through positive correlation.
    std::vector<uint8_t> lobe(c.size(), 0);
    std::vector<int> stack{Dy * gw + D};
    lobe[stack.back()] = 1;
    while (!stack.empty()) {
        const int i = stack.back();
        stack.pop_back();
        const int x = i % gw, y = i / gw;
        const int nx[4] = {x - 1, x + 1, x, x}, ny[4] = {y, y, y - 1, y + 1};
        for (int k = 0; k < 4; ++k) {
            if (nx[k] < 0 || ny[k] < 0 || nx[k] >= gw || ny[k] >= gh) continue;
            const int j = ny[k] * gw + nx[k];
            if (lobe[j] || !(c[j] > 0)) continue;
            lobe[j] = 1;
            stack.push_back(j);
        }
    }
    for (size_t i = 0; i < c.size(); ++i)
        if (!lobe[i] && c[i] > out.score) {
            out.score = c[i];
            out.dx = (static_cast<int>(i % gw) - D) * r.factor;
            out.dy = (static_cast<int>(i / gw) - Dy) * r.factor;
        }
    return out;
}

std::vector<float> blur_box3(const std::vector<float>& l, int w, int h, int r) {
    std::vector<float> a = l, b(l.size());
    // One box pass along rows (stride 1) or columns (stride w), the window clamped at the edges.
    auto pass = [&](const std::vector<float>& in, std::vector<float>& out, bool rows) {
        const int lines = rows ? h : w, len = rows ? w : h;
        const size_t step = rows ? 1 : static_cast<size_t>(w);
        tbb::parallel_for(0, lines, [&](int line) {
            const size_t base = rows ? static_cast<size_t>(line) * w : static_cast<size_t>(line);
            std::vector<double> prefix(static_cast<size_t>(len) + 1, 0.0);
            for (int i = 0; i < len; ++i) prefix[i + 1] = prefix[i] + in[base + i * step];
            for (int i = 0; i < len; ++i) {
                const int i0 = std::max(0, i - r), i1 = std::min(len, i + r + 1);
                out[base + i * step] = static_cast<float>((prefix[i1] - prefix[i0]) / (i1 - i0));
            }
        });
    };
    for (int k = 0; k < 3; ++k) {
        pass(a, b, true);
        pass(b, a, false);
    }
    return a;
}

ValueMasses value_masses(const std::vector<float>& l, int w, int h) {
    ValueMasses out;
    if (l.empty()) return out;
    const std::vector<float> blurred = blur_box3(l, w, h, std::max(1, w / 60));
    // The histogram in 1 L* bins, smoothed twice by [1 4 6 4 1] / 16: a mode is a value held by
    // many pixels, not one bin's luck.
    constexpr int kBins = 101;
    std::vector<double> hist(kBins, 0.0), tmp(kBins);
    for (float v : blurred) hist[std::clamp(static_cast<int>(std::lround(v)), 0, kBins - 1)] += 1;
    for (int pass = 0; pass < 2; ++pass) {
        for (int i = 0; i < kBins; ++i) {
            const int k[5] = {1, 4, 6, 4, 1};
            double s = 0;
            for (int j = -2; j <= 2; ++j) s += k[j + 2] * hist[std::clamp(i + j, 0, kBins - 1)];
            tmp[i] = s / 16.0;
        }
        hist.swap(tmp);
    }
    std::vector<int> peaks;
    for (int i = 0; i < kBins; ++i) {
        const double left = i > 0 ? hist[i - 1] : -1.0, right = i + 1 < kBins ? hist[i + 1] : -1.0;
        if (hist[i] > left && hist[i] >= right && hist[i] > 0) peaks.push_back(i);
    }
    // Two neighbouring modes whose valley stays above half the lower one are one value.
    auto valley = [&](int a, int b) {
        int m = a;
        for (int i = a; i <= b; ++i)
            if (hist[i] < hist[m]) m = i;
        return m;
    };
    for (bool merged = true; merged && peaks.size() > 1;) {
        merged = false;
        for (size_t k = 0; k + 1 < peaks.size(); ++k) {
            const int a = peaks[k], b = peaks[k + 1];
            if (hist[valley(a, b)] > 0.5 * std::min(hist[a], hist[b])) {
                peaks.erase(peaks.begin() + static_cast<long>(hist[a] >= hist[b] ? k + 1 : k));
                merged = true;
                break;
            }
        }
    }
    double total = 0;
    for (double v : hist) total += v;
    for (size_t k = 0; k < peaks.size(); ++k) {
        const int lo = k ? valley(peaks[k - 1], peaks[k]) : 0;
        const int hi = k + 1 < peaks.size() ? valley(peaks[k], peaks[k + 1]) : kBins;
        double mass = 0;
        for (int i = lo; i < hi; ++i) mass += hist[i];
        const double share = total > 0 ? mass / total : 0.0;
        if (share < kValueMinShare) continue;
        out.modes.push_back(peaks[k]);
        out.shares.push_back(share);
    }
    out.values = static_cast<int>(out.modes.size());
    return out;
}

}  // namespace pleinair
