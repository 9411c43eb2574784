// The generalized surface-stroke shader of thesis IV.7 (grass, rock, ground): lighting from a
// blend of aggregate and random normals, deeper strokes darker, separate s and t frequencies
// for base and detail strokes, the vertical edge mask shrunk at crests, deeper sprites larger,
// and materials chosen per particle by noise.
#pragma once

#include <cmath>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "shading/curves.h"
#include "shading/noise.h"
#include "shading/portable_math.h"

namespace pleinair {

struct SurfaceShaderParams {
    float random_normal_weight = 0.3f;  // 0: the surface's normal only; 1: the random one only
    float depth_darken = 0.35f;         // lightness lost by the deepest strokes
    float detail_threshold = 0.6f;      // normalised height above which a stroke is detail
    float base_frequ = 1.5f;            // stroke noise frequency of base strokes
    float detail_frequ_add = 2.5f;      // added for detail strokes
    float base_s_frequ = 1.0f, base_t_frequ = 1.0f;      // s and t factors, base strokes
    float detail_s_frequ = 4.0f, detail_t_frequ = 0.6f;  // grass: thin vertical tufts
    float crest_shrink = 0.8f;   // how much of a sprite's height is lost when seen edge-on
    float inside_growth = 1.0f;  // deepest sprites are 1 + this times the size of top ones
    // Base strokes laid along the ground (issue 27 §4): 0 they stand (the stroke's length up
    // the world's y, as grass's tufts), 1 they lie across the slope, or along lay_azimuth
    // (degrees about +y from +x) where the ground is level.
    float lay = 0.0f;
    float lay_azimuth = 0.0f;
    // Base strokes' length over width, as a factor on the shader's stroke_aspect: a brush drawn
    // long across a near meadow while the tufts keep their shape. 1: as the tufts.
    float base_aspect = 1.0f;
    bool operator==(const SurfaceShaderParams&) const = default;
};

// Peterson and Lee's aggregate normals: the lighting normal leans from the surface's normal
// towards the particle's random one. Opposite normals blending to nothing fall back to the
// surface's.
inline glm::vec3 lighting_normal(const glm::vec3& aggregate, const glm::vec3& random,
                                 float weight) {
    float w = clamp01(weight);
    glm::vec3 n = aggregate * (1.0f - w) + random * w;
    float len = glm::length(n);
    return len > 1e-6f && std::isfinite(len) ? n / len : aggregate;
}

// N.L clamped, then darkened with depth so detail strokes show on top of the strokes below.
inline float surface_lightness(const SurfaceShaderParams& p, float n_dot_l, float height) {
    return clamp01(n_dot_l) * (1.0f - clamp01(p.depth_darken) * (1.0f - clamp01(height)));
}

inline bool is_detail(const SurfaceShaderParams& p, float height) {
    return height > p.detail_threshold;
}

// The direction a base stroke's length takes in the world (unit), from the surface's normal n
// (unit): up the world's y when it stands (lay 0); lying (lay 1), along the ground across its
// fall line, as a brush follows a slope's contour, turning to lay_azimuth where the ground is
// level (within about 10 degrees: the contour of a flat meadow means nothing). Detail strokes
// always stand.
inline glm::vec3 surface_stroke_direction(const SurfaceShaderParams& p, const glm::vec3& n,
                                          float height) {
    const glm::vec3 up(0.0f, 1.0f, 0.0f);
    const float lay = clamp01(p.lay);
    if (!(lay > 0.0f) || is_detail(p, height)) return up;
    const float a = p.lay_azimuth * 0.017453292f;
    // A turn by a about +y takes +x to (cos a, 0, -sin a).
    glm::vec3 along(static_cast<float>(pmath::cos(a)), 0.0f, -static_cast<float>(pmath::sin(a)));
    along -= glm::dot(along, n) * n;        // into the ground's plane
    glm::vec3 contour = glm::cross(n, up);  // across the fall line, |sin slope| long
    const float steep = std::min(glm::length(contour) / 0.17f, 1.0f);
    if (glm::dot(contour, along) < 0.0f) contour = -contour;  // the side nearer the azimuth
    const float cl = glm::length(contour), al = glm::length(along);
    glm::vec3 lie = (cl > 1e-6f ? contour / cl : glm::vec3(0.0f)) * steep +
                    (al > 1e-6f ? along / al : glm::vec3(0.0f)) * (1.0f - steep);
    const glm::vec3 d = up * (1.0f - lay) + lie * lay;
    const float len = glm::length(d);
    return len > 1e-6f && std::isfinite(len) ? d / len : up;
}

// The factor on the shader's stroke_aspect for a stroke at this height: base_aspect for base
// strokes, 1 for detail strokes.
inline float surface_aspect(const SurfaceShaderParams& p, float height) {
    return is_detail(p, height) ? 1.0f : p.base_aspect;
}

// Stroke noise frequencies across (s) and along (t) the stroke.
inline void surface_frequencies(const SurfaceShaderParams& p, float height, float& frequ_s,
                                float& frequ_t) {
    const bool detail = is_detail(p, height);
    const float f = std::max(0.0f, p.base_frequ + (detail ? p.detail_frequ_add : 0.0f));
    frequ_s = f * (detail ? p.detail_s_frequ : p.base_s_frequ);
    frequ_t = f * (detail ? p.detail_t_frequ : p.base_t_frequ);
}

// The fraction of a sprite's height kept at a given |N.V| (Fig. 25): 1 facing the camera,
// 1 - crest_shrink edge-on, so sprites at a hill's crest do not stand above the ridge.
inline float crest_factor(float n_dot_v, float crest_shrink) {
    float facing = clamp01(std::abs(n_dot_v));
    return std::max(1.0f - clamp01(crest_shrink) * (1.0f - facing), 1e-3f);
}

// The vertical sprite coordinate after the crest shrink: the mask is evaluated at t', which
// leaves [0, 1] (mask 0) outside the kept middle band.
inline float crest_t(float t, float factor) { return 0.5f + (t - 0.5f) / factor; }

// Deeper sprites are larger: few of them cover the surface, and detail sits on top.
inline float inside_size(float height, float inside_growth) {
    return 1.0f + std::max(inside_growth, 0.0f) * (1.0f - clamp01(height));
}

// Material by noise over the surface's uv: 0 below the threshold, 1 above (grass and dirt on
// one hillside). frequency in cycles over the surface; offset decorrelates surfaces.
inline int noise_material(float u, float v, float frequency, float threshold, float offset) {
    return noise(u * frequency + offset, v * frequency + 0.5f * offset) > threshold ? 1 : 0;
}

}  // namespace pleinair
