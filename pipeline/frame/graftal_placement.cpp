// The difference-image placement of graftals: Pascal dots subtracted from a desire image.
#include "pipeline/frame/graftal_placement.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <queue>

#include "generators/rng.h"
#include "shading/curves.h"

namespace pleinair {

namespace {

// Adds amount x dot centred on (cx, cy), clipped to the image; with `floor`, no value goes
// below 0 (the desire image; the accumulator of dots taken has no floor to keep).
void add_dot(DesireImage& img, const std::vector<float>& dot, int row, int cx, int cy, float amount,
             bool floor = false) {
    const int r = row / 2, n = row + 1;
    for (int j = 0; j < n; ++j) {
        const int y = cy - r + j;
        if (y < 0 || y >= img.height) continue;
        for (int i = 0; i < n; ++i) {
            const int x = cx - r + i;
            if (x < 0 || x >= img.width) continue;
            float& d = img.desire[static_cast<size_t>(y) * img.width + x];
            d += amount * dot[static_cast<size_t>(j) * n + i];
            if (floor) d = std::max(0.0f, d);
        }
    }
}

void subtract_dot(DesireImage& img, const std::vector<float>& dot, int row, int cx, int cy,
                  float strength) {
    add_dot(img, dot, row, cx, cy, -strength, true);
}

// The desire at a continuous position (pixel centres at +0.5), bilinear between the four
// nearest pixels, clamped at the borders.
float desire_at(const DesireImage& img, float u, float v, int& x0, int& y0, float& fx, float& fy) {
    u -= 0.5f, v -= 0.5f;
    const float fu = std::floor(u), fv = std::floor(v);
    x0 = static_cast<int>(fu), y0 = static_cast<int>(fv);
    fx = u - fu, fy = v - fv;
    auto at = [&](int x, int y) {
        x = std::clamp(x, 0, img.width - 1), y = std::clamp(y, 0, img.height - 1);
        return img.desire[static_cast<size_t>(y) * img.width + x];
    };
    return (1 - fy) * ((1 - fx) * at(x0, y0) + fx * at(x0 + 1, y0)) +
           fy * ((1 - fx) * at(x0, y0 + 1) + fx * at(x0 + 1, y0 + 1));
}

bool valid(const DesireImage& img) {
    return img.width > 0 && img.height > 0 &&
           img.desire.size() == static_cast<size_t>(img.width) * img.height &&
           (img.id.empty() || img.id.size() == img.desire.size());
}

}  // namespace

std::vector<float> pascal_dot(int row) {
    row = std::clamp(row, 0, 60);  // C(60, 30) ~ 1.2e17: still exact enough in double
    std::vector<double> c(static_cast<size_t>(row) + 1, 1.0);
    for (int k = 1; k < row; ++k) c[k] = c[k - 1] * (row - k + 1) / k;
    const double peak = c[static_cast<size_t>(row / 2)];
    const size_t n = c.size();
    std::vector<float> dot(n * n);
    for (size_t j = 0; j < n; ++j)
        for (size_t i = 0; i < n; ++i)
            dot[j * n + i] = static_cast<float>((c[j] / peak) * (c[i] / peak));
    return dot;
}

std::vector<uint32_t> place_candidates(DesireImage& img,
                                       const std::vector<GraftalCandidate>& candidates,
                                       const DifferencePlacement& p, std::vector<float>* weights) {
    std::vector<uint32_t> placed;
    if (weights) weights->clear();
    if (!valid(img)) return placed;
    // The same order in every frame: by a hash of each candidate's key, ties by the key.
    std::vector<uint32_t> order(candidates.size());
    std::iota(order.begin(), order.end(), 0u);
    std::vector<uint64_t> rank(candidates.size());
    for (size_t i = 0; i < candidates.size(); ++i) rank[i] = mix64(candidates[i].key);
    std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
        return rank[a] != rank[b] ? rank[a] < rank[b] : candidates[a].key < candidates[b].key;
    });
    const std::vector<float> dot = pascal_dot(p.dot_row);
    const int row = std::clamp(p.dot_row, 0, 60);
    // The dots placed so far, for candidates that carry their own desire.
    DesireImage taken{img.width, img.height, std::vector<float>(img.desire.size(), 0.0f), {}};
    const bool own = std::any_of(candidates.begin(), candidates.end(),
                                 [](const GraftalCandidate& c) { return c.desire >= 0; });
    for (uint32_t c : order) {
        if (placed.size() >= p.max_count) break;
        const glm::vec2 px = candidates[c].pixel;
        if (!(px.x >= 0 && px.y >= 0 && px.x < img.width && px.y < img.height)) continue;
        const int x = static_cast<int>(px.x), y = static_cast<int>(px.y);
        const size_t at = static_cast<size_t>(y) * img.width + x;
        if (!img.id.empty() && img.id[at] != candidates[c].object) continue;  // hidden there
        // Read and subtracted where the candidate is, between pixels: a candidate moving by a
        // fraction of a pixel changes the desire it leaves by a fraction, not by a whole dot
        // jumping to the next pixel, and so the choices after it change little.
        int x0, y0;
        float fx, fy;
        const float image = desire_at(img, px.x, px.y, x0, y0, fx, fy);
        const float left = candidates[c].desire >= 0
                               ? candidates[c].desire - desire_at(taken, px.x, px.y, x0, y0, fx, fy)
                               : image;
        if (!(left >= p.threshold)) continue;
        const float weight =
            p.band > 0 ? smoothstep(p.threshold, p.threshold + p.band, left) : 1.0f;
        if (!(weight > 0.0f)) continue;
        placed.push_back(c);
        if (weights) weights->push_back(weight);
        const float w[4] = {(1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy};
        for (int k = 0; k < 4; ++k) {
            const float amount = p.strength * weight * w[k];
            subtract_dot(img, dot, row, x0 + (k & 1), y0 + (k >> 1), amount);
            if (own) add_dot(taken, dot, row, x0 + (k & 1), y0 + (k >> 1), amount);
        }
    }
    return placed;
}

std::vector<glm::ivec2> fill_by_difference(DesireImage& img, const DifferencePlacement& p) {
    std::vector<glm::ivec2> placed;
    if (!valid(img)) return placed;
    const std::vector<float> dot = pascal_dot(p.dot_row);
    const int row = std::clamp(p.dot_row, 0, 60);
    // A max-heap of (desire, -index) with lazy updates: an entry whose desire has since been
    // lowered goes back in with its current value. Ties go to the lower index, so the result
    // is one function of the image.
    using Entry = std::pair<float, int64_t>;
    std::priority_queue<Entry> heap;
    for (size_t i = 0; i < img.desire.size(); ++i)
        if (img.desire[i] >= p.threshold) heap.push({img.desire[i], -static_cast<int64_t>(i)});
    while (!heap.empty() && placed.size() < p.max_count) {
        const auto [value, neg] = heap.top();
        heap.pop();
        const size_t i = static_cast<size_t>(-neg);
        const float now = img.desire[i];
        if (now != value) {
            if (now >= p.threshold) heap.push({now, neg});
            continue;
        }
        const int x = static_cast<int>(i % img.width), y = static_cast<int>(i / img.width);
        placed.push_back({x, y});
        subtract_dot(img, dot, row, x, y, p.strength);
    }
    return placed;
}

}  // namespace pleinair
