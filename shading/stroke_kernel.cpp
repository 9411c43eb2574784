// The row kernel, scalar and vector. Highway compiles the vector part once per target and picks
// one at run time, so a build runs on any x86-64 and uses AVX2 where present. Both versions
// evaluate the same expressions in the same order without fused multiply-adds
// (-ffp-contract=off), so they give the same bits; tests/shading/stroke_kernel_test.cpp checks.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "shading/stroke_kernel.cpp"
#include "shading/stroke_kernel.h"

#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace pleinair::HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

template <class D, class V = hn::Vec<D>>
HWY_INLINE V Fade(D d, V t) {
    V a = hn::Mul(hn::Mul(t, t), t);
    V b = hn::Add(hn::Mul(t, hn::Sub(hn::Mul(t, hn::Set(d, 6.0f)), hn::Set(d, 15.0f))),
                  hn::Set(d, 10.0f));
    return hn::Mul(a, b);
}

template <class V>
HWY_INLINE V Lerp(V a, V b, V t) {
    return hn::Add(a, hn::Mul(t, hn::Sub(b, a)));
}

// noise_detail::cell: fraction and lattice index; coordinates beyond 1e9 (or NaN) give 0, 0.
template <class D, class DI, class V = hn::Vec<D>>
HWY_INLINE hn::Vec<DI> Cell(D d, DI di, V x, V& frac) {
    V f = hn::Floor(x);
    auto ok = hn::And(hn::Gt(f, hn::Set(d, -1e9f)), hn::Lt(f, hn::Set(d, 1e9f)));
    frac = hn::IfThenElseZero(ok, hn::Sub(x, f));
    auto i = hn::ConvertTo(di, hn::IfThenElseZero(ok, f));
    return hn::And(i, hn::Set(di, 255));
}

// noise_detail::kGrad2X/Y[h & 7] by a permute, or by selects instead of gathers (the same
// -1, 0 and 1):
// x: -1 for odd h, 1 for even, 0 for h >= 6; y: -1 for h in {2, 3, 7}, 0 for h in {4, 5}.
template <class D, class DI, class V = hn::Vec<D>>
HWY_INLINE V Grad2(D d, DI di, hn::Vec<DI> h, V x, V y) {
    auto k = hn::And(h, hn::Set(di, 7));
    if constexpr (hn::MaxLanes(D()) == 8) {
        // Eight lanes hold the eight gradients: one in-register permute per axis.
        const auto at = hn::IndicesFromVec(d, k);
        const V gx = hn::TableLookupLanes(hn::LoadU(d, noise_detail::kGrad2X), at);
        const V gy = hn::TableLookupLanes(hn::LoadU(d, noise_detail::kGrad2Y), at);
        return hn::Add(hn::Mul(gx, x), hn::Mul(gy, y));
    }
    const V one = hn::Set(d, 1.0f), minus = hn::Set(d, -1.0f);
    auto odd = hn::RebindMask(d, hn::Eq(hn::And(k, hn::Set(di, 1)), hn::Set(di, 1)));
    auto ge6 = hn::RebindMask(d, hn::Gt(k, hn::Set(di, 5)));
    V gx = hn::IfThenZeroElse(ge6, hn::IfThenElse(odd, minus, one));
    auto neg_y = hn::RebindMask(
        d, hn::Or(hn::Eq(hn::And(k, hn::Set(di, 6)), hn::Set(di, 2)), hn::Eq(k, hn::Set(di, 7))));
    auto zero_y = hn::RebindMask(d, hn::Eq(hn::And(k, hn::Set(di, 6)), hn::Set(di, 4)));
    V gy = hn::IfThenZeroElse(zero_y, hn::IfThenElse(neg_y, minus, one));
    return hn::Add(hn::Mul(gx, x), hn::Mul(gy, y));
}

// noise_detail::lattice_hash & 7, lane-wise.
template <class DU, class VU = hn::Vec<DU>>
HWY_INLINE VU LatticeHash(DU du, VU x, VU y) {
    VU h = hn::Xor(hn::Mul(x, hn::Set(du, 0x8DA6B343u)), hn::Mul(y, hn::Set(du, 0xD8163841u)));
    h = hn::Xor(h, hn::ShiftRight<15>(h));
    h = hn::Mul(h, hn::Set(du, 0x2C1B3C6Du));
    h = hn::Xor(h, hn::ShiftRight<12>(h));
    return hn::And(h, hn::Set(du, 7u));
}

template <class D, class V = hn::Vec<D>>
HWY_INLINE V SignedNoise(D d, V x, V y) {
    const hn::RebindToSigned<D> di;
    const hn::RebindToUnsigned<D> du;
    V fx, fy;
    auto x0 = hn::BitCast(du, Cell(d, di, x, fx));
    auto y0 = hn::BitCast(du, Cell(d, di, y, fy));
    V u = Fade(d, fx), v = Fade(d, fy);
    const auto one = hn::Set(du, 1u), wrap = hn::Set(du, 255u);
    auto x1 = hn::And(hn::Add(x0, one), wrap), y1 = hn::And(hn::Add(y0, one), wrap);
    V m1 = hn::Set(d, -1.0f);
    V fx1 = hn::Add(fx, m1), fy1 = hn::Add(fy, m1);
    V n00 = Grad2(d, di, hn::BitCast(di, LatticeHash(du, x0, y0)), fx, fy);
    V n10 = Grad2(d, di, hn::BitCast(di, LatticeHash(du, x1, y0)), fx1, fy);
    V n01 = Grad2(d, di, hn::BitCast(di, LatticeHash(du, x0, y1)), fx, fy1);
    V n11 = Grad2(d, di, hn::BitCast(di, LatticeHash(du, x1, y1)), fx1, fy1);
    return Lerp(Lerp(n00, n10, u), Lerp(n01, n11, u), v);
}

template <class D, class V = hn::Vec<D>>
V Clamp01(D d, V n) {
    return hn::Min(hn::Max(n, hn::Zero(d)), hn::Set(d, 1.0f));
}

template <class D, class V = hn::Vec<D>>
V FractalNoise(D d, V x, V y, int octaves) {
    const V half = hn::Set(d, 0.5f);
    if (octaves <= 1) return Clamp01(d, hn::Add(half, hn::Mul(half, SignedNoise(d, x, y))));
    V sum = hn::Zero(d);
    float amp = 1.0f, norm = 0.0f, f = 1.0f;
    for (int i = 0; i < octaves; ++i) {
        V xs = hn::Add(hn::Mul(x, hn::Set(d, f)), hn::Set(d, 17.17f * i));
        V ys = hn::Add(hn::Mul(y, hn::Set(d, f)), hn::Set(d, 31.31f * i));
        sum = hn::Add(sum, hn::Mul(hn::Set(d, amp), SignedNoise(d, xs, ys)));
        norm += amp;
        amp *= 0.5f;
        f *= 2.0f;
    }
    return Clamp01(d, hn::Add(half, hn::Div(hn::Mul(half, sum), hn::Set(d, norm))));
}

// Lookups in a 16-entry ramp table: in-register permutes where a vector holds at least eight
// lanes (one register of 16, or two of 8 and a select), a gather otherwise.
template <class D>
struct RampIndex {
    static_assert(StrokeRamp::kSize == 16, "the permutes below cover 16 entries");
    using DI = hn::RebindToSigned<D>;
    D d;
    hn::Vec<DI> idx;
    RampIndex(D d_, hn::Vec<DI> i) : d(d_), idx(i) {}
    hn::Vec<D> lookup(const float* table) const {
        const DI di;
        if constexpr (hn::MaxLanes(D()) >= 16) {
            return hn::TableLookupLanes(hn::LoadU(d, table), hn::IndicesFromVec(d, idx));
        } else if constexpr (hn::MaxLanes(D()) == 8) {
            const auto lane = hn::IndicesFromVec(d, hn::And(idx, hn::Set(di, 7)));
            const auto lo = hn::TableLookupLanes(hn::LoadU(d, table), lane);
            const auto hi = hn::TableLookupLanes(hn::LoadU(d, table + 8), lane);
            return hn::IfThenElse(hn::RebindMask(d, hn::Gt(idx, hn::Set(di, 7))), hi, lo);
        } else {
            return hn::GatherIndex(d, table, idx);
        }
    }
};

void ShadeStrokeRow(const StrokeRow& row, int y, int x0, int count, float* alpha_out, float* r_out,
                    float* g_out, float* b_out, int* inside_out) {
    // Sprites are a few to a few dozen pixels wide: eight lanes waste less than sixteen.
    const hn::CappedTag<float, 8> d;
    const hn::RebindToSigned<decltype(d)> di;
    using V = hn::Vec<decltype(d)>;
    const size_t N = hn::Lanes(d);
    constexpr size_t kMaxLanes = HWY_MAX_BYTES / sizeof(float);
    const StrokeConstants& k = *row.k;
    const int n = row.samples_per_axis;
    const float inv_n = 1.0f / static_cast<float>(n);
    const float max_op = clamp01(row.max_opacity);
    const bool step = !(row.feather_max > row.feather_min);
    // Whether a sample in the profile's first or last table cell can show at all. There the
    // profile is at most its value at the cell's inner end (sin^k rises from the border), so
    // when that is below feather_min (with a margin for the functions' last bits) no sample in
    // those cells shows whatever its exact profile, and the table's value serves: edge_profile's
    // exact evaluation (a sine and a power per lane) is only needed where it could change what
    // shows.
    const bool border_shows = std::max(row.edge->v[1], row.edge->v[EdgeTable::kSize - 1]) >=
                              row.feather_min * (1.0f - 1e-4f);
    const float* table = row.edge->v.data();
    constexpr int kSize = EdgeTable::kSize;
    HWY_ALIGN float lanes_f[kMaxLanes];
    HWY_ALIGN float prof_s[kMaxLanes];
    HWY_ALIGN float prof_t[kMaxLanes];
    HWY_ALIGN float us[kMaxLanes];
    HWY_ALIGN float ut[kMaxLanes];
    HWY_ALIGN int32_t border_s[kMaxLanes];
    HWY_ALIGN int32_t border_t[kMaxLanes];
    for (size_t i = 0; i < N; ++i) lanes_f[i] = static_cast<float>(i);
    const V lane = hn::Load(d, lanes_f);

    // edge_profile over a vector; lanes in the first or last table cell are redone exactly.
    auto profile = [&](V u, float* prof, float* ubuf, int32_t* bbuf, auto inside) {
        V x = hn::Mul(u, hn::Set(d, static_cast<float>(kSize)));
        auto i = hn::ConvertTo(di, x);
        auto border = hn::Or(hn::Eq(i, hn::Zero(di)), hn::Gt(i, hn::Set(di, kSize - 2)));
        auto ic = hn::Min(hn::Max(i, hn::Zero(di)), hn::Set(di, kSize));
        V v0 = hn::GatherIndex(d, table, ic);
        V v1 = hn::GatherIndex(d, table, hn::Add(ic, hn::Set(di, 1)));
        V f = hn::Sub(x, hn::ConvertTo(d, ic));
        V p = hn::Add(v0, hn::Mul(f, hn::Sub(v1, v0)));
        auto fix = hn::And(hn::RebindMask(d, border), inside);
        if (border_shows && !hn::AllFalse(d, fix)) {
            hn::Store(p, d, prof);
            hn::Store(u, d, ubuf);
            hn::Store(hn::VecFromMask(di, hn::RebindMask(di, fix)), di, bbuf);
            for (size_t l = 0; l < N; ++l)
                if (bbuf[l]) prof[l] = edge_profile(*row.edge, ubuf[l], row.stroke_fullness);
            p = hn::Load(d, prof);
        }
        return p;
    };

    for (int base = 0; base < count; base += static_cast<int>(N)) {
        const V X = hn::Add(hn::Set(d, static_cast<float>(x0 + base)), lane);
        V cover = hn::Zero(d);
        auto inside_n = hn::Zero(di);
        for (int j = 0; j < n; ++j) {
            const float dy = static_cast<float>(y) + (j + 0.5f) * inv_n - row.cy;
            const float dys = dy * row.sy, dyt = dy * row.tyy;
            for (int i = 0; i < n; ++i) {
                const float off = (i + 0.5f) * inv_n;
                V dx = hn::Sub(hn::Add(X, hn::Set(d, off)), hn::Set(d, row.cx));
                V s = hn::Add(hn::Add(hn::Set(d, 0.5f), hn::Mul(dx, hn::Set(d, row.sx))),
                              hn::Set(d, dys));
                V t = hn::Add(hn::Add(hn::Set(d, 0.5f), hn::Mul(dx, hn::Set(d, row.txx))),
                              hn::Set(d, dyt));
                auto in = hn::And(hn::And(hn::Gt(s, hn::Zero(d)), hn::Lt(s, hn::Set(d, 1.0f))),
                                  hn::And(hn::Gt(t, hn::Zero(d)), hn::Lt(t, hn::Set(d, 1.0f))));
                if (hn::AllFalse(d, in)) continue;
                inside_n = hn::Sub(inside_n, hn::VecFromMask(di, hn::RebindMask(di, in)));
                V e = hn::Mul(profile(s, prof_s, us, border_s, in),
                              profile(t, prof_t, ut, border_t, in));
                auto show = hn::And(
                    in, hn::And(hn::Ge(e, hn::Set(d, row.feather_min)), hn::Gt(e, hn::Zero(d))));
                if (hn::AllFalse(d, show)) continue;
                V ns = hn::Add(hn::Mul(s, hn::Set(d, k.frequ_s)), hn::Set(d, k.offset_s));
                V nt = hn::Add(hn::Mul(t, hn::Set(d, k.frequ_t)), hn::Set(d, k.offset_t));
                V x = hn::Mul(FractalNoise(d, ns, nt, row.octaves), e);
                V a;
                if (step) {
                    a = hn::IfThenElseZero(hn::Ge(x, hn::Set(d, row.feather_min)),
                                           hn::Set(d, 1.0f));
                } else {
                    V tt = Clamp01(d, hn::Div(hn::Sub(x, hn::Set(d, row.feather_min)),
                                              hn::Set(d, row.feather_max - row.feather_min)));
                    a = hn::Mul(hn::Mul(tt, tt),
                                hn::Sub(hn::Set(d, 3.0f), hn::Mul(hn::Set(d, 2.0f), tt)));
                }
                a = hn::Min(a, hn::Set(d, max_op));
                cover = hn::Add(cover, hn::IfThenElseZero(show, a));
            }
        }
        V a = hn::Mul(hn::Mul(cover, hn::Set(d, inv_n)), hn::Set(d, inv_n));
        const size_t left = std::min(N, static_cast<size_t>(count - base));
        HWY_ALIGN int32_t ins[kMaxLanes];
        hn::Store(inside_n, di, ins);
        if (hn::AllFalse(d, hn::Gt(a, hn::Zero(d)))) {  // nothing shows: no colour needed
            for (size_t l = 0; l < left; ++l) {
                alpha_out[base + l] = 0.0f;
                r_out[base + l] = g_out[base + l] = b_out[base + l] = 0.0f;
                inside_out[base + l] = ins[l];
            }
            continue;
        }

        // Colour at the pixel centre, from the ramp.
        const float dy = static_cast<float>(y) + 0.5f - row.cy;
        V dx = hn::Sub(hn::Add(X, hn::Set(d, 0.5f)), hn::Set(d, row.cx));
        V s = Clamp01(d, hn::Add(hn::Add(hn::Set(d, 0.5f), hn::Mul(dx, hn::Set(d, row.sx))),
                                 hn::Set(d, dy * row.sy)));
        V t = Clamp01(d, hn::Add(hn::Add(hn::Set(d, 0.5f), hn::Mul(dx, hn::Set(d, row.txx))),
                                 hn::Set(d, dy * row.tyy)));
        const StrokeRamp& ramp = *row.ramp;
        V cr, cg, cb;
        if (!(k.sub_amt > 0.0f)) {
            const Color c = ramp_color(ramp, 0.5f);
            cr = hn::Set(d, c.x), cg = hn::Set(d, c.y), cb = hn::Set(d, c.z);
        } else {
            V nx = hn::Add(hn::Mul(s, hn::Set(d, k.sub_frequ_s)), hn::Set(d, k.offset_t));
            V ny = hn::Add(hn::Mul(t, hn::Set(d, k.sub_frequ_t)), hn::Set(d, k.offset_s));
            V xr = hn::Mul(FractalNoise(d, nx, ny, 1),
                           hn::Set(d, static_cast<float>(StrokeRamp::kSize)));
            auto i = hn::Min(hn::Max(hn::ConvertTo(di, xr), hn::Zero(di)),
                             hn::Set(di, StrokeRamp::kSize - 1));
            V f = hn::Sub(xr, hn::ConvertTo(d, i));
            const RampIndex<decltype(d)> at(d, i);
            cr = hn::Add(at.lookup(ramp.base[0]), hn::Mul(at.lookup(ramp.step[0]), f));
            cg = hn::Add(at.lookup(ramp.base[1]), hn::Mul(at.lookup(ramp.step[1]), f));
            cb = hn::Add(at.lookup(ramp.base[2]), hn::Mul(at.lookup(ramp.step[2]), f));
        }
        HWY_ALIGN float out[4][kMaxLanes];
        hn::Store(a, d, out[0]);
        hn::Store(cr, d, out[1]);
        hn::Store(cg, d, out[2]);
        hn::Store(cb, d, out[3]);
        for (size_t l = 0; l < left; ++l) {
            alpha_out[base + l] = ins[l] ? out[0][l] : 0.0f;
            r_out[base + l] = out[1][l];
            g_out[base + l] = out[2][l];
            b_out[base + l] = out[3][l];
            inside_out[base + l] = ins[l];
        }
    }
}

}  // namespace pleinair::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace pleinair {

HWY_EXPORT(ShadeStrokeRow);

void shade_stroke_row(const StrokeRow& row, int y, int x0, int count, float* alpha, float* r,
                      float* g, float* b, int* inside) {
    HWY_DYNAMIC_DISPATCH(ShadeStrokeRow)(row, y, x0, count, alpha, r, g, b, inside);
}

float stroke_coverage(const StrokeRow& row, int x, int y, int& inside) {
    const int n = row.samples_per_axis;
    const float inv_n = 1.0f / static_cast<float>(n);
    StrokeShaderParams p;  // only the mask's three values are read
    p.stroke_feather_min = row.feather_min;
    p.stroke_feather_max = row.feather_max;
    p.max_stroke_opacity = row.max_opacity;
    float cover = 0.0f;
    inside = 0;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            float dx = static_cast<float>(x) + (i + 0.5f) * inv_n - row.cx;
            float dy = static_cast<float>(y) + (j + 0.5f) * inv_n - row.cy;
            float s = 0.5f + dx * row.sx + dy * row.sy;
            float t = 0.5f + dx * row.txx + dy * row.tyy;
            if (s <= 0.0f || s >= 1.0f || t <= 0.0f || t >= 1.0f) continue;
            ++inside;
            float e = row.edge ? edge_mask(*row.edge, s, t, row.stroke_fullness)
                               : edge_mask(s, t, row.stroke_fullness);
            // noise <= 1: below the lower feather threshold nothing shows.
            if (e < row.feather_min || e <= 0.0f) continue;
            cover += stroke_opacity(p, stroke_noise(*row.k, s, t, row.octaves), e);
        }
    return inside ? cover * inv_n * inv_n : 0.0f;
}

void stroke_pixel_st(const StrokeRow& row, int x, int y, float& s, float& t) {
    float dx = static_cast<float>(x) + 0.5f - row.cx, dy = static_cast<float>(y) + 0.5f - row.cy;
    s = clamp01(0.5f + dx * row.sx + dy * row.sy);
    t = clamp01(0.5f + dx * row.txx + dy * row.tyy);
}

void shade_stroke_row_scalar(const StrokeRow& row, int y, int x0, int count, float* alpha, float* r,
                             float* g, float* b, int* inside) {
    for (int c = 0; c < count; ++c) {
        const int x = x0 + c;
        alpha[c] = stroke_coverage(row, x, y, inside[c]);
        float s, t;
        stroke_pixel_st(row, x, y, s, t);
        Color col = stroke_color(*row.k, *row.ramp, s, t);
        r[c] = col.x, g[c] = col.y, b[c] = col.z;
    }
}

}  // namespace pleinair
#endif
