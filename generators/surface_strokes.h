// The generalized stroke builder (thesis IV.7, Fig. 24): any grid surface becomes a field of
// stroke particles, clustered per (u, v) section, displaced off the surface, with detail strokes
// that fade with distance and base strokes that never do.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <glm/ext/vector_int2.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <vector>

#include "generators/terrain.h"

namespace pleinair {

struct SurfaceStrokeParams {
    int particle_spans_u = 5;
    int particle_spans_v = 5;
    int particles_per_cluster = 5;     // emitted at random inside each section
    double displacement_height = 0.1;  // world units, up or down along the normal
    double detail_threshold =
        0.6;  // normalised height above which a stroke is detail ("Min Out for Fadeoff")
    double fade_length = 0.2;       // distance-value span over which a detail stroke fades
    double fade_length_var = 0.05;  // its gaussian standard deviation
    double min_fade_length = 0.1;   // no detail stroke fades faster than this
    uint32_t material = 0;          // stored in every particle (grass, dirt, rock, ...)
};

// Unit vectors as two 16-bit octahedral coordinates (Cigolle et al. 2014): 4 bytes instead of
// 12, angular error under 1e-4 rad. Values in [0, 1] as 16-bit fixed point in steps of
// 1/65534, so 0, 0.5 and 1 are exact.
uint32_t encode_unit(const glm::vec3& n);
glm::vec3 decode_unit(uint32_t code);
inline uint16_t encode_unorm(float x) {
    const float c = x < 0.0f ? 0.0f : (x > 1.0f ? 1.0f : x);
    return static_cast<uint16_t>(c * 65534.0f + 0.5f);
}
inline float decode_unorm(uint16_t x) { return static_cast<float>(x) / 65534.0f; }

// Struct of arrays, as the raster loop wants (DESIGN.md), packed to 36 bytes a particle: a
// landscape holds millions of them.
struct SurfaceParticles {
    std::vector<glm::vec3> position;    // world
    std::vector<uint32_t> normal_code;  // the surface's ("aggregate") normal, unit
    std::vector<uint32_t> random_code;  // uniform on the sphere, unit
    std::vector<uint32_t> uv_code;      // on the source surface, 0..1 (u low, v high)
    std::vector<uint16_t> height_code;  // displacement, 0 = deepest .. 1 = highest
    std::vector<uint16_t> material;
    std::vector<float> label;  // unique in (0, 1)
    // Distance values where a detail stroke starts to fade and is gone, in 1/16384 (begin
    // rounded down, end up, so no fade gets shorter); base strokes never fade (both > 1).
    std::vector<uint32_t> fade_code;

    glm::vec3 normal(size_t i) const { return decode_unit(normal_code[i]); }
    glm::vec3 random_normal(size_t i) const { return decode_unit(random_code[i]); }
    glm::vec2 uv(size_t i) const {
        return {decode_unorm(static_cast<uint16_t>(uv_code[i] & 0xffffu)),
                decode_unorm(static_cast<uint16_t>(uv_code[i] >> 16))};
    }
    float height(size_t i) const { return decode_unorm(height_code[i]); }
    float fade_begin(size_t i) const {
        return static_cast<float>(fade_code[i] & 0xffffu) / 16384.0f;
    }
    float fade_end(size_t i) const { return static_cast<float>(fade_code[i] >> 16) / 16384.0f; }

    size_t size() const { return position.size(); }
    template <class F>
    void each_array(F&& f) {
        f(position), f(normal_code), f(random_code), f(uv_code), f(height_code), f(material);
        f(label), f(fade_code);
    }
    void reserve(size_t n) {
        each_array([n](auto& a) { a.reserve(n); });
    }
    void truncate(size_t n) {
        each_array([n](auto& a) { a.resize(n); });
    }
    // Appends o's particles [first, first + n), or all of them.
    void append(const SurfaceParticles& o, size_t first = 0, size_t n = ~size_t{0}) {
        n = std::min(n, o.size() - std::min(first, o.size()));
        auto cat = [&](auto& a, const auto& b) {
            a.insert(a.end(), b.begin() + static_cast<std::ptrdiff_t>(first),
                     b.begin() + static_cast<std::ptrdiff_t>(first + n));
        };
        cat(position, o.position), cat(normal_code, o.normal_code);
        cat(random_code, o.random_code), cat(uv_code, o.uv_code);
        cat(height_code, o.height_code), cat(material, o.material), cat(label, o.label);
        cat(fade_code, o.fade_code);
    }
};

// Decides whether the particle just emitted at index `i` stays (it may also change its
// material); dropped particles keep their random draws, so the others do not change.
using StrokeKeep = std::function<bool(SurfaceParticles&, size_t i)>;

// Pure: streams keyed by (seed, surface_key, span u, span v), so one section's strokes do not
// depend on the others or on the span counts elsewhere. Appends to `out` the rows of sections
// [first_row, end_row) (end_row < 0: to the last), so callers may emit bands in parallel and
// concatenate them in order for the same result.
void emit_surface_strokes(const GridSurface& surface, const SurfaceStrokeParams& params,
                          uint64_t seed, uint64_t surface_key, SurfaceParticles& out,
                          const StrokeKeep& keep = {}, int first_row = 0, int end_row = -1);

// Where a world grid cell's strokes stand: the ground's point and unit normal at (x, z), or
// false where there is none (under water).
using GroundAt = std::function<bool(double x, double z, glm::vec3& position, glm::vec3& normal)>;

// Strokes on a world grid of square cells of side `cell` in (x, z), `params.particles_per_cluster`
// in each listed cell, keyed by (seed, surface_key, cell x, cell z): a cell's strokes are the
// same whichever other cells are emitted, so a region can grow without changing the rest. Each
// stroke's label comes from its key. `on_top`: none fades with distance (fade_code as a base
// stroke's) and heights lie in the upper half, as detail strokes on top of the surface's own;
// otherwise they are the surface's own strokes, base and detail, fading as emit_surface_strokes'
// do. `keep`, when given, decides each as emit_surface_strokes' does.
void emit_cell_strokes(const std::vector<glm::ivec2>& cells, double cell,
                       const SurfaceStrokeParams& params, uint64_t seed, uint64_t surface_key,
                       const GroundAt& ground, SurfaceParticles& out, bool on_top = true,
                       const StrokeKeep& keep = {});

// The same over a quad mesh (rocks, banks): every face is a bilinear patch divided into the
// params' spans; streams keyed by (seed, surface_key, face, span u, span v).
void emit_mesh_strokes(const QuadMesh& mesh, const SurfaceStrokeParams& params, uint64_t seed,
                       uint64_t surface_key, SurfaceParticles& out);

// Over a triangle mesh (quads whose last corner repeats the third, as glTF surfaces are read):
// `density` strokes per square world unit on average, each triangle's count its area times the
// density, rounded down, plus one with the chance of the remainder, so large and small
// triangles are covered alike. Uniform over each triangle; streams keyed by (seed,
// surface_key, triangle).
void emit_triangle_strokes(const QuadMesh& mesh, const SurfaceStrokeParams& params, double density,
                           uint64_t seed, uint64_t surface_key, SurfaceParticles& out);

}  // namespace pleinair
