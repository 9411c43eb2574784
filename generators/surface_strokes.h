// The generalized stroke builder (thesis IV.7, Fig. 24): any grid surface becomes a field of
// stroke particles, clustered per (u, v) section, displaced off the surface, with detail strokes
// that fade with distance and base strokes that never do.
#pragma once

#include <cstdint>
#include <functional>
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

// Struct of arrays, as the raster loop wants (DESIGN.md).
struct SurfaceParticles {
    std::vector<glm::vec3> position;       // world
    std::vector<glm::vec3> normal;         // the surface's ("aggregate") normal, unit
    std::vector<glm::vec3> random_normal;  // uniform on the sphere, unit
    std::vector<glm::vec2> uv;             // on the source surface, 0..1
    std::vector<float> height;             // displacement, 0 = deepest .. 1 = highest
    std::vector<uint32_t> material;
    std::vector<float> label;       // unique in (0, 1)
    std::vector<float> fade_begin;  // distance value where a detail stroke starts to fade
    std::vector<float> fade_end;    // ... and is gone; > 1 for strokes that never fade
    size_t size() const { return position.size(); }
    void reserve(size_t n) {
        position.reserve(n), normal.reserve(n), random_normal.reserve(n), uv.reserve(n);
        height.reserve(n), material.reserve(n), label.reserve(n), fade_begin.reserve(n);
        fade_end.reserve(n);
    }
    void append(const SurfaceParticles& o) {
        auto cat = [](auto& a, const auto& b) { a.insert(a.end(), b.begin(), b.end()); };
        cat(position, o.position), cat(normal, o.normal), cat(random_normal, o.random_normal);
        cat(uv, o.uv), cat(height, o.height), cat(material, o.material), cat(label, o.label);
        cat(fade_begin, o.fade_begin), cat(fade_end, o.fade_end);
    }
    void truncate(size_t n) {
        position.resize(n), normal.resize(n), random_normal.resize(n), uv.resize(n);
        height.resize(n), material.resize(n), label.resize(n), fade_begin.resize(n);
        fade_end.resize(n);
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

// The same over a quad mesh (rocks, banks): every face is a bilinear patch divided into the
// params' spans; streams keyed by (seed, surface_key, face, span u, span v).
void emit_mesh_strokes(const QuadMesh& mesh, const SurfaceStrokeParams& params, uint64_t seed,
                       uint64_t surface_key, SurfaceParticles& out);

}  // namespace pleinair
