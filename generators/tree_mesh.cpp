// Face extrusion and limb growth on the tree's OpenMesh control mesh.
#include "generators/tree_mesh.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

#include "shading/portable_math.h"

namespace pleinair {

using OpenMesh::FaceHandle;
using OpenMesh::VertexHandle;

namespace {

glm::dvec3 to_glm(const OpenMesh::Vec3d& p) { return {p[0], p[1], p[2]}; }
OpenMesh::Vec3d to_om(const glm::dvec3& p) { return {p.x, p.y, p.z}; }

// Rotation taking unit vector a onto unit vector b, applied to v.
glm::dvec3 rotate_between(const glm::dvec3& v, const glm::dvec3& a, const glm::dvec3& b) {
    glm::dvec3 axis = glm::cross(a, b);
    double s = glm::length(axis), c = glm::dot(a, b);
    if (s < 1e-12) {
        if (c > 0) return v;
        return rotate(v, any_perpendicular(a), M_PI);
    }
    return rotate(v, axis / s, pmath::atan2(s, c));
}

}  // namespace

double radians(double degrees) { return degrees * (M_PI / 180.0); }

glm::dvec3 rotate(const glm::dvec3& v, const glm::dvec3& k, double angle) {
    double c = pmath::cos(angle), s = pmath::sin(angle);
    return v * c + glm::cross(k, v) * s + k * (glm::dot(k, v) * (1.0 - c));
}

glm::dvec3 any_perpendicular(const glm::dvec3& v) { return orthonormal_basis(v).first; }

std::pair<glm::dvec3, glm::dvec3> orthonormal_basis(const glm::dvec3& n) {
    // Duff et al., "Building an Orthonormal Basis, Revisited" (JCGT 2017): branch-free, no
    // square root, continuous except across n.z = 0's sign flip.
    const double sign = std::copysign(1.0, n.z);
    const double a = -1.0 / (sign + n.z);
    const double b = n.x * n.y * a;
    return {{1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x}, {b, sign + n.y * n.y * a, -n.y}};
}

glm::dvec3 safe_normalize(const glm::dvec3& v, const glm::dvec3& fallback) {
    double len = glm::length(v);
    return (len > 1e-300 && std::isfinite(len)) ? v / len : fallback;
}

glm::dvec3 turn_direction(const glm::dvec3& v, double cos_t, double sin_t, double turns) {
    // Rotating v by t about the unit axis a = cos(az) u + sin(az) w (a perpendicular to v)
    // gives v cos t + (a x v) sin t, and a x v = sin(az) u - cos(az) w.
    const auto [u, w] = orthonormal_basis(v);
    double sa, ca;
    pmath::sincos(2.0 * pmath::kPi * turns, sa, ca);
    return safe_normalize(v * cos_t + (sa * u - ca * w) * sin_t, v);
}

glm::dvec3 wobble_direction(const glm::dvec3& v, double degrees, double turns) {
    double s, c;
    pmath::sincos(radians(degrees), s, c);
    return turn_direction(v, c, s, turns);
}

glm::dvec3 apply_tropism(const glm::dvec3& heading, const glm::dvec3& direction, double strength) {
    if (strength <= 0) return heading;
    glm::dvec3 d = safe_normalize(direction, glm::dvec3(0));
    return safe_normalize(heading + strength * d, heading);
}

double tropism_pull(double strength, double increase, double length, double unit) {
    return std::max(0.0, strength + increase * length / unit);
}

TreeMesh::TreeMesh() {
    // Room for a large tree up front: growing OpenMesh's arrays step by step showed in profiles.
    mesh.reserve(2048, 4096, 2048);
}

glm::dvec3 TreeMesh::point(VertexHandle v) const { return to_glm(mesh.point(v)); }

Ring extrude_face(TreeMesh& tm, FaceHandle face, const Ring& a,
                  const std::array<glm::dvec3, 4>& pos, std::array<FaceHandle, 4>& sides) {
    // The face itself moves up to become the new top, and four new quads fill the sides. The
    // connectivity is spliced with the kernel's own operations: delete_face + add_face would
    // search for and re-check what an extrusion already knows, at several times the cost.
    auto& m = tm.mesh;
    OpenMesh::HalfedgeHandle h[4];  // the face's half-edges a_j -> a_j+1
    h[0] = m.halfedge_handle(face);
    while (m.from_vertex_handle(h[0]) != a[0]) h[0] = m.next_halfedge_handle(h[0]);
    for (int j = 1; j < 4; ++j) h[j] = m.next_halfedge_handle(h[j - 1]);

    Ring b;
    OpenMesh::HalfedgeHandle up[4], top[4];  // a_j -> b_j and b_j -> b_j+1
    for (int j = 0; j < 4; ++j) b[j] = m.add_vertex(to_om(pos[j]));
    for (int j = 0; j < 4; ++j) up[j] = m.new_edge(a[j], b[j]);
    for (int j = 0; j < 4; ++j) top[j] = m.new_edge(b[j], b[(j + 1) & 3]);
    for (int j = 0; j < 4; ++j) {
        // Side j = (a_j, a_j+1, b_j+1, b_j): it takes over the face's half-edge a_j -> a_j+1,
        // so the orientation carries over and the surface stays closed.
        const int k = (j + 1) & 3;
        const OpenMesh::HalfedgeHandle loop[4] = {h[j], up[k], m.opposite_halfedge_handle(top[j]),
                                                  m.opposite_halfedge_handle(up[j])};
        sides[j] = m.new_face();
        for (int i = 0; i < 4; ++i) {
            m.set_next_halfedge_handle(loop[i], loop[(i + 1) & 3]);
            m.set_face_handle(loop[i], sides[j]);
        }
        m.set_halfedge_handle(sides[j], h[j]);
    }
    for (int j = 0; j < 4; ++j) {
        m.set_next_halfedge_handle(top[j], top[(j + 1) & 3]);
        m.set_face_handle(top[j], face);
        m.set_halfedge_handle(b[j], top[j]);
    }
    m.set_halfedge_handle(face, top[0]);
    return b;
}

void grow_limb(TreeMesh& tm, int limb_index, const StepParams& sp, const StopRule& stop, Rng& rng) {
    for (int step = 0; step < stop.max_steps; ++step) {
        // Every step draws the same numbers in the same order, used or not.
        const double wobble = sample(*sp.wobble, rng);
        const double azimuth = rand1(rng);
        const double len = sample(*sp.extrude_length, rng) * tm.unit;
        const double twist = sample(*sp.twist, rng);
        const double taper = sample(*sp.taper, rng);

        Limb& L = tm.limbs[limb_index];
        if (L.length >= stop.max_length || L.centers.back().y >= stop.max_height) return;
        const Ring ring = L.rings.back();
        const glm::dvec3 c = L.centers.back();
        const double r = L.radii.back();

        glm::dvec3 heading = wobble_direction(L.heading, wobble, azimuth);
        const double pull =
            tropism_pull(sp.tropism_strength, sp.tropism_increase, L.length, tm.unit);
        heading = apply_tropism(heading, sp.tropism_direction, pull);

        // Limit the turn so the inner side of the new segment cannot fold back through the
        // previous ring: tan(turn) * r < len.
        glm::dvec3 dir = heading;
        double angle = pmath::acos(std::clamp(glm::dot(L.direction, heading), -1.0, 1.0));
        double max_turn = pmath::atan2(0.8 * len, r);
        if (angle > max_turn) {
            glm::dvec3 axis = glm::cross(L.direction, heading);
            double s = glm::length(axis);
            axis = s > 1e-12 ? axis / s : any_perpendicular(L.direction);
            dir = glm::normalize(rotate(L.direction, axis, max_turn));
        }

        double new_r = taper * r;
        bool last = false;
        if (new_r <= tm.min_radius) {
            new_r = std::min(tm.min_radius, r);
            last = true;
        }

        // The face turns by the full twist, but new vertex j is the image of old vertex j - k,
        // k the nearest whole number of quarter turns: it lands within 45 degrees of old vertex
        // j, which it joins. Side quads then never cross the axis, even at 180 degrees a step.
        const long k = std::lround(twist / 90.0);
        const double theta = radians(twist);
        const glm::dvec3 c_new = c + dir * len;
        std::array<glm::dvec3, 4> pos;
        for (int j = 0; j < 4; ++j) {
            int src = static_cast<int>(((j - k) % 4 + 4) % 4);
            glm::dvec3 v = tm.point(ring[src]) - c;
            v = rotate_between(v, L.direction, dir);
            v = rotate(v, dir, theta);
            v -= dir * glm::dot(v, dir);  // keep the new face planar, perpendicular to dir
            pos[j] = c_new + v * (new_r / r);
        }
        // Growth never enters the ground (y = 0 in the tree's frame): the limb stops instead.
        if (std::min({pos[0].y, pos[1].y, pos[2].y, pos[3].y}) < 0) return;

        std::array<FaceHandle, 4> sides;
        Ring b = extrude_face(tm, L.top, ring, pos, sides);

        glm::dvec3 centroid(0);
        for (const auto& p : pos) centroid += p * 0.25;
        double radius = 0;
        for (const auto& p : pos) radius += 0.25 * glm::length(p - centroid);

        L.rings.push_back(b);
        L.sides.insert(L.sides.end(), sides.begin(), sides.end());
        L.centers.push_back(centroid);
        L.radii.push_back(std::min(radius, r));
        L.direction = dir;
        L.heading = heading;
        L.length += len;
        if (last) return;
    }
}

QuadMesh to_quad_mesh(const TreeMesh& tm) {
    // Extrusion never deletes: every face and vertex of the kernel is live.
    const auto& m = tm.mesh;
    QuadMesh q;
    q.positions.reserve(m.n_vertices());
    for (size_t i = 0; i < m.n_vertices(); ++i)
        q.positions.push_back(glm::vec3(tm.point(VertexHandle(static_cast<int>(i)))));
    q.quads.reserve(m.n_faces());
    for (size_t i = 0; i < m.n_faces(); ++i) {
        FaceHandle f(static_cast<int>(i));
        glm::uvec4 quad;
        auto h = m.halfedge_handle(f);
        for (int c = 0; c < 4; ++c) {
            quad[c] = static_cast<uint32_t>(m.from_vertex_handle(h).idx());
            h = m.next_halfedge_handle(h);
        }
        q.quads.push_back(quad);
    }
    return q;
}

}  // namespace pleinair
