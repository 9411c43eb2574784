// Elementary functions (sin, cos, exp, log, pow, atan2, ...) computed from IEEE-754 additions,
// multiplications, divisions and square roots only, so their bits are the same with any C
// library, compiler or CPU. libm's are not correctly rounded and differ by an ulp between
// implementations; wherever such a value decides a stroke, a level or a colour, it decides the
// image's bytes. Every value pleinair paints goes through these instead.
//
// The polynomials are fdlibm's (Sun Microsystems, 1993; freely usable with its notice), the
// reductions Cody and Waite's. Accuracy, measured against glibc in portable_math_test.cpp: within
// 2 ulp in double for the arguments a scene holds, so the float overloads (computed in double,
// rounded once) are nearly always correctly rounded. Speed against libm:
// tests/bench/bench_math.cpp. Nothing here is contracted into FMA (the build passes
// -ffp-contract=off): fusing would change the bits between CPUs with and without it.
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>

namespace pleinair::pmath {

inline constexpr double kPi = 3.14159265358979311600e+00;
inline constexpr double kPiLo = 1.22464679914735317720e-16;  // pi - kPi
inline constexpr double kHalfPi = 1.57079632679489655800e+00;
inline constexpr double kHalfPiLo = 6.12323399573676588613e-17;

namespace detail {

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
inline constexpr double kInf = std::numeric_limits<double>::infinity();

// x rounded to the nearest integer, ties to even, for |x| < 2^51: adding and subtracting 1.5 2^52
// leaves no fraction bits. Exact, and inlined where std::floor is a libm call on baseline x86-64.
inline double round_to_int(double x) {
    constexpr double kShift = 6755399441055744.0;  // 1.5 * 2^52
    return (x + kShift) - kShift;
}

// 2^k for -1022 <= k <= 1023, from its bits.
inline double pow2(int k) { return std::bit_cast<double>(static_cast<uint64_t>(k + 1023) << 52); }

// y 2^k, exact (as std::ldexp, inlined): two steps where 2^k alone would not be a normal double.
inline double scale(double y, int k) {
    if (k >= -1022 && k <= 1023) return y * pow2(k);
    if (k > 1023) return y * pow2(1023) * pow2(k - 1023 > 1023 ? 1023 : k - 1023);
    return y * pow2(-1022) * pow2(k + 1022 < -1022 ? -1022 : k + 1022);
}

// ln 2 in two parts: the high one has its low 32 bits zero, so k * kLn2Hi is exact for |k| < 2^20.
inline constexpr double kLn2Hi = 6.93147180369123816490e-01;
inline constexpr double kLn2Lo = 1.90821492927058770002e-10;
inline constexpr double kInvLn2 = 1.44269504088896338700e+00;

// sin and cos of |r| <= pi/4 (fdlibm's __kernel_sin and __kernel_cos).
inline double sin_kernel(double r) {
    const double z = r * r;
    const double p = 8.33333333332248946124e-03 +
                     z * (-1.98412698298579493134e-04 +
                          z * (2.75573137070700676789e-06 +
                               z * (-2.50507602534068634195e-08 + z * 1.58969099521155010221e-10)));
    return r + r * z * (-1.66666666666666324348e-01 + z * p);
}

inline double cos_kernel(double r) {
    const double z = r * r;
    const double p =
        z * (4.16666666666666019037e-02 +
             z * (-1.38888888888741095749e-03 +
                  z * (2.48015872894767294178e-05 +
                       z * (-2.75573143513906633035e-07 +
                            z * (2.08757232129817482790e-09 + z * -1.13596475577881948265e-11)))));
    // 1 - z/2 + z p, with 1 - z/2 split so that its rounding error is added back.
    const double hz = 0.5 * z, w = 1.0 - hz;
    return w + (((1.0 - w) - hz) + z * p);
}

// x = k pi/2 + r with |r| <= about pi/4 and q = k mod 4, by Cody and Waite's reduction with
// pi/2 in three parts of 33, 33 and 53 bits: the first two products are exact for |k| < 2^20
// (|x| < 1.6e6), beyond any angle a scene holds. Larger x are first brought into [0, 2 pi) by
// fmod, which is exact; the result stays a deterministic function of x, only less accurate.
inline double reduce_half_pi(double x, int& q) {
    if (std::fabs(x) > 1e6) x = std::fmod(x, 2 * kPi);
    const double k = round_to_int(x * 6.36619772367581382433e-01);
    const double r = (x - k * 1.57079632673412561417e+00) - k * 6.07710050630396597660e-11;
    q = static_cast<int>(static_cast<int64_t>(k) & 3);
    return r - k * 2.02226624871116645580e-21;
}

// atan of 0 <= t < 2^66 (fdlibm's s_atan): five intervals, each with a polynomial in its offset.
inline double atan_positive(double t) {
    static constexpr double kHi[] = {4.63647609000806093515e-01, 7.85398163397448278999e-01,
                                     9.82793723247329054082e-01, 1.57079632679489655800e+00};
    static constexpr double kLo[] = {2.26987774529616870924e-17, 3.06161699786838301793e-17,
                                     1.39033110312309984516e-17, 6.12323399573676603587e-17};
    int id;
    double x = t;
    if (t < 0.4375) {
        if (t < 3.7252902984e-09) return t;  // 2^-28: atan t = t to the last bit
        id = -1;
    } else if (t < 1.1875) {
        if (t < 0.6875)
            id = 0, x = (2.0 * t - 1.0) / (2.0 + t);
        else
            id = 1, x = (t - 1.0) / (t + 1.0);
    } else if (t < 2.4375) {
        id = 2, x = (t - 1.5) / (1.0 + 1.5 * t);
    } else {
        id = 3, x = -1.0 / t;
    }
    const double z = x * x, w = z * z;
    const double s1 =
        z * (3.33333333333329318027e-01 +
             w * (1.42857142725034663711e-01 +
                  w * (9.09088713343650656196e-02 +
                       w * (6.66107313738753120669e-02 +
                            w * (4.97687799461593236017e-02 + w * 1.62858201153657823623e-02)))));
    const double s2 =
        w * (-1.99999999998764832476e-01 +
             w * (-1.11111104054623557880e-01 +
                  w * (-7.69187620504482999495e-02 +
                       w * (-5.83357013379057348645e-02 + w * -3.65315727442169155270e-02))));
    if (id < 0) return x - x * (s1 + s2);
    return kHi[id] - ((x * (s1 + s2) - kLo[id]) - x);
}

}  // namespace detail

inline void sincos(double x, double& s, double& c) {
    if (!std::isfinite(x)) {
        s = c = detail::kNaN;
        return;
    }
    int q;
    const double r = detail::reduce_half_pi(x, q);
    const double sr = detail::sin_kernel(r), cr = detail::cos_kernel(r);
    switch (q) {
        case 0:
            s = sr, c = cr;
            break;
        case 1:
            s = cr, c = -sr;
            break;
        case 2:
            s = -sr, c = -cr;
            break;
        default:
            s = -cr, c = sr;
            break;
    }
}

// sin and cos alone evaluate only the kernel their quadrant needs (the same bits as sincos).
inline double sin(double x) {
    if (!std::isfinite(x)) return detail::kNaN;
    int q;
    const double r = detail::reduce_half_pi(x, q);
    const double v = q & 1 ? detail::cos_kernel(r) : detail::sin_kernel(r);
    return q & 2 ? -v : v;
}

inline double cos(double x) {
    if (!std::isfinite(x)) return detail::kNaN;
    int q;
    const double r = detail::reduce_half_pi(x, q);
    const double v = q & 1 ? detail::sin_kernel(r) : detail::cos_kernel(r);
    return (q == 1 || q == 2) ? -v : v;
}

inline double tan(double x) {
    double s, c;
    sincos(x, s, c);
    return s / c;
}

inline double exp(double x) {
    if (std::isnan(x)) return x;
    if (x > 709.782712893384) return detail::kInf;
    if (x < -745.1332191019412) return 0.0;
    // x = k ln2 + r, |r| <= ln2 / 2; e^r by fdlibm's rational form, scaled by 2^k exactly.
    const double k = detail::round_to_int(x * detail::kInvLn2);
    const double hi = x - k * detail::kLn2Hi, lo = k * detail::kLn2Lo;
    const double r = hi - lo, z = r * r;
    const double c =
        r - z * (1.66666666666666019037e-01 +
                 z * (-2.77777777770155933842e-03 +
                      z * (6.61375632143793436117e-05 +
                           z * (-1.65339022054652515390e-06 + z * 4.13813679705723846039e-08))));
    const double y = 1.0 - ((lo - (r * c) / (2.0 - c)) - hi);
    return detail::scale(y, static_cast<int>(k));
}

inline double exp2(double x) {
    if (std::isnan(x)) return x;
    if (x >= 1024.0) return detail::kInf;
    if (x < -1080.0) return 0.0;
    // 2^x = 2^k e^{(x - k) ln 2}: x - k is exact, so powers of two come out exact.
    const double k = detail::round_to_int(x);
    return detail::scale(exp((x - k) * 6.93147180559945286227e-01), static_cast<int>(k));
}

namespace detail {
// log x for finite x > 0 as k ln2 + log(1 + f), sqrt(1/2) <= 1 + f < sqrt(2) (fdlibm's e_log);
// returns log(1 + f) alone in `rest` so log2 can add k exactly.
inline double log_parts(double x, int& k) {
    // x = m 2^k with 1 <= m < 2, from the bits (subnormals scaled up first), then
    // sqrt(1/2) <= m < sqrt(2).
    int bias = 1023;
    if (x < 2.2250738585072014e-308) x *= 18014398509481984.0, bias += 54;  // 2^54
    const uint64_t bits = std::bit_cast<uint64_t>(x);
    k = static_cast<int>(bits >> 52) - bias;
    double m = std::bit_cast<double>((bits & 0x000fffffffffffffull) | 0x3ff0000000000000ull);
    if (m > 1.41421356237309514547) m *= 0.5, ++k;
    const double f = m - 1.0, s = f / (2.0 + f);
    const double z = s * s, w = z * z;
    const double t1 = w * (3.999999999940941908e-01 +
                           w * (2.222219843214978396e-01 + w * 1.531383769920937332e-01));
    const double t2 = z * (6.666666666666735130e-01 +
                           w * (2.857142874366239149e-01 +
                                w * (1.818357216161805012e-01 + w * 1.479819860511658591e-01)));
    const double hfsq = 0.5 * f * f;
    return f - (hfsq - s * (hfsq + t1 + t2));
}
}  // namespace detail

inline double log(double x) {
    if (!(x > 0.0)) return x == 0.0 ? -detail::kInf : detail::kNaN;
    if (x == detail::kInf) return x;
    int k;
    const double f = detail::log_parts(x, k);
    // k ln2_hi is exact; the low part joins the small terms first.
    return k * detail::kLn2Hi + (f + k * detail::kLn2Lo);
}

inline double log2(double x) {
    if (!(x > 0.0)) return x == 0.0 ? -detail::kInf : detail::kNaN;
    if (x == detail::kInf) return x;
    int k;
    const double f = detail::log_parts(x, k);
    return k + f * detail::kInvLn2;  // powers of two give k exactly
}

// x^y for x >= 0 (what pleinair needs: gamma, bias, growth laws); NaN for x < 0.
inline double pow(double x, double y) {
    if (std::isnan(x) || std::isnan(y) || x < 0.0) return detail::kNaN;
    if (y == 0.0 || x == 1.0) return 1.0;
    if (x == 0.0) return y > 0.0 ? 0.0 : detail::kInf;
    return exp(y * log(x));
}

inline double atan(double x) {
    if (std::isnan(x)) return x;
    const double a = std::fabs(x) < 7.3786976294838206e19 ? detail::atan_positive(std::fabs(x))
                                                          : kHalfPi + kHalfPiLo;
    return x < 0 ? -a : a;
}

// The angle of (x, y) in (-pi, pi], with atan2(+-0, x) = +-0 for x >= 0 and +-pi for x < 0.
inline double atan2(double y, double x) {
    if (std::isnan(x) || std::isnan(y)) return x + y;
    const double ax = std::fabs(x), ay = std::fabs(y);
    double a;
    if (ay == 0.0) {
        a = std::signbit(x) ? kPi : 0.0;
    } else if (ax == detail::kInf && ay == detail::kInf) {
        a = std::signbit(x) ? 3.0 * kPi / 4.0 : kPi / 4.0;
    } else if (ay <= ax) {
        a = atan(ay / ax);
        if (std::signbit(x)) a = kPi - (a - kPiLo);
    } else {
        a = kHalfPi - (atan(ax / ay) - kHalfPiLo);
        if (std::signbit(x)) a = kPi - (a - kPiLo);
    }
    return std::signbit(y) ? -a : a;
}

inline double asin(double x) {
    if (!(std::fabs(x) <= 1.0)) return detail::kNaN;
    return atan2(x, std::sqrt((1.0 - x) * (1.0 + x)));
}

inline double acos(double x) {
    if (!(std::fabs(x) <= 1.0)) return detail::kNaN;
    return atan2(std::sqrt((1.0 - x) * (1.0 + x)), x);
}

inline double cbrt(double x) {
    if (x == 0.0 || !std::isfinite(x)) return x;
    const double a = std::fabs(x);
    double y = exp(log(a) / 3.0);
    y -= (y * y * y - a) / (3.0 * y * y);  // one Newton step: the guess is good to ~1e-15
    return x < 0 ? -y : y;
}

// sqrt(x^2 + y^2) without overflow or underflow in the squares.
inline double hypot(double x, double y) {
    double a = std::fabs(x), b = std::fabs(y);
    if (a == detail::kInf || b == detail::kInf) return detail::kInf;
    if (std::isnan(a) || std::isnan(b)) return a + b;
    if (a < b) std::swap(a, b);
    if (a == 0.0) return 0.0;
    const double r = b / a;
    return a * std::sqrt(1.0 + r * r);
}

// Single precision: computed in double and rounded once.
inline float sin(float x) { return static_cast<float>(sin(static_cast<double>(x))); }
inline float cos(float x) { return static_cast<float>(cos(static_cast<double>(x))); }
inline float tan(float x) { return static_cast<float>(tan(static_cast<double>(x))); }
inline float exp(float x) { return static_cast<float>(exp(static_cast<double>(x))); }
inline float exp2(float x) { return static_cast<float>(exp2(static_cast<double>(x))); }
inline float log(float x) { return static_cast<float>(log(static_cast<double>(x))); }
inline float log2(float x) { return static_cast<float>(log2(static_cast<double>(x))); }
inline float pow(float x, float y) {
    return static_cast<float>(pow(static_cast<double>(x), static_cast<double>(y)));
}
inline float atan(float x) { return static_cast<float>(atan(static_cast<double>(x))); }
inline float atan2(float y, float x) {
    return static_cast<float>(atan2(static_cast<double>(y), static_cast<double>(x)));
}
inline float asin(float x) { return static_cast<float>(asin(static_cast<double>(x))); }
inline float acos(float x) { return static_cast<float>(acos(static_cast<double>(x))); }
inline float cbrt(float x) { return static_cast<float>(cbrt(static_cast<double>(x))); }
inline float hypot(float x, float y) {
    return static_cast<float>(hypot(static_cast<double>(x), static_cast<double>(y)));
}

}  // namespace pleinair::pmath
