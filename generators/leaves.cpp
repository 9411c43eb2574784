// Leaf particles from the tree's vertices, then their normalised distances, labels and fades.
#include "generators/leaves.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <numeric>

#include "generators/tree_mesh.h"
#include "shading/curves.h"
#include "shading/portable_math.h"

namespace pleinair {

namespace {

// Which rings of a limb may emit leaves: [first, last].
struct RingRange {
    int first, last;
};

RingRange eligible_rings(const Limb& L, const LeafParams& lp, int lowest_trunk, int trim_trunk,
                         uint64_t seed) {
    const int top = static_cast<int>(L.rings.size()) - 1;
    if (L.level == 0) return {lowest_trunk, top - trim_trunk};
    Rng rng = make_rng(seed, Purpose::kLeafLimb, L.key);
    const int from_center = sample_whole(lp.steps_from_center, rng);
    const int from_tip = sample_whole(lp.steps_from_tip, rng);
    // Ring 0 of a branch is its parent's face: those vertices belong to the parent.
    return {std::max(1, from_center), top - from_tip};
}

// Labels in (0, 1) from 23 bits of each key's hash (odd multiples of 2^-24, exact in float).
// Two keys meeting on the same label (about one tree in two has such a pair among 3,000
// leaves) are parted by the next float up, in key order, so labels stay unique and the others
// do not move.
std::vector<float> unique_labels(const std::vector<uint64_t>& keys) {
    const size_t n = keys.size();
    std::vector<float> out(n);
    for (size_t i = 0; i < n; ++i)
        out[i] = static_cast<float>((static_cast<double>(keys[i] >> 41) + 0.5) / 8388608.0);
    std::vector<uint32_t> order(n);
    for (size_t i = 0; i < n; ++i) order[i] = static_cast<uint32_t>(i);
    std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
        return out[a] != out[b] ? out[a] < out[b] : keys[a] < keys[b];
    });
    for (size_t j = 1; j < n; ++j) {
        float& cur = out[order[j]];
        const float prev = out[order[j - 1]];
        if (cur <= prev) cur = std::nextafter(prev, 1.0f);
        if (!(cur < 1.0f)) cur = std::nextafter(1.0f, 0.0f);  // 2^-25 from 1: never reached
    }
    return out;
}

}  // namespace

LeafParticles emit_leaves(const TreeMesh& tm, const TreeParams& params, uint64_t seed,
                          uint32_t tree_id, glm::dvec3& center) {
    const LeafParams& lp = params.leaves;
    LeafParticles out;
    std::vector<glm::dvec3> pos;  // double until the end: distances are taken locally
    std::vector<double> along;
    std::vector<double> g_start, g_len;  // the fade's gaussian draws, made while growing

    // First the decisions, so every array is allocated once.
    struct Emitter {
        const Limb* limb;
        int ring, corner;
        uint64_t key;
    };
    std::vector<Emitter> emitters;
    Rng tree_rng = make_rng(seed, Purpose::kTree, uint64_t{100});
    const int lowest_trunk = sample_whole(lp.lowest_step_trunk, tree_rng);
    const int trim_trunk = sample_whole(lp.trim_top_steps_trunk, tree_rng);
    const double probability = sample(lp.probability, tree_rng);
    for (const Limb& L : tm.limbs) {
        if (L.level < lp.lowest_level) continue;
        const RingRange rings = eligible_rings(L, lp, lowest_trunk, trim_trunk, seed);
        for (int r = rings.first; r <= rings.last; ++r) {
            for (int j = 0; j < 4; ++j) {
                const uint64_t key =
                    hash_keys(L.key, static_cast<uint64_t>(r), static_cast<uint64_t>(j));
                Rng decide = make_rng(seed, Purpose::kLeafDecide, key);
                if (rand1(decide) < probability) emitters.push_back({&L, r, j, key});
            }
        }
    }
    const size_t most = emitters.size() * static_cast<size_t>(std::lround(lp.branching_steps.base));
    pos.reserve(most);
    along.reserve(most);
    out.normal.reserve(most);
    g_start.reserve(most);
    g_len.reserve(most);

    // Each leaf's label comes from its own key (the emitter's and the step's), not from its
    // place in the list, so adding a branch relabels no other leaf.
    std::vector<uint64_t> label_key;
    label_key.reserve(most);
    out.limb.reserve(most);
    for (const Emitter& e : emitters) {
        const Limb& L = *e.limb;
        Rng rng = make_rng(seed, Purpose::kLeafGrow, e.key);
        const glm::dvec3 p0 = tm.point(L.rings[e.ring][e.corner]);
        const glm::dvec3 outward =
            safe_normalize(p0 - L.centers[e.ring], any_perpendicular(L.direction));
        // Start direction: uniform over the cone of aperture branch_angle about the vertex's
        // outward normal.
        const double half = 0.5 * radians(sample(lp.branch_angle, rng));
        const double cos_t = 1.0 - rand1(rng) * (1.0 - pmath::cos(half));
        const double sin_t = std::sqrt(std::max(0.0, 1.0 - cos_t * cos_t));
        glm::dvec3 dir = turn_direction(outward, cos_t, sin_t, rand1(rng));
        const int steps = sample_whole(lp.branching_steps, rng);
        const double tropism = sample(lp.tropism.strength, rng);

        glm::dvec3 p = p0;
        double dist = 0;
        bool grounded = false;
        for (int k = 0; k < steps; ++k) {
            const double wob = sample(lp.branch_dir_wobble, rng);
            const double wob_az = rand1(rng);
            const double step = sample(lp.branching_distance, rng) * tm.unit;
            const double gs = rand_gaussian(rng), gl = rand_gaussian(rng);
            if (grounded) continue;  // keep drawing: the stream's position is fixed
            const double pull = tropism_pull(tropism, lp.tropism.increase, dist, tm.unit);
            dir = apply_tropism(wobble_direction(dir, wob, wob_az), lp.tropism.direction, pull);
            const glm::dvec3 next = p + dir * step;
            if (next.y < 0) {  // leaves never go under the ground
                grounded = true;
                continue;
            }
            p = next;
            dist += step;
            pos.push_back(p);
            label_key.push_back(hash_keys(seed, static_cast<uint64_t>(Purpose::kLeafLabel), e.key,
                                          static_cast<uint64_t>(k)));
            along.push_back(dist);
            out.normal.push_back(glm::vec3(dir));
            g_start.push_back(gs);
            g_len.push_back(gl);
            out.limb.push_back(static_cast<uint32_t>(e.limb - tm.limbs.data()));
        }
    }

    const size_t n = pos.size();
    // Centre locator: canopy centroid (sum in double) plus the preset's offset.
    glm::dvec3 sum(0);
    for (const auto& p : pos) sum += p;
    const Limb& trunk = tm.limbs.front();
    center = (n > 0 ? sum / static_cast<double>(n) : trunk.centers.back()) +
             params.center_offset * params.unit;

    double max_along = 0, max_center = 0;
    std::vector<double> from_center(n);
    for (size_t i = 0; i < n; ++i) {
        from_center[i] = glm::length(pos[i] - center);
        max_along = std::max(max_along, along[i]);
        max_center = std::max(max_center, from_center[i]);
    }
    const FadeParams& fp = lp.fade;
    const std::vector<float> labels = unique_labels(label_key);
    out.position.resize(n);
    out.branch_distance.resize(n);
    out.center_distance.resize(n);
    out.label.resize(n);
    out.tree_id.assign(n, tree_id);
    out.fade_begin.resize(n);
    out.fade_end.resize(n);
    // Each leaf's rank in distance from the centre, 0 innermost .. 1 outermost (ties by index),
    // the distance measured in units of the crown's spread along each axis: a tall poplar then
    // thins from its top and sides alike instead of losing its height first. The fade follows
    // the rank, not the distance itself, so a crown whose leaves crowd at middle distances still
    // thins at one pace across the circles.
    glm::dvec3 spread(0.0);
    for (const auto& p : pos) spread += (p - center) * (p - center);
    spread = glm::sqrt(spread / static_cast<double>(std::max<size_t>(n, 1)));
    const double floor = 1e-3 * std::max({spread.x, spread.y, spread.z, 1e-9});
    spread = glm::max(spread, glm::dvec3(floor));
    std::vector<double> normalised(n);
    for (size_t i = 0; i < n; ++i) normalised[i] = glm::length((pos[i] - center) / spread);
    std::vector<size_t> order(n);
    for (size_t i = 0; i < n; ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
        return normalised[a] < normalised[b] || (normalised[a] == normalised[b] && a < b);
    });
    std::vector<double> rank(n, 0.0);
    for (size_t r = 0; r < n; ++r)
        rank[order[r]] = n > 1 ? static_cast<double>(r) / static_cast<double>(n - 1) : 0.0;
    for (size_t i = 0; i < n; ++i) {
        out.position[i] = glm::vec3(pos[i]);
        out.branch_distance[i] = max_along > 0 ? static_cast<float>(along[i] / max_along) : 0.0f;
        out.center_distance[i] =
            max_center > 0 ? static_cast<float>(std::min(1.0, from_center[i] / max_center)) : 0.0f;
        out.label[i] = labels[i];
        // The innermost `keep` of the leaves never fade: they paint the tree beyond the far
        // circle. The others fade completely inside the circles, the outermost from the near
        // one, so no leaf is left half transparent at the far circle.
        double len = std::max(fp.length_min, std::clamp(fp.length.base + fp.length.var * g_len[i],
                                                        fp.length.lo, fp.length.hi));
        len = std::min(len, 1.0);
        double start = 2.0;
        if (rank[i] >= fp.keep) {
            const double x = fp.keep < 1 ? (1.0 - rank[i]) / (1.0 - fp.keep) : 0.0;
            start = bias(static_cast<float>(x), static_cast<float>(fp.threshold_bias));
            start = std::clamp(start * (1.0 - len) + fp.threshold_var * g_start[i], 0.0, 1.0 - len);
        }
        out.fade_begin[i] = static_cast<float>(start);
        out.fade_end[i] = static_cast<float>(start + len);
    }
    return out;
}

}  // namespace pleinair
