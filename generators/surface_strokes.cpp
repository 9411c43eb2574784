// Surface strokes: sections, clusters, displacement, normals and fade thresholds (IV.7).
#include "generators/surface_strokes.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <numeric>

#include "generators/rng.h"

namespace pleinair {

void emit_surface_strokes(const GridSurface& g, const SurfaceStrokeParams& p, uint64_t seed,
                          uint64_t surface_key, SurfaceParticles& out) {
    if (g.nu < 2 || g.nv < 2 || p.particle_spans_u < 1 || p.particle_spans_v < 1 ||
        p.particles_per_cluster < 1)
        return;
    const double H = std::max(p.displacement_height, 0.0);
    const size_t first = out.size();
    const size_t total = static_cast<size_t>(p.particle_spans_u) * p.particle_spans_v *
                         static_cast<size_t>(p.particles_per_cluster);
    // Labels spread evenly over (0, 1) in emission order, then scattered by a stride coprime
    // with the count, so neighbours get unrelated noise.
    size_t stride = total > 2 ? (total / 2 + 1) | 1u : 1;
    while (total > 1 && std::gcd(stride, total) != 1) stride += 2;
    for (int sv = 0; sv < p.particle_spans_v; ++sv)
        for (int su = 0; su < p.particle_spans_u; ++su) {
            Rng rng = make_rng(seed, Purpose::kSurface, surface_key, su, sv);
            for (int k = 0; k < p.particles_per_cluster; ++k) {
                double u = (su + rand1(rng)) / p.particle_spans_u;
                double v = (sv + rand1(rng)) / p.particle_spans_v;
                glm::vec3 pos, n;
                eval_grid(g, u, v, pos, n);
                double d = H > 0 ? rand_range(rng, -H, H) : 0.0;
                float h = H > 0 ? static_cast<float>((d + H) / (2 * H)) : 0.5f;
                // Uniform on the sphere: z uniform in [-1, 1], angle uniform.
                double z = rand_range(rng, -1.0, 1.0), a = rand_range(rng, 0.0, 2 * M_PI);
                double r = std::sqrt(std::max(0.0, 1 - z * z));
                glm::vec3 rn(static_cast<float>(r * std::cos(a)),
                             static_cast<float>(r * std::sin(a)), static_cast<float>(z));
                double fade_draw = rand1(rng), len_draw = rand_gaussian(rng);
                out.position.push_back(pos + n * static_cast<float>(d));
                out.normal.push_back(n);
                out.random_normal.push_back(glm::normalize(rn));
                out.uv.push_back({static_cast<float>(u), static_cast<float>(v)});
                out.height.push_back(h);
                out.material.push_back(p.material);
                size_t idx = out.label.size() - first;
                out.label.push_back(static_cast<float>((((idx * stride) % total) + 0.5) / total));
                if (h > p.detail_threshold) {
                    // Detail: fades over [begin, begin + len] inside the distance range 0..1.
                    double len = std::clamp(p.fade_length + p.fade_length_var * len_draw,
                                            std::max(p.min_fade_length, 1e-3), 1.0);
                    double begin = fade_draw * (1 - len);
                    out.fade_begin.push_back(static_cast<float>(begin));
                    out.fade_end.push_back(static_cast<float>(begin + len));
                } else {
                    // Base strokes never fade: they would open holes in the surface.
                    out.fade_begin.push_back(2.0f);
                    out.fade_end.push_back(3.0f);
                }
            }
        }
}

}  // namespace pleinair
