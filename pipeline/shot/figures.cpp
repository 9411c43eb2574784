// Figures to strokes: the generator's touches encoded as surface particles (normal, random
// normal, label) beside their widths and colours, the shape a particle file takes.
#include "pipeline/shot/figures.h"

#include <cmath>
#include <glm/geometric.hpp>

#include "generators/rng.h"

namespace pleinair {

ImportedParticles figure_particles(const FigureDesc& f, const glm::vec3& sun) {
    FigureParams p = f.params;
    p.skin = srgb_to_linear(f.skin), p.hair = srgb_to_linear(f.hair);
    p.top = srgb_to_linear(f.top), p.bottom = srgb_to_linear(f.bottom);
    const FigureTouches t = generate_figure(p, f.seed, f.position);
    ImportedParticles out;
    SurfaceParticles& s = out.strokes;
    s.reserve(t.size());
    for (size_t i = 0; i < t.size(); ++i) {
        s.position.push_back(t.position[i]);
        const glm::vec3 n = std::isfinite(t.normal[i].x) ? t.normal[i] : sun;
        s.normal_code.push_back(encode_unit(n));
        const uint64_t h = hash_keys(f.seed, static_cast<uint64_t>(Purpose::kFigure), 1u << 20, i);
        Rng rng = make_rng(f.seed, Purpose::kFigure, 1u << 21, i);
        push_stroke_keys(s, h, rng);
        s.uv_code.push_back(0);
        s.height_code.push_back(encode_unorm(1.0f));
        s.material.push_back(static_cast<uint16_t>(f.material));
        s.fade_code.push_back((2u * 16384u) | ((3u * 16384u) << 16));  // never fades
        out.width.push_back(t.width[i]);
        out.color.push_back(figure_color(p, t.part[i]));
    }
    return out;
}

}  // namespace pleinair
