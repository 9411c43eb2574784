// The painterly stroke shader of thesis IV.4 to IV.6, shared by leaf and bark strokes: lighting
// from the particle's place in the tree, the shadow remap, colour picked by lightness, the noise
// stroke mask under a rounded edge mask, tint and atmospheric perspective.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "shading/color.h"
#include "shading/curves.h"
#include "shading/noise.h"
#include "shading/portable_math.h"

namespace pleinair {

// Every parameter of the thesis's Fig. 21 under its name, plus the few the thesis fixed in code
// (marked "ours"). Defaults are Fig. 21's values where it shows one. Documented for users in
// pipeline/input/shader_io.cpp, where they are parsed.
struct StrokeShaderParams {
    // Lightness ranges of the palette's dark, mid and light splines (IV.5).
    float dark_cutoff_start = 0.30f;
    float dark_cutoff_end = 0.40f;
    float mid_cutoff_start = 0.60f;
    float mid_cutoff_end = 0.68f;
    float shadow_bias = 0.40f;
    // Stroke mask (IV.4.4).
    float stroke_fullness = 0.80f;
    float stroke_feather_min = 0.40f;
    float stroke_feather_max = 0.60f;
    float max_stroke_opacity = 0.90f;
    float stroke_frequ = 1.5f;  // ours: noise frequency before the two factors below
    float center_frequ_factor = 5.0f;
    float lightness_frequ_factor = 5.0f;
    float s_frequ_scale = 1.0f;  // ours (IV.7 has it for grass): frequency across the stroke
    float t_frequ_scale = 1.0f;  // ... and along it
    // Colour noise inside a stroke.
    float sub_stroke_frequ = 8.0f;
    float sub_stroke_amt = 0.12f;  // ours: lightness swing of that noise
    // Ours: that noise's frequency across (s) and along (t) the stroke over sub_stroke_frequ; a
    // high s and a low t draw streaks along the stroke, as a brush's bristles do.
    float sub_stroke_s_scale = 1.0f, sub_stroke_t_scale = 1.0f;
    // Lighting modifiers (IV.4.1): outer leaves lighter, inner darker, through gains.
    float outer_brighten = 0.35f;  // ours
    float inner_darken = 0.45f;    // ours
    float center_gain = 0.65f;     // ours: gain on the distance from the centre
    float branch_gain = 0.5f;      // ours: gain on the distance along the implied branch
    // Per-tree tint.
    float unique_tint_amt = 0.02f;
    Color tint_color1{1.0f, 0.85f, 0.55f};
    Color tint_color2{0.55f, 0.7f, 0.9f};
    // Atmospheric perspective (IV.6). Colours here are sRGB, as in preset files.
    float dist_curve_bias = 0.10f;
    Color dist_hue_color{0.55f, 0.65f, 0.8f};
    float dist_hue_strength = 0.03f;
    float dist_sat_limiter = 0.0f;
    float dist_value_min = 0.20f;
    float dist_value_max = 0.78f;
    // Sprite shape (ours).
    float sprite_size = 0.3f;    // world size of a stroke, in the tree's units
    float size_jitter = 0.25f;   // relative, drawn from the label
    float stroke_aspect = 1.0f;  // length / width; bark strokes are long
    float angle_jitter = 40.0f;  // degrees, drawn from the label
    // Degrees from upright, counter-clockwise on screen, of the strokes that follow no surface or
    // limb (leaves): 90 lays them flat, as Corot's foliage "a mass of horizontal strokes".
    float stroke_angle = 0.0f;
    // Degrees below horizontal past which a leaf's implied branch falls steeply enough that its
    // stroke runs down along it instead (a willow's curtains); over 90: none does.
    float hanging_slope = 91.0f;
    // The crown seen up close (ours, issue 13 §4); 0 leaves the thesis's crown as it is.
    float sun_side = 0.0f;     // lights gather on the crown's sunlit side, darks on the other
    float edge_shrink = 0.0f;  // strokes smaller towards the crown's edge
    float edge_break = 0.0f;   // ... and broken into dabs there
    float holes = 0.0f;        // share of the outer crown opened into holes the sky shows through
    float hole_frequ = 0.35f;  // frequency of those holes, per tree unit
    bool operator==(const StrokeShaderParams&) const = default;
};

// IV.4.1: N.L clamped, then outer leaves brightened and inner ones darkened through gains of
// the stored distances. The darkening stands for self-shadowing by outer leaves that fade away
// with distance (IV.6), so it weakens as lod_distance goes to 1.
// The outer term is the same under any light, so whoever lights one leaf many times (the sun's
// shadow casters) keeps it: stroke_outer, then stroke_lightness_outer.
inline float stroke_outer(const StrokeShaderParams& p, float center_distance,
                          float branch_distance) {
    return 0.5f * (gain(center_distance, p.center_gain) + gain(branch_distance, p.branch_gain));
}

inline float stroke_lightness_outer(const StrokeShaderParams& p, float n_dot_l, float outer,
                                    float lod_distance) {
    float l = clamp01(n_dot_l);
    l += (1.0f - l) * clamp01(p.outer_brighten) * outer * outer;
    float inner = 1.0f - outer;
    l *= 1.0f - clamp01(p.inner_darken) * inner * inner * (1.0f - clamp01(lod_distance));
    return clamp01(l);
}

inline float stroke_lightness(const StrokeShaderParams& p, float n_dot_l, float center_distance,
                              float branch_distance, float lod_distance) {
    return stroke_lightness_outer(p, n_dot_l, stroke_outer(p, center_distance, branch_distance),
                                  lod_distance);
}

// IV.4.2: a shadow multiplier in 0..1 (1 = lit) remapped to 0.5..1 so shadows never go black,
// then biased; bias 0.5 leaves it alone, lower darkens, higher lightens.
inline float shadow_remap(float shadow, float shadow_bias) {
    return bias(0.5f + 0.5f * clamp01(shadow), shadow_bias);
}

// IV.4.4: strokes get smaller (higher frequency) away from the centre and in the light.
inline float stroke_frequency(const StrokeShaderParams& p, float center_distance, float lightness) {
    return std::max(0.0f, p.stroke_frequ + p.center_frequ_factor * clamp01(center_distance) +
                              p.lightness_frequ_factor * clamp01(lightness));
}

// IV.4.4, Fig. 20: 1 in the middle of the sprite, 0 on its border, rounded by sin; fullness is
// the bias that pushes the shape out to the border (0.8) or shrinks it (0.2).
inline float edge_mask(float s, float t, float stroke_fullness) {
    constexpr float kPi = 3.14159265358979f;
    // Each factor clamped: sin(pi * 1.0f) is -8.7e-8 in float, and two of them multiply to a
    // positive number whose bias is far from 0.
    float e = clamp01(pmath::sin(kPi * clamp01(s))) * clamp01(pmath::sin(kPi * clamp01(t)));
    return bias(e, stroke_fullness);
}

// edge_mask as the product of two tabulated profiles: bias(sin(pi s) sin(pi t), b) equals
// sin(pi s)^k sin(pi t)^k with k = log(b) / log(0.5), so one 1D table of sin(pi u)^k serves
// both axes. The "edge_lut" accuracy setting; its error is measured by `pleinair bench
// accuracy` and bounded in the tests.
struct EdgeTable {
    static constexpr int kSize = 256;
    std::array<float, kSize + 2> v{};  // guard entry: index kSize + 1 is valid
};

inline EdgeTable make_edge_table(float stroke_fullness) {
    EdgeTable t;
    constexpr float kPi = 3.14159265358979f;
    for (int i = 0; i <= EdgeTable::kSize; ++i)
        t.v[i] = bias(clamp01(pmath::sin(kPi * static_cast<float>(i) / EdgeTable::kSize)),
                      stroke_fullness);
    t.v[0] = t.v[EdgeTable::kSize] = 0.0f;
    t.v[EdgeTable::kSize + 1] = 0.0f;
    return t;
}

// The profile has an infinite slope at the border when b > 0.5 (sin^k with k < 1), which no
// linear table follows: the first and last cells are evaluated exactly.
inline float edge_profile(const EdgeTable& t, float u, float stroke_fullness) {
    float x = clamp01(u) * EdgeTable::kSize;
    int i = static_cast<int>(x);
    if (i == 0 || i >= EdgeTable::kSize - 1) {
        constexpr float kPi = 3.14159265358979f;
        return bias(clamp01(pmath::sin(kPi * clamp01(u))), stroke_fullness);
    }
    float f = x - static_cast<float>(i);
    return t.v[i] + f * (t.v[i + 1] - t.v[i]);
}

inline float edge_mask(const EdgeTable& t, float s, float t_, float stroke_fullness) {
    return edge_profile(t, s, stroke_fullness) * edge_profile(t, t_, stroke_fullness);
}

// The stroke's opacity from its noise value and edge mask.
inline float stroke_opacity(const StrokeShaderParams& p, float noise_value, float edge) {
    float a = smoothstep(p.stroke_feather_min, p.stroke_feather_max, noise_value * edge);
    return std::min(a, clamp01(p.max_stroke_opacity));
}

// IV.6: depth between the near and far distances as 0..1, curved by dist_curve_bias (small
// values keep the near range clear and let the effect grow with distance).
inline float distance_value(float depth, float near_distance, float far_distance,
                            float curve_bias) {
    float d = color_detail::unit_in(depth, near_distance, far_distance);
    return bias(d, curve_bias);
}

// A tree id as 0..1, scattered so neighbouring ids get unrelated tints.
inline float tree_hash01(uint32_t id) {
    uint32_t h = id * 0x9E3779B1u;
    h ^= h >> 16;
    h *= 0x85EBCA6Bu;
    h ^= h >> 13;
    return static_cast<float>(h >> 8) * (1.0f / 16777216.0f);
}

// A 0..1 value from a label, for size and angle jitter that differ from the noise offsets.
inline float label_hash(float label, uint32_t salt) {
    uint32_t bits;
    static_assert(sizeof bits == sizeof label);
    std::memcpy(&bits, &label, sizeof bits);
    return tree_hash01(bits ^ (salt * 0x27d4eb2fu));
}

// A stroke's size factor drawn from its label: its sprite and its shadow caster share it.
inline float stroke_size_jitter(const StrokeShaderParams& p, float label) {
    return 1.0f + p.size_jitter * (2.0f * label_hash(label, 1) - 1.0f);
}

// A stroke's turn in radians drawn from its label: its sprite and its shadow caster share it.
inline double stroke_angle_jitter(const StrokeShaderParams& p, float label) {
    return (label_hash(label, 2) - 0.5) * p.angle_jitter * M_PI / 180.0;
}

// The crown up close (issue 13 §4), from what a leaf particle carries: its lightness scaled by
// which side of the crown it is on (side: 1 facing the sun, 0 away, from the direction from the
// crown's centre), so the lights gather where Corot put them.
inline float crown_side_lightness(const StrokeShaderParams& p, float lightness, float side) {
    return clamp01(lightness * (1.0f + clamp01(p.sun_side) * (1.8f * clamp01(side) - 0.9f)));
}

// Its stroke's size factor: smaller towards the crown's edge.
inline float crown_edge_size(const StrokeShaderParams& p, float center_distance) {
    const float d = clamp01(center_distance);
    return 1.0f - clamp01(p.edge_shrink) * d * d;
}

// The share of its coverage kept (a dry-brush fade): more broken towards the edge.
inline float crown_edge_fade(const StrokeShaderParams& p, float center_distance) {
    return 1.0f - clamp01(p.edge_break) * smoothstep(0.5f, 1.0f, center_distance);
}

// Whether the leaf at tree-local `position` lies in a hole of the crown: low-frequency noise
// over the tree under a threshold that grows from none at half the centre distance to `holes`
// at the edge, so holes cluster and open outwards, the same in every frame.
inline bool crown_hole(const StrokeShaderParams& p, float px, float py, float pz,
                       float center_distance) {
    if (!(p.holes > 0.0f)) return false;
    const float f = p.hole_frequ;
    const float n = noise(px * f + 17.0f, py * f + 3.0f, pz * f + 41.0f);
    // The noise lies mostly within 0.2..0.8: a threshold of 0.2 + 0.6 x removes about a
    // share x of the leaves.
    const float share = clamp01(p.holes) * smoothstep(0.5f, 1.0f, center_distance);
    return share > 0.0f && n < 0.2f + 0.6f * share;
}

// Everything of a stroke that is constant over its sprite, computed once per sprite.
struct StrokeConstants {
    float lightness = 0;  // after lighting modifiers and shadow
    float frequ_s = 1, frequ_t = 1;
    float offset_s = 0, offset_t = 0;  // from the label: every sprite's noise differs
    float sub_frequ_s = 0, sub_frequ_t = 0, sub_amt = 0;
    Color tint{0.0f};     // already multiplied by unique_tint_amt
    float tint_keep = 1;  // 1 - unique_tint_amt
    Color hue{0.0f};      // dist_hue_color * (dist_hue_strength * d)
    float hue_keep = 1;
    float max_saturation = 1;
    float value_lo = 0, value_hi = 1;  // linear
    bool atmosphere = false;
    // A particle's own colour (imported particles), linear, over the luminance of the palette's
    // middle colour: painted times the palette colour's luminance, it is the file's colour at
    // mid lightness, darker in shade (never black) and lighter in the light. own_amount 0 keeps
    // the palette's.
    Color own{0.0f};
    float own_amount = 0;
    // What the stroke mirrors (still water, pipeline/frame/reflection.h), linear and premultiplied
    // by its share: the palette's colour times mirror_keep, plus this. Black and 1: no mirror.
    Color mirror{0.0f};
    float mirror_keep = 1;
    // The mass's value the touch is laid in at (linear luminance) and the share of the way its
    // colour goes there, last, keeping its hue (pipeline/frame/distance_mass.h). 0: its own.
    float key_luminance = 0, key_amount = 0;
};

// What the stroke mask's noise reads of StrokeConstants, for whoever keeps many strokes around
// (shadow casters) and needs no colour.
struct StrokeNoise {
    float frequ_s = 1, frequ_t = 1;
    float offset_s = 0, offset_t = 0;
};

// A stroke's noise at its lightness: IV.4.4's frequency, and offsets far apart in label space,
// kept below 256 (the lattice period), so every stroke's noise differs.
inline StrokeNoise stroke_noise_for(const StrokeShaderParams& p, float lightness,
                                    float center_distance, float label) {
    const float f = stroke_frequency(p, center_distance, lightness);
    StrokeNoise n;
    n.frequ_s = f * p.s_frequ_scale;
    n.frequ_t = f * p.t_frequ_scale;
    n.offset_s = 211.37f * clamp01(label);
    n.offset_t = 97.91f * clamp01(label) + 13.0f;
    return n;
}

// The per-sprite part of the shader. `shadow` is 1 when lit (the still renderer has no shadow
// rays yet), `d` the atmospheric distance value (distance_value), `tree_id` seeds the tint.
inline StrokeConstants stroke_constants(const StrokeShaderParams& p, float n_dot_l,
                                        float center_distance, float branch_distance, float label,
                                        uint32_t tree_id, float shadow, float d, float lod_distance,
                                        bool use_tint, bool use_atmosphere) {
    StrokeConstants k;
    float l = stroke_lightness(p, n_dot_l, center_distance, branch_distance, lod_distance);
    if (shadow < 1.0f) l *= shadow_remap(shadow, p.shadow_bias);
    k.lightness = l;
    const StrokeNoise n = stroke_noise_for(p, l, center_distance, label);
    k.frequ_s = n.frequ_s, k.frequ_t = n.frequ_t;
    k.offset_s = n.offset_s, k.offset_t = n.offset_t;
    k.sub_frequ_s = p.sub_stroke_frequ * p.sub_stroke_s_scale;
    k.sub_frequ_t = p.sub_stroke_frequ * p.sub_stroke_t_scale;
    k.sub_amt = p.sub_stroke_amt;
    if (use_tint) {
        Color t = srgb_to_linear(mix(p.tint_color1, p.tint_color2, tree_hash01(tree_id)));
        float a = clamp01(p.unique_tint_amt);
        k.tint = t * a;
        k.tint_keep = 1.0f - a;
    }
    if (use_atmosphere) {
        d = clamp01(d);
        float a = clamp01(p.dist_hue_strength) * d;
        k.hue = srgb_to_linear(p.dist_hue_color) * a;
        k.hue_keep = 1.0f - a;
        k.max_saturation = 1.0f - clamp01(p.dist_sat_limiter) * d;
        k.value_lo = srgb_to_linear(clamp01(p.dist_value_min) * d);
        k.value_hi = srgb_to_linear(1.0f - (1.0f - clamp01(p.dist_value_max)) * d);
        k.atmosphere = true;
    }
    return k;
}

// RenderMan's filterwidth idiom for the stroke mask: how much the mask's noise changes across
// one sample's footprint on screen (1 / samples_per_axis pixels), to widen the feather by, so
// a few samples per pixel do not alias. The noise argument moves frequ / (2 half) lattice units
// per pixel; 0.3 is half a footprint times the noise's typical slope (0.6 per lattice unit).
inline float stroke_filter_width(const StrokeConstants& k, float half_w_px, float half_l_px,
                                 int samples_per_axis) {
    float g = std::max(k.frequ_s / std::max(2.0f * half_w_px, 1e-6f),
                       k.frequ_t / std::max(2.0f * half_l_px, 1e-6f));
    return std::min(0.3f * g / static_cast<float>(std::max(samples_per_axis, 1)), 0.5f);
}

inline StrokeNoise noise_of(const StrokeConstants& k) {
    return {k.frequ_s, k.frequ_t, k.offset_s, k.offset_t};
}

// noise_of(stroke_constants(p, n_dot_l, ...)) of a lit stroke at full detail (shadow 1,
// lod_distance 0), from its kept stroke_outer: the same bits, without the gains' powers.
inline StrokeNoise lit_stroke_noise(const StrokeShaderParams& p, float n_dot_l, float outer,
                                    float center_distance, float label) {
    return stroke_noise_for(p, stroke_lightness_outer(p, n_dot_l, outer, 0.0f), center_distance,
                            label);
}

// Noise of the stroke mask at sprite coordinates (s, t).
inline float stroke_noise(const StrokeNoise& n, float s, float t, int octaves) {
    return fractal_noise(s * n.frequ_s + n.offset_s, t * n.frequ_t + n.offset_t, octaves);
}

inline float stroke_noise(const StrokeConstants& k, float s, float t, int octaves) {
    return stroke_noise(noise_of(k), s, t, octaves);
}

// The particle's own colour, what it mirrors, tint, then atmospheric perspective: what happens
// to a palette colour after the lookup.
inline Color finish_color(const StrokeConstants& k, Color c) {
    if (k.own_amount > 0.0f) c = mix(c, scale_keeping_hue(k.own, luminance(c)), k.own_amount);
    if (k.mirror_keep < 1.0f) c = c * k.mirror_keep + k.mirror;
    c = c * k.tint_keep + k.tint;
    if (k.atmosphere) {
        c = c * k.hue_keep + k.hue;
        c = limit_saturation(c, k.max_saturation);
        c = clamp_value(c, k.value_lo, k.value_hi);
    }
    if (k.key_amount > 0.0f) c = toward_luminance(c, k.key_luminance, k.key_amount);
    return c;
}

// Colour of the stroke at (s, t), exactly: lightness jittered by the sub-stroke noise, looked
// up in the palette, tinted, then pushed into the distance.
inline Color stroke_color(const StrokeConstants& k, const Palette& palette, float s, float t) {
    float l = k.lightness;
    if (k.sub_amt > 0.0f)
        l += k.sub_amt *
             (noise(s * k.sub_frequ_s + k.offset_t, t * k.sub_frequ_t + k.offset_s) - 0.5f);
    return finish_color(k, palette_lookup(palette, l));
}

// A stroke's final colours tabulated against its sub-stroke noise value: lightness varies only
// through that noise inside a sprite, and tint and atmosphere are constant over it, so
// kSize + 1 colours per sprite replace the palette, tint and atmosphere per fragment. The
// "palette_lut" accuracy setting. Stored per channel as each interval's start and step, so the
// vector kernel looks both up with in-register permutes (16 entries fit two 8-lane registers)
// and computes exactly the scalar's c0 + (c1 - c0) * f.
struct StrokeRamp {
    static constexpr int kSize = 16;
    float base[3][kSize]{};  // colour at the start of interval i, per channel
    float step[3][kSize]{};  // colour at its end minus that
};

inline StrokeRamp make_ramp(const StrokeConstants& k, const Palette& palette) {
    StrokeRamp r;
    Color prev{};
    for (int i = 0; i <= StrokeRamp::kSize; ++i) {
        float n = static_cast<float>(i) / StrokeRamp::kSize;
        Color c = finish_color(k, palette_lookup(palette, k.lightness + k.sub_amt * (n - 0.5f)));
        if (i > 0)
            for (int ch = 0; ch < 3; ++ch) {
                r.base[ch][i - 1] = prev[ch];
                r.step[ch][i - 1] = c[ch] - prev[ch];
            }
        prev = c;
    }
    return r;
}

// The ramp's colour at noise value n in 0..1 (1 is the end of the last interval; outside,
// the end intervals extend).
inline Color ramp_color(const StrokeRamp& r, float n) {
    float x = n * StrokeRamp::kSize;
    int i = std::clamp(static_cast<int>(x), 0, StrokeRamp::kSize - 1);
    float f = x - static_cast<float>(i);
    return {r.base[0][i] + r.step[0][i] * f, r.base[1][i] + r.step[1][i] * f,
            r.base[2][i] + r.step[2][i] * f};
}

// stroke_color through the ramp.
inline Color stroke_color(const StrokeConstants& k, const StrokeRamp& r, float s, float t) {
    if (!(k.sub_amt > 0.0f)) return ramp_color(r, 0.5f);
    return ramp_color(r, noise(s * k.sub_frequ_s + k.offset_t, t * k.sub_frequ_t + k.offset_s));
}

}  // namespace pleinair
