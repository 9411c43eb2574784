// level_of_detail: per tree, the distance values at its centre and the survivors' growth.
#include "pipeline/frame/lod.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#define GLM_ENABLE_EXPERIMENTAL
#include <cstdio>
#include <glm/gtx/norm.hpp>

#include "pipeline/input/camera_track.h"
#include "pipeline/shot/shot.h"
#include "shading/curves.h"
#include "shading/portable_math.h"
#include "shading/stroke_shader.h"

namespace pleinair {

double view_depth(const Camera& cam, const glm::dvec3& world) {
    return glm::dot(world - cam.eye, cam.forward);
}

float leaf_fade(float value, float fade_begin, float fade_end, float g) {
    if (!(fade_end > fade_begin)) return value >= fade_begin ? 0.0f : 1.0f;
    return 1.0f - gain((value - fade_begin) / (fade_end - fade_begin), g);
}

float bark_fade(float trunk_value, bool fades, float label, float g) {
    if (!fades) return 1.0f;
    const float begin = bark_fade_begin(label);
    return leaf_fade(trunk_value, begin, begin + kBarkFadeSpan, g);
}

double max_fade_rate(double shortest_fade, float g) {
    // The steepest slope of the eased fade, sampled (gain's slope is unbounded at the ends
    // below g = 0.5, so the bound is found, not derived).
    constexpr int kSteps = 256;
    double steepest = 1;
    for (int i = 0; i < kSteps; ++i)
        steepest = std::max(
            steepest, double(gain((i + 1.0f) / kSteps, g) - gain(float(i) / kSteps, g)) * kSteps);
    return std::max(shortest_fade, 0.02) / (kMinFadeFrames * steepest);
}

float near_field_fade(float near_value, float center_distance, float label, float g) {
    if (!(near_value > 0)) return 1.0f;
    const float begin = 0.15f + 0.55f * clamp01(center_distance) + 0.3f * label_hash(label, 4);
    return leaf_fade(near_value, begin, begin + 0.3f, g);
}

namespace {

// Where a leaf at distance r and bin coordinates (e, a) reads the bins, and what of its move
// the bins' extents alone decide: the survivors' search changes only the exponents, so each
// step costs an exponential per survivor, not a logarithm and an exponential (pmath::pow is
// exp(y log x), so the factor has the same bits).
struct SpreadAt {
    size_t i00 = 0, i01 = 0, i10 = 0, i11 = 0;  // bins (e0, a0), (e0, a1), (e0 + 1, a0), ...
    float wa0 = 1, wa1 = 0, we0 = 1, we1 = 0;   // bilinear weights
    bool inside = false;                        // r < the extent R there: it may move
    double log_ratio = 0;                       // log(r / R)

    // r -> R (r / R)^gamma inside the bins' extent R: survivors move out, the silhouette does
    // not. Near the centre the move is bounded by max_spread.
    float factor(const TreeLod& t) const {
        if (!inside) return 1.0f;
        const glm::vec2* g = t.radial.data();
        const float gx =
            (g[i00].x * wa0 + g[i01].x * wa1) * we0 + (g[i10].x * wa0 + g[i11].x * wa1) * we1;
        if (!(gx < 1.0f)) return 1.0f;
        return std::min(t.max_spread,
                        static_cast<float>(pmath::exp(static_cast<double>(gx - 1.0f) * log_ratio)));
    }
};

SpreadAt spread_at(const TreeLod& t, float r, float e, float a) {
    e = std::clamp(e, 0.0f, kElevationBins - 1.0f);
    const int e0 = std::min(static_cast<int>(e), kElevationBins - 2);
    const float fe = e - e0;
    const float af = std::floor(a);
    const float fa = a - af;
    const int a0 = (static_cast<int>(af) + kAzimuthBins) % kAzimuthBins;
    const int a1 = (a0 + 1) % kAzimuthBins;
    auto bin = [](int ei, int ai) { return static_cast<size_t>(ei * kAzimuthBins + ai); };
    SpreadAt s;
    s.i00 = bin(e0, a0), s.i01 = bin(e0, a1), s.i10 = bin(e0 + 1, a0), s.i11 = bin(e0 + 1, a1);
    s.wa0 = 1 - fa, s.wa1 = fa, s.we0 = 1 - fe, s.we1 = fe;
    const glm::vec2* g = t.radial.data();
    const float gy = (g[s.i00].y * s.wa0 + g[s.i01].y * s.wa1) * s.we0 +
                     (g[s.i10].y * s.wa0 + g[s.i11].y * s.wa1) * s.we1;
    s.inside = r < gy;
    if (s.inside) s.log_ratio = pmath::log(static_cast<double>(r / gy));
    return s;
}

// A leaf's weight in the survivors' move: its fade squared. A leaf half faded covers the
// crown's edge less than half a leaf's worth (its dry-brush dabs overlap the others' as much as
// a whole stroke would); weighted by the fade alone, the survivors stayed too far in and the
// receding oak of tree-dolly covered 9.3% less than at full detail mid-fade, 7.7% with this
// (bench coherence, 2026-12-01). Leaves wholly there or gone weigh the same either way.
float spread_weight(float fade) { return fade * fade; }

// The survivors' move, bin by bin: sums in double and in index order, so no thread count or
// order can change a bit of it.
void radial_spread(const LeafBasis& B, const std::vector<float>& fade, const glm::vec3& center,
                   float max_growth, TreeLod& t) {
    constexpr int kBins = kElevationBins * kAzimuthBins;
    std::vector<double> all_w(kBins, 0.0), all_r2(kBins, 0.0), kept_w(kBins, 0.0),
        kept_r2(kBins, 0.0), extent(kBins, 0.0);
    for (size_t j = 0; j < B.size(); ++j) {
        const float r = B.r[j];
        if (!(r > 0)) continue;
        const float e = B.e[j], a = B.a[j];
        const int be = std::clamp(static_cast<int>(std::lround(e)), 0, kElevationBins - 1);
        const int ba = (static_cast<int>(std::lround(a)) + kAzimuthBins) % kAzimuthBins;
        const int bin = be * kAzimuthBins + ba;
        const double alpha = spread_weight(fade[j]);
        all_w[bin] += 1, all_r2[bin] += double(r) * r;
        kept_w[bin] += alpha, kept_r2[bin] += alpha * r * r;
        extent[bin] = std::max(extent[bin], double(r));
    }
    double aw = 0, ar = 0, kw = 0, kr = 0, reach = 0;
    for (int i = 0; i < kBins; ++i)
        aw += all_w[i], ar += all_r2[i], kw += kept_w[i], kr += kept_r2[i],
            reach = std::max(reach, extent[i]);
    if (!(kw > 1e-6) || !(kr > 0) || !(reach > 0)) return;
    // The exponent that takes the survivors' RMS distance to the crown's while the crown's
    // extent stays put: r -> R (r / R)^gamma.
    auto exponent = [](double rms_all, double rms_kept, double r) {
        if (!(rms_kept < rms_all) || !(rms_all < r) || !(rms_kept > 0)) return 1.0;
        return std::clamp(pmath::log(rms_all / r) / pmath::log(rms_kept / r), 0.05, 1.0);
    };
    const double whole = exponent(std::sqrt(ar / aw), std::sqrt(kr / kw), reach);
    t.center = center;
    t.radial.assign(kBins, glm::vec2(1.0f, static_cast<float>(reach)));
    for (int i = 0; i < kBins; ++i) {
        if (!(all_w[i] > 0)) continue;
        const double g = kept_w[i] > 0.5 && kept_r2[i] > 0
                             ? exponent(std::sqrt(all_r2[i] / all_w[i]),
                                        std::sqrt(kept_r2[i] / kept_w[i]), extent[i])
                             : whole;
        t.radial[i] = glm::vec2(static_cast<float>(g), static_cast<float>(extent[i]));
    }
    t.max_spread = max_growth;
    // Each bin's exponent matches its RMS for a survivor at the RMS distance only, and leaves
    // take exponents interpolated between bins: one factor k on every bin's (1 - gamma), found
    // by bisection, brings the survivors' RMS distance to the whole crown's.
    const std::vector<glm::vec2> base = t.radial;
    const double target = ar / aw;
    // The survivors' distances, fades and where they read the bins, once: the search only
    // changes the bins' exponents.
    struct Survivor {
        float r, alpha;
        SpreadAt at;
    };
    std::vector<Survivor> kept;
    for (size_t j = 0; j < B.size(); ++j) {
        const float alpha = spread_weight(fade[j]);
        const float r = B.r[j];
        if (!(alpha > 0) || !(r > 0)) continue;
        kept.push_back({r, alpha, spread_at(t, r, B.e[j], B.a[j])});
    }
    auto rms_with = [&](double k) {
        for (size_t i = 0; i < base.size(); ++i)
            t.radial[i].x = static_cast<float>(std::max(0.05, 1.0 - (1.0 - base[i].x) * k));
        double moved = 0;
        for (const Survivor& s : kept) {
            const double m = s.r * s.at.factor(t);
            moved += s.alpha * m * m;
        }
        return moved / kw;
    };
    double lo = 0, hi = 4;
    if (rms_with(hi) < target) {
        lo = hi;
    } else {
        for (int it = 0; it < 10; ++it) {
            const double mid = 0.5 * (lo + hi);
            (rms_with(mid) < target ? lo : hi) = mid;
        }
    }
    rms_with(lo);
}

}  // namespace

glm::vec3 spread_leaf(const TreeLod& t, const glm::vec3& p) {
    if (t.radial.empty()) return p;
    const glm::vec3 v = p - t.center;
    const float r = glm::length(v);
    if (!(r > 0)) return p;
    float e, a;
    direction_bins(v, r, e, a);
    return t.center + v * spread_factor(t, r, e, a);
}

glm::vec3 spread_leaf(const TreeLod& t, const glm::vec3& p, float r, float e, float a) {
    if (t.radial.empty() || !(r > 0)) return p;
    return t.center + (p - t.center) * spread_factor(t, r, e, a);
}

float spread_factor(const TreeLod& t, float r, float e, float a) {
    return spread_at(t, r, e, a).factor(t);
}

ParticleLod particle_lod(const Shot& shot, const FrameLod& lod, size_t item, SpriteKind kind,
                         size_t j, const glm::dvec3& world) {
    const Camera& cam = lod.camera;
    ParticleLod out;
    out.world = world;
    const std::vector<BuiltTree>& trees = *shot.trees;
    if (kind == SpriteKind::kSurface) {
        const size_t chunk = item - trees.size();
        const SurfaceParticles& S = shot.land->chunks[chunk];
        if (shot.land->is_near(chunk)) {
            // The near field's detail strokes appear one by one as the camera approaches, each
            // from its own threshold (drawn from its label), never from a count.
            if (!lod.near_field) return out.fade = 0, out;
            const float nf = near_field_value(view_depth(cam, world), lod.circles.near_field);
            const float from = 0.75f * label_hash(S.label[j], 5);
            out.fade = 1.0f - leaf_fade(nf, from, from + 0.25f, lod.fade_gain);
            return out;
        }
        const double z = view_depth(cam, world);
        // In the near field the surface's own strokes get smaller, as the leaves do, so the
        // foreground is not a few large soft blobs; the near field's strokes fill in.
        if (lod.near_field)
            out.scale = near_field_scale(near_field_value(z, lod.circles.near_field));
        const float fb = S.fade_begin(j);
        if (fb > 1.0f) return out;  // a base stroke: it would leave a hole
        const DistanceCircles& c = lod.circles;
        const Atmosphere& a = shot.scene.atmosphere;
        const float dv = lod.surfaces ? circle_value(z, c.leaf_near, c.leaf_far)
                                      : circle_value(z, a.near_distance, a.far_distance);
        out.fade = 1.0f - smoothstep(fb, S.fade_end(j), dv);
        return out;
    }
    if (lod.trees.empty()) return out;
    const TreeLod& t = lod.trees[item];
    const BuiltTree& b = trees[item];
    if (kind == SpriteKind::kBark) {
        if (lod.trunks)
            out.fade = bark_fade(t.trunk, twig_bark_fades(b.tree().branches[b.bark().limb[j]]),
                                 b.bark().label[j], lod.fade_gain);
        return out;
    }
    const LeafParticles& L = b.tree().leaves;
    if (lod.leaves) {
        out.fade = leaf_fade(t.leaf, L.fade_begin[j], L.fade_end[j], lod.fade_gain);
        out.lod_distance = t.darkening_lift;
        // The faded leaves' casters still stand in the sun's scene (built once): the share of
        // the crown that is gone no longer shades the survivors.
        out.shadow_lift = 1.0f - t.kept;
        if (out.gone()) return out;
        if (t.leaf > 0) {
            out.scale = t.growth;
            out.growth = t.growth;
            const LeafBasis* B = shot.leaf_basis.empty() ? nullptr : shot.leaf_basis[item].get();
            const glm::vec3 spread = B ? spread_leaf(t, L.position[j], B->r[j], B->e[j], B->a[j])
                                       : spread_leaf(t, L.position[j]);
            out.world = shot.placements[item].place(spread);
            out.moved = true;
        }
    }
    if (lod.near_field) {
        const float nf = near_field_value(view_depth(cam, out.world), lod.circles.near_field);
        // Thinning leaves shrink away rather than turn transparent: half-transparent strokes
        // near the camera read as blur, the very thing the near field is there to avoid.
        out.thin = near_field_fade(nf, L.center_distance[j], L.label[j], lod.fade_gain);
        out.scale *= out.thin * near_field_scale(nf);
    }
    return out;
}

float thin_presence(float r, float u) {
    if (!(r < 1.0f)) return 1.0f;
    const float q = r * r;
    if (!(q > 0.0f)) return 0.0f;
    return clamp01((q * (1.0f + kThinBand) - u) / (kThinBand * q));
}

float thin_kept(float q) {
    if (!(q < 1.0f)) return 1.0f;
    if (!(q > 0.0f)) return 0.0f;
    const double b = kThinBand, top = q * (1.0 + b);
    if (top <= 1.0) return static_cast<float>(q * (1.0 + 0.5 * b));
    // The band clipped at u = 1: whole below q, then the line from 1 at q towards 0 at top.
    return static_cast<float>(q + (1.0 - q) * (top - 0.5 * (1.0 + q)) / (b * q));
}

float thin_draw(size_t item, SpriteKind kind, size_t j) {
    // SplitMix64's finaliser over the particle's key: independent of its label, so the
    // thinning does not follow the leaves' fade thresholds or the stroke noise.
    uint64_t z = (uint64_t{item} << 35) ^ (uint64_t(kind) << 32) ^ uint64_t { j };
    z += 0x9e3779b97f4a7c15ull;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    z ^= z >> 31;
    return static_cast<float>(z >> 40) * (1.0f / 16777216.0f);
}

namespace {

// A tree's distance values for leaves and bark, replayed along the track from its first frame,
// each step bounded so that no fade completes in fewer than kMinFadeFrames frames, however fast
// the camera goes.
// The bounds on a step are the family's (leaf_rates, by family) and kBarkFadeSpan's.
void replay_tree(const Shot& shot, size_t i, const std::vector<FrameView>& path,
                 const std::vector<double>& leaf_rates, double trunk_rate, TreeLod& t) {
    const BuiltTree& b = (*shot.trees)[i];
    const glm::dvec3 center = shot.placements[i].place(b.tree().center);
    const double leaf_rate = leaf_rates[b.family];
    for (size_t k = 0; k < path.size(); ++k) {
        const DistanceCircles& pc = path[k].circles;
        const double depth = view_depth(path[k].camera, center);
        const float leaf = circle_value(depth, pc.leaf_near, pc.leaf_far);
        const float trunk = circle_value(depth, pc.trunk_near, pc.trunk_far);
        if (k == 0) {
            t.leaf = leaf, t.trunk = trunk;
            continue;
        }
        t.leaf += static_cast<float>(std::clamp<double>(leaf - t.leaf, -leaf_rate, leaf_rate));
        t.trunk += static_cast<float>(std::clamp<double>(trunk - t.trunk, -trunk_rate, trunk_rate));
    }
}

// The leaves' detail at the tree's distance value t.leaf (> 0): how much the interior
// darkening weakens, how much survivors grow and where they spread to.
void leaf_detail(const BuiltTree& b, const LeafBasis& B, const RenderSettings& rs, float max_growth,
                 TreeLod& t) {
    const LeafParticles& L = b.tree().leaves;
    // Interior darkening stands for shade cast by outer leaves (IV.4.1); as they fade it
    // weakens (IV.6), by as much as keeps the survivors' mean lightness the whole tree's.
    // A leaf's lightness is linear in the weakening w: l0 + (l1 - l0) w, at a typical N.L.
    double sum = 0, full = 0, k0 = 0, k1 = 0;
    std::vector<float> alpha(L.size());  // each leaf's fade, for the spread below too
    for (size_t j = 0; j < L.size(); ++j) {
        alpha[j] = leaf_fade(t.leaf, L.fade_begin[j], L.fade_end[j], rs.fade_gain);
        const double a = alpha[j];
        const double l0 = B.light0[j], l1 = B.light1[j];
        sum += a, full += l0, k0 += a * l0, k1 += a * (l1 - l0);
    }
    if (sum > 0 && k1 > 1e-9 * sum)
        t.darkening_lift = static_cast<float>(
            std::clamp((full / static_cast<double>(L.size()) - k0 / sum) / (k1 / sum), 0.0, 1.0));
    // Cook et al. 2007: the survivors' area grows by 1 / u, so the crown's coverage stays
    // (for leaves overlapping at random), here by u^-0.9 (kGrowthPower), since the spread
    // below also widens the crown the survivors fill: with 1 / u the far oak of tree-dolly
    // covered 4.3% more than at full detail, with u^-0.9 0.2% less.
    t.kept = static_cast<float>(sum / static_cast<double>(L.size()));
    const float floor = pmath::pow(max_growth, -1.0f / kGrowthPower);
    t.growth = std::min(max_growth, pmath::pow(std::max(t.kept, floor), -kGrowthPower));
    radial_spread(B, alpha, b.tree().center, max_growth, t);
}

}  // namespace

FrameLod level_of_detail(const Shot& shot, const FrameView& view, const RenderSettings& rs) {
    FrameLod lod;
    lod.camera = view.camera;
    if (!rs.level_of_detail) return lod;
    const DistanceCircles& c = view.circles;
    lod.circles = c;
    lod.fade_gain = rs.fade_gain;
    lod.leaves = c.leaves();
    lod.trunks = c.trunks() && shot.plan.bark;
    lod.surfaces = c.leaves();
    lod.near_field = c.near_field > 0;
    lod.thin_small = rs.thin_below_px > 0 && c.any();
    if (!lod.leaves && !lod.trunks) return lod;
    const std::vector<BuiltTree>& trees = *shot.trees;
    lod.trees.resize(trees.size());
    const std::vector<FrameView> path = replay_path(shot.scene, view);
    const float max_growth = std::max(1.0f, rs.max_leaf_growth);
    // Per family, not per tree: each bound samples the fade's slope 256 times.
    std::vector<double> leaf_rates;
    for (const Family& f : shot.scene.families) {
        const FadeParams& fp = f.params.leaves.fade;
        leaf_rates.push_back(max_fade_rate(std::max(fp.length_min, fp.length.lo), rs.fade_gain));
    }
    const double trunk_rate = max_fade_rate(kBarkFadeSpan, rs.fade_gain);
    tbb::parallel_for(size_t{0}, trees.size(), [&](size_t i) {
        replay_tree(shot, i, path, leaf_rates, trunk_rate, lod.trees[i]);
        if (!lod.trunks) lod.trees[i].trunk = 0;
    });
    if (!lod.leaves) return lod;
    // A tree's leaf detail is a function of its grown tree (its member) and its distance value
    // alone: trees drawn from one member at the same value (the far wood, all at 1) share it,
    // computed once and copied, the same bits as computed tree by tree.
    std::map<std::pair<const Tree*, uint32_t>, size_t> first;
    std::vector<size_t> source(trees.size(), trees.size()), computed;
    for (size_t i = 0; i < trees.size(); ++i) {
        if (trees[i].tree().leaves.size() == 0 || lod.trees[i].leaf <= 0) continue;
        uint32_t bits;
        std::memcpy(&bits, &lod.trees[i].leaf, sizeof bits);
        auto [it, fresh] = first.emplace(std::make_pair(&trees[i].tree(), bits), i);
        source[i] = it->second;
        if (fresh) computed.push_back(i);
    }
    tbb::parallel_for(size_t{0}, computed.size(), [&](size_t k) {
        const size_t i = computed[k];
        const BuiltTree& b = trees[i];
        if (!shot.leaf_basis.empty())
            return leaf_detail(b, *shot.leaf_basis[i], rs, max_growth, lod.trees[i]);
        // A shot built with the level of detail off, painted with it on.
        const LeafBasis B = leaf_basis(b.tree(), shot.scene.families[b.family].leaf_shader);
        leaf_detail(b, B, rs, max_growth, lod.trees[i]);
    });
    for (size_t i = 0; i < trees.size(); ++i) {
        if (source[i] == i || source[i] == trees.size()) continue;
        // The same leaf value by construction; the bark's is the tree's own.
        const float trunk = lod.trees[i].trunk;
        lod.trees[i] = lod.trees[source[i]];
        lod.trees[i].trunk = trunk;
    }
    return lod;
}

namespace {

// The level of detail's line for --explain: the circles (into `why`), and how far the trees
// have faded.
std::string lod_detail(const FrameLod& lod, std::string& why) {
    auto num = [](double v) {
        char b[32];
        std::snprintf(b, sizeof b, "%g", v);
        return std::string(b);
    };
    const DistanceCircles& c = lod.circles;
    std::string what;
    if (lod.leaves) what += "leaves " + num(c.leaf_near) + "-" + num(c.leaf_far);
    if (lod.trunks)
        what += std::string(what.empty() ? "" : ", ") + "trunks " + num(c.trunk_near) + "-" +
                num(c.trunk_far);
    if (lod.near_field)
        what += std::string(what.empty() ? "" : ", ") + "near field " + num(c.near_field);
    std::string detail;
    if (lod.leaves && !lod.trees.empty()) {
        double kept = 0;
        float most = 1;
        for (const TreeLod& t : lod.trees) kept += t.kept, most = std::max(most, t.growth);
        detail = "leaves kept " + num(std::round(1000 * kept / lod.trees.size()) / 10) +
                 "% on average, survivors grown up to " + num(std::round(100 * most) / 100) + "x";
    }
    why = "distance circles: " + (what.empty() ? "none" : what);
    return detail;
}

}  // namespace

FrameLod lod_stage(const FrameContext& ctx) {
    StagePhase phase(ctx, "level of detail");
    const FrameView& view = ctx.settings.lod_view ? *ctx.settings.lod_view : ctx.view;
    FrameLod lod = level_of_detail(ctx.shot, view, ctx.render());
    if (ctx.plan.lod) {
        std::string why;
        std::string detail = lod_detail(lod, why);
        phase.done(std::move(why), std::move(detail));
    }
    return lod;
}

}  // namespace pleinair
