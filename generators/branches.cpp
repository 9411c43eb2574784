// Branches from the side faces of trunk or branches.
#include "generators/branches.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

#include "shading/portable_math.h"

namespace pleinair {

namespace {

using OpenMesh::FaceHandle;

// Position of segment s along its limb, 0 at the base and 1 at the top: height for the trunk,
// step count for a branch.
double position_along(const Limb& L, int s) {
    const int segments = static_cast<int>(L.rings.size()) - 1;
    if (L.level == 0) {
        double top = L.centers.back().y;
        double mid = 0.5 * (L.centers[s].y + L.centers[s + 1].y);
        return top > 0 ? mid / top : 0.0;
    }
    return (s + 0.5) / segments;
}

// `length_scale`: the apical profile's scale of max_length where the branch starts.
void sprout(TreeMesh& tm, int parent_index, int s, int j, int level, uint64_t key,
            const BranchParams& bp, double length_scale, uint64_t seed) {
    Rng rng = make_rng(seed, Purpose::kBranchGrow, key);
    const double angle = sample(bp.angle, rng);
    const double max_length = sample(bp.max_length, rng) * length_scale * tm.unit;
    const double first_length = sample(bp.first_length, rng) * tm.unit;
    const double first_taper = sample(bp.first_taper, rng);
    const int max_steps = sample_whole(bp.max_steps, rng);
    const double tropism_strength = sample(bp.tropism.strength, rng);

    const Limb& P = tm.limbs[parent_index];
    FaceHandle f = P.sides[4 * s + j];
    if (!f.is_valid()) return;
    Ring a;
    auto h = tm.mesh.halfedge_handle(f);
    glm::dvec3 p[4], c(0);
    for (int i = 0; i < 4; ++i) {
        a[i] = tm.mesh.from_vertex_handle(h);
        p[i] = tm.point(a[i]);
        c += 0.25 * p[i];
        h = tm.mesh.next_halfedge_handle(h);
    }
    const glm::dvec3 axis = safe_normalize(P.centers[s + 1] - P.centers[s], P.direction);
    const glm::dvec3 n =
        safe_normalize(glm::cross(p[2] - p[0], p[3] - p[1]), any_perpendicular(axis));

    // The square fits in the circle around the face's centre that touches its nearest edge (so
    // it stays inside even a skewed face), scaled by first_taper and never wider than the parent
    // there: radii do not grow from parent to child.
    double inradius = 1e300;
    for (int i = 0; i < 4; ++i) {
        const glm::dvec3 edge = p[(i + 1) & 3] - p[i];
        const double len = glm::length(edge);
        if (len > 0) inradius = std::min(inradius, glm::length(glm::cross(edge, c - p[i])) / len);
    }
    const double parent_r = std::min(P.radii[s], P.radii[s + 1]);
    const double half_diag = first_taper * std::min(inradius, parent_r);
    if (!(half_diag > tm.min_radius)) return;

    // First extrusion: short, along the face normal, new face square and planar (Fig. 12).
    // The square's sides run along the face's, so each side quad is a trapezoid between two
    // parallel edges and never folds, however long the parent face is.
    const glm::dvec3 along = (p[1] - p[0]) + (p[2] - p[3]);
    const glm::dvec3 e1 = safe_normalize(along - n * glm::dot(along, n), any_perpendicular(n));
    const glm::dvec3 e2 = glm::cross(n, e1);
    const glm::dvec3 c1 = c + n * first_length;
    // Square corners sit at 45 + 90 m degrees in (e1, e2); face vertex i takes corner m0 + i,
    // the cyclic offset nearest the vertices' own angles (a skewed face has no clean quadrants).
    int best_m0 = 0;
    double best_cost = 1e300;
    for (int m0 = 0; m0 < 4; ++m0) {
        double cost = 0;
        for (int i = 0; i < 4; ++i) {
            const double theta = pmath::atan2(glm::dot(p[i] - c, e2), glm::dot(p[i] - c, e1));
            const double d = std::remainder(theta - radians(45.0 + 90.0 * (m0 + i)), 2.0 * M_PI);
            cost += d * d;
        }
        if (cost < best_cost) best_cost = cost, best_m0 = m0;
    }
    std::array<glm::dvec3, 4> pos;
    for (int i = 0; i < 4; ++i) {
        const double phi = radians(45.0 + 90.0 * (best_m0 + i));
        pos[i] = c1 + half_diag * (pmath::cos(phi) * e1 + pmath::sin(phi) * e2);
    }
    if (std::min({pos[0].y, pos[1].y, pos[2].y, pos[3].y}) < 0) return;

    // Heading: the parent's axis turned toward the face normal by `angle`.
    glm::dvec3 n_perp = safe_normalize(n - axis * glm::dot(n, axis), n);
    glm::dvec3 heading = pmath::cos(radians(angle)) * axis + pmath::sin(radians(angle)) * n_perp;

    const double parent_radius_here = parent_r;
    std::array<FaceHandle, 4> sides;
    Ring b = extrude_face(tm, f, a, pos, sides);
    tm.limbs[parent_index].sides[4 * s + j] = FaceHandle();  // f is the branch's cap now

    Limb L;
    L.key = key;
    L.level = level;
    L.parent = parent_index;
    L.parent_segment = s;
    L.rings = {a, b};
    L.sides.assign(sides.begin(), sides.end());
    L.centers = {c, c1};
    L.radii = {parent_radius_here, half_diag};
    L.top = f;
    L.direction = n;
    L.heading = safe_normalize(heading, n);
    L.length = first_length;
    tm.limbs.push_back(std::move(L));

    StepParams sp{&bp.extrude_length,   &bp.twist,        &bp.taper,          &bp.wobble,
                  bp.tropism.direction, tropism_strength, bp.tropism.increase};
    StopRule stop;
    stop.max_steps = max_steps - 1;
    stop.max_length = max_length;
    grow_limb(tm, static_cast<int>(tm.limbs.size()) - 1, sp, stop, rng);
}

}  // namespace

void grow_branches(TreeMesh& tm, const BranchParams& bp, int level, uint64_t seed) {
    if (!bp.enabled) return;
    // Per-tree draws of this level, from their own stream.
    Rng tree_rng = make_rng(seed, Purpose::kTree, static_cast<uint64_t>(level));
    const double min_height = sample(bp.min_height, tree_rng);
    const double max_height = sample(bp.max_height, tree_rng);
    const double probability = sample(bp.probability, tree_rng);
    const int n_limbs = static_cast<int>(tm.limbs.size());
    for (int li = 0; li < n_limbs; ++li) {
        if (tm.limbs[li].level != level - 1) continue;
        const int segments = static_cast<int>(tm.limbs[li].rings.size()) - 1;
        for (int s = 0; s < segments; ++s) {
            double at = position_along(tm.limbs[li], s);
            bool eligible = at >= min_height && at <= max_height;
            // Where the branch starts within the eligible span, 0 at its lowest point.
            const double t =
                max_height > min_height
                    ? std::clamp((at - min_height) / (max_height - min_height), 0.0, 1.0)
                    : 0.0;
            const double length_scale =
                bp.length_at_base + (bp.length_at_top - bp.length_at_base) * t;
            for (int j = 0; j < 4; ++j) {
                uint64_t key = hash_keys(tm.limbs[li].key, static_cast<uint64_t>(level),
                                         static_cast<uint64_t>(s), static_cast<uint64_t>(j));
                Rng decide = make_rng(seed, Purpose::kBranchDecide, key);
                if (eligible && rand1(decide) < probability)
                    sprout(tm, li, s, j, level, key, bp, length_scale, seed);
            }
        }
    }
}

}  // namespace pleinair
