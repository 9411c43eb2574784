// measure_form and side_masks: a tree's form from its side view's coverage (masks.h closes the
// masks and finds their components and outlines).
#include "pipeline/bench/tree_form.h"

#include <algorithm>
#include <cmath>

#include "pipeline/bench/masks.h"
#include "pipeline/output/contact_sheet.h"

namespace pleinair {

namespace {

// The first index along `counts` (rows or columns) by which `share` of the total lies before
// it, from the front; from the back when `back`.
int quantile_edge(const std::vector<size_t>& counts, size_t total, double share, bool back) {
    const double want = share * static_cast<double>(total);
    double sum = 0;
    const int n = static_cast<int>(counts.size());
    for (int k = 0; k < n; ++k) {
        const int i = back ? n - 1 - k : k;
        sum += static_cast<double>(counts[static_cast<size_t>(i)]);
        if (sum > want) return i;
    }
    return back ? 0 : n - 1;
}

// The mean over the crown's two sides (columns within kHemSide of the crown's width from
// `left` and from `right`) of the height above the trunk's foot where their leaves end.
double hem(const SideMasks& m, int left, int right, int base, double height) {
    const int side = std::max(1, static_cast<int>(std::lround(kHemSide * (right - left + 1))));
    double sum = 0;
    for (const auto& [x0, x1] :
         {std::pair{left, left + side}, std::pair{right - side + 1, right + 1}}) {
        std::vector<size_t> rows(static_cast<size_t>(m.height), 0);
        size_t n = 0;
        for (int y = 0; y < m.height; ++y)
            for (int x = std::max(0, x0); x < std::min(m.width, x1); ++x)
                if (m.leaf[static_cast<size_t>(y) * m.width + x])
                    ++rows[static_cast<size_t>(y)], ++n;
        const int lowest = n ? quantile_edge(rows, n, kHemStray, true) : base;
        sum += std::max(0, base - lowest) / height;
    }
    return 0.5 * sum;
}

}  // namespace

TreeForm measure_form(const SideMasks& m, const Tree& tree) {
    TreeForm f;
    const int w = m.width, h = m.height;
    std::vector<size_t> rows(static_cast<size_t>(h), 0), cols(static_cast<size_t>(w), 0);
    size_t leaves = 0;
    int bark_top = h, bark_base = -1;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t i = static_cast<size_t>(y) * w + x;
            if (m.leaf[i]) ++rows[static_cast<size_t>(y)], ++cols[static_cast<size_t>(x)], ++leaves;
            if (m.bark[i]) bark_top = std::min(bark_top, y), bark_base = std::max(bark_base, y);
        }
    if (leaves == 0 || bark_base < 0) return f;
    // The crown's extent without its last half percent of leaf pixels each way: a stray stroke
    // does not widen it.
    constexpr double kStray = 0.005;
    const int top = quantile_edge(rows, leaves, kStray, false);
    const int bottom = quantile_edge(rows, leaves, kStray, true);
    const int left = quantile_edge(cols, leaves, kStray, false);
    const int right = quantile_edge(cols, leaves, kStray, true);
    const double crown_h = bottom - top + 1, crown_w = right - left + 1;
    // Height from the trunk's foot to the crown's top: a spread over a height, as botanists
    // give a species' form.
    const double height = bark_base - std::min(top, bark_top) + 1;
    f.crown_ratio = crown_w / height;
    f.clear_trunk = std::max(0, bark_base - bottom) / height;

    f.hem = hem(m, left, right, bark_base, height);

    const LeafParticles& L = tree.leaves;
    size_t below = 0;
    for (size_t i = 0; i < L.position.size() && i < L.limb.size(); ++i)
        below += L.position[i].y < tree.branches[L.limb[i]].start.y;
    f.droop = L.position.empty() ? 0.0 : static_cast<double>(below) / L.position.size();

    const double extent = std::max(crown_w, crown_h);
    // Masses: the crown closed over the gaps between its strokes, then worn down by kNeckRadius,
    // so that masses joined only by a waist narrower than twice that come apart; a mass counts
    // when its core holds kMassShare of all the cores (a stroke's leftover does not).
    const Mask clumped = closed(m.leaf, w, h, static_cast<int>(std::lround(kClumpRadius * extent)));
    const Mask cores = eroded(clumped, w, h, static_cast<int>(std::lround(kNeckRadius * extent)));
    size_t core_total = 0;
    for (const uint8_t c : cores) core_total += c != 0;
    std::vector<bool> seen(cores.size(), false);
    for (size_t i = 0; i < cores.size(); ++i)
        if (cores[i] && !seen[i])
            f.clumps += flood(cores, w, h, i, 1, seen) >= kMassShare * core_total;
    // A crown thinner everywhere than the waist (a strand, a sapling) is still one mass.
    if (core_total == 0) f.clumps = 1;

    // The outline: the crown closed, and every gap it then encloses filled.
    const Mask shut = outline(m.leaf, w, h, static_cast<int>(std::lround(kOutlineRadius * extent)));
    size_t inside = 0, sky = 0;
    for (size_t i = 0; i < shut.size(); ++i) {
        if (!shut[i]) continue;
        ++inside;
        sky += !m.leaf[i] && !m.bark[i];
    }
    f.holes = inside ? static_cast<double>(sky) / inside : 0.0;
    return f;
}

SideMasks side_masks(const SceneDesc& scene, const BuiltTree& tree, int width, int height) {
    const CameraParams camera = side_camera(tree, width, height);
    BuiltTree leaves = tree;
    leaves.bark_strokes = std::make_shared<BarkParticles>();
    BuiltTree bark = tree;
    bark.grown = std::make_shared<Tree>(tree.tree());
    bark.grown->leaves = LeafParticles{};
    SideMasks m;
    m.width = width, m.height = height;
    auto coverage = [&](const BuiltTree& b) {
        const Frame f = paint_alone(scene, b, camera, true);
        Mask out(f.alpha.size());
        for (size_t i = 0; i < out.size(); ++i) out[i] = f.alpha[i] > 0.5f;
        return out;
    };
    m.leaf = coverage(leaves);
    m.bark = coverage(bark);
    return m;
}

}  // namespace pleinair
