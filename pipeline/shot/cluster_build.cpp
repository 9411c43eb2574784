// build_clusters: particles sorted by a Morton code of their place (a tree's also by when they
// fade), cut into runs, bounded.
#include "pipeline/shot/cluster_build.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

#include "shading/stroke_shader.h"

namespace pleinair {

namespace {

// 10 bits of x, y and z interleaved.
uint32_t morton3(uint32_t x, uint32_t y, uint32_t z) {
    auto spread = [](uint32_t v) {
        v &= 0x3ffu;
        v = (v | (v << 16)) & 0x030000ffu;
        v = (v | (v << 8)) & 0x0300f00fu;
        v = (v | (v << 4)) & 0x030c30c3u;
        v = (v | (v << 2)) & 0x09249249u;
        return v;
    };
    return spread(x) | (spread(y) << 1) | (spread(z) << 2);
}

// Indices 0 .. n - 1 ordered by the Morton code of pos(i) in their bounding box, ties by index.
template <class Pos>
std::vector<uint32_t> by_place(size_t n, Pos&& pos) {
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (size_t i = 0; i < n; ++i) lo = glm::min(lo, pos(i)), hi = glm::max(hi, pos(i));
    const glm::vec3 ext = glm::max(hi - lo, glm::vec3(1e-20f));
    std::vector<std::pair<uint32_t, uint32_t>> keyed(n);
    for (size_t i = 0; i < n; ++i) {
        const glm::vec3 u = glm::clamp((pos(i) - lo) / ext, 0.0f, 1.0f) * 1023.0f;
        // A non-finite place sorts last, as it comes.
        const bool ok = std::isfinite(u.x) && std::isfinite(u.y) && std::isfinite(u.z);
        keyed[i] = {ok ? morton3(uint32_t(u.x), uint32_t(u.y), uint32_t(u.z)) : ~0u,
                    static_cast<uint32_t>(i)};
    }
    std::sort(keyed.begin(), keyed.end());
    std::vector<uint32_t> order(n);
    for (size_t i = 0; i < n; ++i) order[i] = keyed[i].second;
    return order;
}

struct Box {
    glm::dvec3 lo{std::numeric_limits<double>::max()}, hi{-std::numeric_limits<double>::max()};
    void add(const glm::dvec3& p) { lo = glm::min(lo, p), hi = glm::max(hi, p); }
    // Padded by a millionth of its coordinates' size: the places frames compute in double
    // from the same floats may round the other way.
    void pad() {
        const glm::dvec3 m = glm::max(glm::abs(lo), glm::abs(hi));
        const double e = 1e-6 * (1.0 + std::max({m.x, m.y, m.z}));
        lo -= glm::dvec3(e), hi += glm::dvec3(e);
    }
};

// A tree-local box placed in the world: the bounds of its eight corners placed.
Box placed(const TreePlacement& pl, const Box& local) {
    Box out;
    for (int c = 0; c < 8; ++c) {
        const glm::dvec3 p((c & 1) ? local.hi.x : local.lo.x, (c & 2) ? local.hi.y : local.lo.y,
                           (c & 4) ? local.hi.z : local.lo.z);
        out.add(pl.position + pl.linear() * p);
    }
    return out;
}

// The distance value at or above which particle j has faded out (lod.h's fades): its tree's for
// leaves and bark, its own for surface strokes; infinity if it never does.
float gone_at(const ParticleSource& shot, size_t item, SpriteKind kind, size_t j) {
    const std::vector<BuiltTree>& trees = shot.trees;
    float at = std::numeric_limits<float>::infinity();
    if (kind == SpriteKind::kLeaf) {
        const LeafParticles& L = trees[item].tree().leaves;
        at = std::max(L.fade_begin[j], L.fade_end[j]);
    } else if (kind == SpriteKind::kBark) {
        const BuiltTree& b = trees[item];
        if (twig_bark_fades(b.tree().branches[b.bark().limb[j]]))
            at = bark_fade_begin(b.bark().label[j]) + kBarkFadeSpan;
    } else {
        const SurfaceParticles& S = shot.land.chunks[item - trees.size()];
        if (!(S.fade_begin(j) > 1.0f)) at = std::max(S.fade_begin(j), S.fade_end(j));
    }
    return std::isnan(at) ? std::numeric_limits<float>::infinity() : at;
}

// Particle j's stroke size bounds into its cluster.
void bound_stroke(const ParticleSource& shot, size_t item, SpriteKind kind, size_t j,
                  ParticleCluster& c) {
    MaterialId mat;
    const ParticleInput in = particle_input(shot, item, kind, j, RayOrigin{}, mat);
    const StrokeShaderParams& p = *shot.materials[mat].shader;
    const float edge = kind == SpriteKind::kLeaf ? crown_edge_size(p, in.center_distance) : 1.0f;
    const float jitter = stroke_size_jitter(p, in.label);
    c.stroke = std::max(c.stroke, static_cast<float>((in.width + in.length) * jitter * edge));
    const double aspect = in.width > 0 ? in.length / in.width : 0.0;
    c.min_px_factor = std::max(c.min_px_factor, static_cast<float>((1.0 + aspect) * edge));
}

// The clusters of one kind of item `item`, whose particles' places are pos(j) (tree-local for
// trees, world for surfaces).
template <class Pos>
void cluster_kind(const ParticleSource& shot, size_t item, SpriteKind kind, size_t n, Pos&& pos,
                  ItemClusters& out) {
    if (n == 0) return;
    std::vector<uint32_t> order = by_place(n, pos);
    std::vector<float> gone(n);
    for (size_t j = 0; j < n; ++j) gone[j] = gone_at(shot, item, kind, j);
    // A tree's leaves and bark strokes fade by one distance value, the tree's, each at its own
    // threshold: runs of like thresholds fade out whole, and a tree is mostly in view or not.
    if (kind != SpriteKind::kSurface)
        std::stable_sort(order.begin(), order.end(),
                         [&](uint32_t a, uint32_t b) { return gone[a] < gone[b]; });
    const std::vector<BuiltTree>& trees = shot.trees;
    const bool tree = item < trees.size();
    const TreePlacement* pl = tree ? &shot.placements[item] : nullptr;
    // Leaves spread out along their direction from the crown's centre, never past its farthest
    // leaf (lod.h): a little more for the float arithmetic that moves them.
    glm::vec3 center(0.0f);
    float reach = 0;
    if (kind == SpriteKind::kLeaf) {
        center = trees[item].tree().center;
        for (size_t j = 0; j < n; ++j) reach = std::max(reach, glm::length(pos(j) - center));
        reach *= 1.0001f;
    }
    for (size_t first = 0; first < n; first += kClusterSize) {
        ParticleCluster c;
        c.kind = kind;
        c.first = static_cast<uint32_t>(out.order.size());
        c.count = static_cast<uint32_t>(std::min<size_t>(kClusterSize, n - first));
        Box box, spread;
        c.gone_at = -std::numeric_limits<float>::infinity();
        for (uint32_t k = 0; k < c.count; ++k) {
            const uint32_t j = order[first + k];
            out.order.push_back(j);
            const glm::vec3 p = pos(j);
            box.add(glm::dvec3(p)), spread.add(glm::dvec3(p));
            if (kind == SpriteKind::kLeaf) {
                const glm::vec3 v = p - center;
                const float r = glm::length(v);
                if (r > 0 && std::isfinite(r)) spread.add(glm::dvec3(center + v * (reach / r)));
            }
            bound_stroke(shot, item, kind, j, c);
            c.gone_at = std::max(c.gone_at, gone[j]);
        }
        if (tree) box = placed(*pl, box), spread = placed(*pl, spread);
        box.pad(), spread.pad();
        c.lo = box.lo, c.hi = box.hi, c.spread_lo = spread.lo, c.spread_hi = spread.hi;
        out.clusters.push_back(c);
    }
}

}  // namespace

std::vector<ItemClusters> build_clusters(const ParticleSource& shot) {
    const std::vector<BuiltTree>& trees = shot.trees;
    std::vector<ItemClusters> all(shot.item_count());
    tbb::parallel_for(size_t{0}, all.size(), [&](size_t i) {
        ItemClusters& out = all[i];
        if (i >= trees.size()) {
            const SurfaceParticles& S = shot.land.chunks[i - trees.size()];
            cluster_kind(
                shot, i, SpriteKind::kSurface, S.size(), [&](size_t j) { return S.position[j]; },
                out);
            return;
        }
        const BuiltTree& b = trees[i];
        if (shot.bark)
            cluster_kind(
                shot, i, SpriteKind::kBark, b.bark().size(),
                [&](size_t j) { return b.bark().position[j]; }, out);
        const LeafParticles& L = b.tree().leaves;
        cluster_kind(
            shot, i, SpriteKind::kLeaf, L.size(), [&](size_t j) { return L.position[j]; }, out);
    });
    return all;
}

}  // namespace pleinair
