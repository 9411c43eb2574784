// Surface strokes: sections, clusters, displacement, normals and fade thresholds (IV.7).
#include "generators/surface_strokes.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <numeric>

#include "generators/rng.h"
#include "shading/portable_math.h"

namespace pleinair {

namespace {

// Labels spread evenly over (0, 1) in emission order, then scattered by a stride coprime with
// the count, so neighbours get unrelated noise.
struct Labeller {
    size_t total, stride, next = 0;
    explicit Labeller(size_t n) : total(std::max<size_t>(n, 1)) {
        stride = total > 2 ? (total / 2 + 1) | 1u : 1;
        while (total > 1 && std::gcd(stride, total) != 1) stride += 2;
    }
    float operator()() { return at(next++); }
    // The label of the idx-th particle in emission order.
    float at(size_t idx) const {
        return static_cast<float>((((idx * stride) % total) + 0.5) / static_cast<double>(total));
    }
};

// One particle at (pos, n) on the surface, drawing its displacement, random normal and fade
// from `rng` (always the same number of draws, so streams stay aligned).
void emit_one(Rng& rng, const SurfaceStrokeParams& p, const glm::vec3& pos, const glm::vec3& n,
              glm::vec2 uv, float label, SurfaceParticles& out) {
    const double H = std::max(p.displacement_height, 0.0);
    double d = rand_range(rng, -H, H);
    float h = H > 0 ? static_cast<float>((d + H) / (2 * H)) : 0.5f;
    if (!(H > 0)) d = 0;
    // Uniform on the sphere: z uniform in [-1, 1], angle uniform.
    double z = rand_range(rng, -1.0, 1.0), a = rand_range(rng, 0.0, 2 * M_PI);
    double r = std::sqrt(std::max(0.0, 1 - z * z));
    glm::vec3 rn(static_cast<float>(r * pmath::cos(a)), static_cast<float>(r * pmath::sin(a)),
                 static_cast<float>(z));
    double fade_draw = rand1(rng), len_draw = rand_gaussian(rng);
    out.position.push_back(pos + n * static_cast<float>(d));
    out.normal_code.push_back(encode_unit(n));
    out.random_code.push_back(encode_unit(glm::normalize(rn)));
    out.uv_code.push_back(encode_unorm(uv.x) | (static_cast<uint32_t>(encode_unorm(uv.y)) << 16));
    out.height_code.push_back(encode_unorm(h));
    out.material.push_back(static_cast<uint16_t>(p.material));
    out.label.push_back(label);
    if (h > p.detail_threshold) {
        // Detail: fades over [begin, begin + len] inside the distance range 0..1.
        double len = std::clamp(p.fade_length + p.fade_length_var * len_draw,
                                std::max(p.min_fade_length, 1e-3), 1.0);
        double begin = fade_draw * (1 - len);
        const auto b = static_cast<uint32_t>(std::floor(begin * 16384.0));
        const auto e = static_cast<uint32_t>(std::ceil((begin + len) * 16384.0));
        out.fade_code.push_back(b | (std::min(e, 16384u) << 16));
    } else {
        // Base strokes never fade: they would open holes in the surface.
        out.fade_code.push_back((2u * 16384u) | ((3u * 16384u) << 16));
    }
}

}  // namespace

uint32_t encode_unit(const glm::vec3& n) {
    const float l1 = std::abs(n.x) + std::abs(n.y) + std::abs(n.z);
    if (!(l1 > 0.0f) || !std::isfinite(l1)) return encode_unit({0, 1, 0});
    float x = n.x / l1, y = n.y / l1;
    if (n.z < 0.0f) {  // fold the lower half over the diagonals
        const float fx = (1.0f - std::abs(y)) * (x >= 0.0f ? 1.0f : -1.0f);
        const float fy = (1.0f - std::abs(x)) * (y >= 0.0f ? 1.0f : -1.0f);
        x = fx, y = fy;
    }
    auto q = [](float v) {
        return static_cast<uint32_t>(
            std::lround((std::clamp(v, -1.0f, 1.0f) * 0.5f + 0.5f) * 65535.0f));
    };
    return q(x) | (q(y) << 16);
}

glm::vec3 decode_unit(uint32_t code) {
    const float x = static_cast<float>(code & 0xffffu) / 65535.0f * 2.0f - 1.0f;
    const float y = static_cast<float>(code >> 16) / 65535.0f * 2.0f - 1.0f;
    glm::vec3 n(x, y, 1.0f - std::abs(x) - std::abs(y));
    const float t = std::max(-n.z, 0.0f);
    n.x += n.x >= 0.0f ? -t : t;
    n.y += n.y >= 0.0f ? -t : t;
    return glm::normalize(n);
}

void emit_surface_strokes(const GridSurface& g, const SurfaceStrokeParams& p, uint64_t seed,
                          uint64_t surface_key, SurfaceParticles& out, const StrokeKeep& keep,
                          int first_row, int end_row) {
    if (g.nu < 2 || g.nv < 2 || p.particle_spans_u < 1 || p.particle_spans_v < 1 ||
        p.particles_per_cluster < 1)
        return;
    const size_t ppc = static_cast<size_t>(p.particles_per_cluster);
    const Labeller label(static_cast<size_t>(p.particle_spans_u) * p.particle_spans_v * ppc);
    first_row = std::max(first_row, 0);
    end_row = end_row < 0 ? p.particle_spans_v : std::min(end_row, p.particle_spans_v);
    out.reserve(out.size() + static_cast<size_t>(std::max(end_row - first_row, 0)) *
                                 static_cast<size_t>(p.particle_spans_u) * ppc);
    for (int sv = first_row; sv < end_row; ++sv)
        for (int su = 0; su < p.particle_spans_u; ++su) {
            Rng rng = make_rng(seed, Purpose::kSurface, surface_key, su, sv);
            const size_t first = (static_cast<size_t>(sv) * p.particle_spans_u + su) * ppc;
            for (size_t k = 0; k < ppc; ++k) {
                double u = (su + rand1(rng)) / p.particle_spans_u;
                double v = (sv + rand1(rng)) / p.particle_spans_v;
                glm::vec3 pos, n;
                eval_grid(g, u, v, pos, n);
                const size_t before = out.size();
                emit_one(rng, p, pos, n, {static_cast<float>(u), static_cast<float>(v)},
                         label.at(first + k), out);
                if (keep && !keep(out, before)) out.truncate(before);
            }
        }
}

void emit_cell_strokes(const std::vector<glm::ivec2>& cells, double cell,
                       const SurfaceStrokeParams& p, uint64_t seed, uint64_t surface_key,
                       const GroundAt& ground, SurfaceParticles& out, bool on_top,
                       const StrokeKeep& keep) {
    if (!(cell > 0) || p.particles_per_cluster < 1) return;
    for (const glm::ivec2& c : cells) {
        const uint64_t cx = static_cast<uint32_t>(c.x), cz = static_cast<uint32_t>(c.y);
        Rng rng = make_rng(seed, Purpose::kSurface, surface_key, cx, cz);
        for (int k = 0; k < p.particles_per_cluster; ++k) {
            const double x = (c.x + rand1(rng)) * cell, z = (c.y + rand1(rng)) * cell;
            // A label in (0, 1) from the stroke's own key (24 bits).
            const uint64_t h = hash_keys(seed, static_cast<uint64_t>(Purpose::kSurface),
                                         surface_key, cx, cz, static_cast<uint64_t>(k));
            const float label = (static_cast<float>(h >> 40) + 0.5f) / 16777216.0f;
            glm::vec3 pos, n;
            const bool there = ground(x, z, pos, n);
            const size_t before = out.size();
            emit_one(rng, p, pos, n, {0.0f, 0.0f}, label, out);  // draws the same either way
            if (!there || (keep && !keep(out, before))) {
                out.truncate(before);
                continue;
            }
            if (!on_top) continue;
            out.height_code[before] = encode_unorm(0.5f + 0.5f * out.height(before));
            out.fade_code[before] = (2u * 16384u) | ((3u * 16384u) << 16);
        }
    }
}

void emit_mesh_strokes(const QuadMesh& mesh, const SurfaceStrokeParams& p, uint64_t seed,
                       uint64_t surface_key, SurfaceParticles& out) {
    if (p.particle_spans_u < 1 || p.particle_spans_v < 1 || p.particles_per_cluster < 1) return;
    Labeller label(mesh.quads.size() * p.particle_spans_u * p.particle_spans_v *
                   static_cast<size_t>(p.particles_per_cluster));
    for (size_t f = 0; f < mesh.quads.size(); ++f) {
        // Each face is a bilinear patch: a 2 x 2 grid the section sampler already knows, laid
        // so the grid's normal faces out of the counter-clockwise quad.
        GridSurface patch;
        patch.nu = patch.nv = 2;
        const glm::uvec4& q = mesh.quads[f];
        patch.positions = {mesh.positions[q[0]], mesh.positions[q[3]], mesh.positions[q[1]],
                           mesh.positions[q[2]]};
        for (int sv = 0; sv < p.particle_spans_v; ++sv)
            for (int su = 0; su < p.particle_spans_u; ++su) {
                Rng rng = make_rng(seed, Purpose::kSurface, surface_key, f, su, sv);
                for (int k = 0; k < p.particles_per_cluster; ++k) {
                    double u = (su + rand1(rng)) / p.particle_spans_u;
                    double v = (sv + rand1(rng)) / p.particle_spans_v;
                    glm::vec3 pos, n;
                    eval_grid(patch, u, v, pos, n);
                    emit_one(rng, p, pos, n, {static_cast<float>(u), static_cast<float>(v)},
                             label(), out);
                }
            }
    }
}

void emit_triangle_strokes(const QuadMesh& mesh, const SurfaceStrokeParams& p, double density,
                           uint64_t seed, uint64_t surface_key, SurfaceParticles& out) {
    if (!(density > 0)) return;
    // Counts first: the labels are spread over the whole mesh's strokes.
    std::vector<uint32_t> count(mesh.quads.size());
    size_t total = 0;
    for (size_t f = 0; f < mesh.quads.size(); ++f) {
        const glm::uvec4& q = mesh.quads[f];
        const glm::dvec3 a(mesh.positions[q[0]]), b(mesh.positions[q[1]]), c(mesh.positions[q[2]]);
        const double expected = 0.5 * glm::length(glm::cross(b - a, c - a)) * density;
        Rng rng = make_rng(seed, Purpose::kSurface, surface_key, f, 0, 0);
        const double whole = std::floor(std::min(expected, 1e6));
        count[f] = static_cast<uint32_t>(whole) + (rand1(rng) < expected - whole ? 1u : 0u);
        total += count[f];
    }
    Labeller label(total);
    out.reserve(out.size() + total);
    for (size_t f = 0; f < mesh.quads.size(); ++f) {
        if (count[f] == 0) continue;
        const glm::uvec4& q = mesh.quads[f];
        const glm::vec3 &a = mesh.positions[q[0]], &b = mesh.positions[q[1]],
                        &c = mesh.positions[q[2]];
        const glm::vec3 cr = glm::cross(b - a, c - a);
        const float len = glm::length(cr);
        const glm::vec3 n = len > 0.0f && std::isfinite(len) ? cr / len : glm::vec3(0, 1, 0);
        Rng rng = make_rng(seed, Purpose::kSurface, surface_key, f, 1, 0);
        for (uint32_t k = 0; k < count[f]; ++k) {
            // Uniform on the triangle: the square root folds the unit square onto it.
            const double r1 = std::sqrt(rand1(rng)), r2 = rand1(rng);
            const glm::vec3 pos = a * static_cast<float>(1 - r1) +
                                  b * static_cast<float>(r1 * (1 - r2)) +
                                  c * static_cast<float>(r1 * r2);
            emit_one(rng, p, pos, n, {static_cast<float>(r1), static_cast<float>(r2)}, label(),
                     out);
        }
    }
}

}  // namespace pleinair
