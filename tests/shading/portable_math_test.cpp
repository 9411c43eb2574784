// pleinair's own elementary functions: accurate against glibc, exact where they must be, defined
// at every edge, and bit-for-bit the same on every platform (their fingerprints below).
#include "shading/portable_math.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <regex>
#include <sstream>
#include <string>

namespace pleinair {
namespace {

namespace pm = pmath;

// Distance in representable doubles (same sign assumed; 0 for equal values).
double ulps(double got, double want) {
    if (got == want) return 0;
    const double gap = std::nextafter(std::fabs(want), HUGE_VAL) - std::fabs(want);
    return std::fabs(got - want) / gap;
}

// Arguments spread evenly over [lo, hi], from a fixed integer sequence (no libm in the spread).
double arg(int i, int n, double lo, double hi) { return lo + (hi - lo) * (i + 0.5) / n; }

struct Case {
    const char* name;
    std::function<double(double)> mine, libm;
    double lo, hi, max_ulps;
};

TEST(PortableMath, WithinAFewUlpsOfGlibcOverTheRangesASceneUses) {
    const Case cases[] = {
        {"sin", [](double x) { return pm::sin(x); }, [](double x) { return std::sin(x); }, -100,
         100, 2},
        {"sin large", [](double x) { return pm::sin(x); }, [](double x) { return std::sin(x); },
         1e4, 1e6, 2},
        {"cos", [](double x) { return pm::cos(x); }, [](double x) { return std::cos(x); }, -100,
         100, 2},
        {"tan", [](double x) { return pm::tan(x); }, [](double x) { return std::tan(x); }, -1.5,
         1.5, 3},
        {"exp", [](double x) { return pm::exp(x); }, [](double x) { return std::exp(x); }, -700,
         700, 2},
        {"exp2", [](double x) { return pm::exp2(x); }, [](double x) { return std::exp2(x); }, -60,
         60, 2},
        {"log", [](double x) { return pm::log(x); }, [](double x) { return std::log(x); }, 1e-300,
         1e300, 2},
        {"log near 1", [](double x) { return pm::log(x); }, [](double x) { return std::log(x); },
         0.5, 2, 2},
        {"log2", [](double x) { return pm::log2(x); }, [](double x) { return std::log2(x); }, 1e-10,
         1e10, 2},
        {"atan", [](double x) { return pm::atan(x); }, [](double x) { return std::atan(x); }, -50,
         50, 2},
        {"asin", [](double x) { return pm::asin(x); }, [](double x) { return std::asin(x); }, -1, 1,
         2},
        {"acos", [](double x) { return pm::acos(x); }, [](double x) { return std::acos(x); }, -1, 1,
         2},
        {"cbrt", [](double x) { return pm::cbrt(x); }, [](double x) { return std::cbrt(x); }, -1e6,
         1e6, 3},
        {"hypot", [](double x) { return pm::hypot(x, 0.37 * x + 1.0); },
         [](double x) { return std::hypot(x, 0.37 * x + 1.0); }, -1e3, 1e3, 2},
        // x^y as e^(y log x): log's last-bit error is multiplied by |y log x|, so for the gamma
        // exponent over six decades 32 ulps (7e-15 relative), still 1e7 times finer than a float.
        {"pow 2.4", [](double x) { return pm::pow(x, 2.4); },
         [](double x) { return std::pow(x, 2.4); }, 1e-6, 1, 32},
        {"pow 1/2.4", [](double x) { return pm::pow(x, 1 / 2.4); },
         [](double x) { return std::pow(x, 1 / 2.4); }, 1e-6, 1, 8},
    };
    for (const Case& c : cases) {
        double worst = 0, at = 0;
        const int n = 200000;
        for (int i = 0; i < n; ++i) {
            const double x = c.lo > 0 ? std::exp(arg(i, n, std::log(c.lo), std::log(c.hi)))
                                      : arg(i, n, c.lo, c.hi);
            const double u = ulps(c.mine(x), c.libm(x));
            if (u > worst) worst = u, at = x;
        }
        EXPECT_LE(worst, c.max_ulps) << c.name << " at " << at;
        RecordProperty(std::string(c.name) + " max ulps", std::to_string(worst));
    }
}

TEST(PortableMath, Atan2InEveryQuadrantAndOnTheAxes) {
    for (int i = 0; i < 3600; ++i) {
        const double a = -3.14 + 6.28 * i / 3600.0;
        for (double r : {1e-3, 1.0, 1e5}) {
            const double x = r * std::cos(a), y = r * std::sin(a);
            EXPECT_LE(ulps(pm::atan2(y, x), std::atan2(y, x)), 2) << x << ", " << y;
        }
    }
    EXPECT_EQ(pm::atan2(0.0, 1.0), 0.0);
    EXPECT_TRUE(std::signbit(pm::atan2(-0.0, 1.0)));
    EXPECT_EQ(pm::atan2(0.0, -1.0), pm::kPi);
    EXPECT_EQ(pm::atan2(-0.0, -1.0), -pm::kPi);
    EXPECT_EQ(pm::atan2(1.0, 0.0), pm::kHalfPi);
    EXPECT_EQ(pm::atan2(-1.0, 0.0), -pm::kHalfPi);
    EXPECT_EQ(pm::atan2(1.0, 1.0), std::atan2(1.0, 1.0));
    EXPECT_TRUE(std::isnan(pm::atan2(std::nan(""), 1.0)));
}

TEST(PortableMath, ExactWhereTheMathematicsIs) {
    EXPECT_EQ(pm::sin(0.0), 0.0);
    EXPECT_EQ(pm::cos(0.0), 1.0);
    EXPECT_EQ(pm::exp(0.0), 1.0);
    EXPECT_EQ(pm::log(1.0), 0.0);
    EXPECT_EQ(pm::pow(1.0, 7.3), 1.0);
    EXPECT_EQ(pm::pow(0.3, 0.0), 1.0);
    EXPECT_EQ(pm::pow(0.0, 2.4), 0.0);
    EXPECT_EQ(pm::cbrt(27.0), 3.0);
    EXPECT_EQ(pm::cbrt(-8.0), -2.0);
    EXPECT_EQ(pm::hypot(3.0, 4.0), 5.0);
    EXPECT_EQ(pm::atan(1.0), pm::kPi / 4);
    for (int k = -1070; k <= 1023; ++k) {
        EXPECT_EQ(pm::log2(std::ldexp(1.0, k)), k) << k;
        EXPECT_EQ(pm::exp2(static_cast<double>(k)), std::ldexp(1.0, k)) << k;
    }
    // Float overloads round the double once, so they are correctly rounded but for the rare
    // argument whose value lies within a few double ulps of a float's rounding boundary.
    int differ = 0;
    for (int i = 0; i < 100000; ++i) {
        const float x = static_cast<float>(arg(i, 100000, -10, 10)), p = std::fabs(x) + 1e-3f;
        const auto rounded = [](double v) { return static_cast<float>(v); };
        differ += pm::sin(x) != rounded(std::sin(double(x)));
        differ += pm::exp(x) != rounded(std::exp(double(x)));
        differ += pm::log(p) != rounded(std::log(double(p)));
        differ += pm::pow(p, 2.4f) != rounded(std::pow(double(p), double(2.4f)));
        differ += pm::atan2(x, 2.0f) != rounded(std::atan2(double(x), 2.0));
    }
    EXPECT_LE(differ, 2);
}

TEST(PortableMath, DefinedAtEveryEdge) {
    const double inf = HUGE_VAL;
    EXPECT_TRUE(std::isnan(pm::sin(inf)));
    EXPECT_TRUE(std::isnan(pm::cos(NAN)));
    EXPECT_EQ(pm::exp(1000.0), inf);
    EXPECT_EQ(pm::exp(-1000.0), 0.0);
    EXPECT_EQ(pm::exp2(2000.0), inf);
    EXPECT_EQ(pm::exp2(-2000.0), 0.0);
    EXPECT_EQ(pm::log(0.0), -inf);
    EXPECT_EQ(pm::log(inf), inf);
    EXPECT_TRUE(std::isnan(pm::log(-1.0)));
    EXPECT_EQ(pm::log(4.9e-324), std::log(4.9e-324));  // the smallest subnormal
    EXPECT_TRUE(std::isnan(pm::pow(-2.0, 2.0)));
    EXPECT_EQ(pm::pow(0.0, -1.0), inf);
    EXPECT_TRUE(std::isnan(pm::asin(1.0000001)));
    EXPECT_EQ(pm::asin(1.0), pm::kHalfPi);
    EXPECT_EQ(pm::acos(1.0), 0.0);
    EXPECT_EQ(pm::acos(-1.0), pm::kPi);
    EXPECT_EQ(pm::atan(inf), pm::kHalfPi);
    EXPECT_LE(ulps(pm::hypot(1e300, 1e300), std::hypot(1e300, 1e300)), 1);
    EXPECT_LE(ulps(pm::hypot(1e-300, 1e-300), std::hypot(1e-300, 1e-300)), 1);
    EXPECT_EQ(pm::hypot(inf, std::nan("")), inf);
    EXPECT_EQ(pm::cbrt(-inf), -inf);
    // Huge angles: finite, in range, and deterministic (no libm behind them).
    for (double x : {1e7, -3.3e12, 1e300}) {
        const double s = pm::sin(x), c = pm::cos(x);
        EXPECT_TRUE(std::fabs(s) <= 1 && std::fabs(c) <= 1) << x;
        EXPECT_NEAR(s * s + c * c, 1.0, 1e-15) << x;
    }
}

// FNV-1a over the bits of each function on 4096 fixed arguments. These fingerprints are the
// byte-identity promise made checkable: on any platform, compiler or C library they must come
// out the same, and a change that moves one bit of one value moves one of them. They were
// recorded on x86-64 (GCC 12 and Clang 14, glibc 2.36); a deliberate change to a function
// records them again.
uint64_t fingerprint(const std::function<double(double)>& f, double lo, double hi) {
    uint64_t h = 1469598103934665603ull;
    for (int i = 0; i < 4096; ++i) {
        const double y = f(arg(i, 4096, lo, hi));
        uint64_t bits;
        std::memcpy(&bits, &y, sizeof bits);
        for (int b = 0; b < 8; ++b) h = (h ^ ((bits >> (8 * b)) & 0xff)) * 1099511628211ull;
    }
    return h;
}

TEST(PortableMath, SameBitsOnEveryPlatform) {
    const struct {
        const char* name;
        uint64_t bits;
    } want[] = {
        {"sincos", 0xb71bccba5c8e42a6ull}, {"exp", 0x19cc74b8fcfa8e46ull},
        {"log", 0x902f40fbd7871d8aull},    {"pow", 0x6b49ce6c2ceb8badull},
        {"atan2", 0x4836ef261af86223ull},  {"asin", 0x729e65ac0d2f5fd6ull},
        {"cbrt", 0xcd1a6280b89cb586ull},   {"float", 0x63c4a50f1ef106c2ull},
    };
    const uint64_t got[] = {
        fingerprint([](double x) { return pm::sin(x) + 3 * pm::cos(x); }, -50, 50),
        fingerprint([](double x) { return pm::exp(x) + pm::exp2(x); }, -30, 30),
        fingerprint([](double x) { return pm::log(x) + pm::log2(x); }, 1e-5, 1e5),
        fingerprint([](double x) { return pm::pow(x, 2.4) + pm::pow(x, 1 / 2.4); }, 0, 1),
        fingerprint([](double x) { return pm::atan2(x, 1.5 - x * x) + pm::atan(x); }, -4, 4),
        fingerprint([](double x) { return pm::asin(x) + pm::acos(x) + pm::tan(x); }, -1, 1),
        fingerprint([](double x) { return pm::cbrt(x) + pm::hypot(x, 2.0); }, -100, 100),
        fingerprint(
            [](double x) {
                const float f = static_cast<float>(x);
                return double(pm::sin(f)) + pm::cos(f) + pm::pow(f, 0.7f) + pm::atan2(f, 1.0f);
            },
            0, 10),
    };
    for (size_t i = 0; i < std::size(want); ++i)
        EXPECT_EQ(got[i], want[i].bits) << want[i].name << ": 0x" << std::hex << got[i];
}

// What keeps the promise: no code that computes what pleinair paints calls libm's (or glm's)
// transcendental functions; pmath's are called instead. Comments are skipped.
TEST(PortableMath, NoLibmTranscendentalsInTheLibraries) {
    const std::regex call(
        R"(((^|[^\w.>:]|std::)(sin|cos|tan|sincos|exp|exp2|expm1|log|log2|log10|log1p|pow|atan|)"
        R"(atan2|asin|acos|cbrt|hypot|sinh|cosh|tanh|erf|erfc)f?|glm::(sin|cos|tan|exp|exp2|)"
        R"(log|log2|pow|atan|asin|acos|rotate|angleAxis|perspective|slerp))\s*\()");
    const std::filesystem::path root = PLEINAIR_SOURCE_DIR;
    int files = 0;
    for (const char* dir : {"generators", "pipeline", "shading"}) {
        for (const auto& entry : std::filesystem::recursive_directory_iterator(root / dir)) {
            const auto ext = entry.path().extension();
            if (ext != ".cpp" && ext != ".h") continue;
            if (entry.path().filename() == "portable_math.h") continue;
            ++files;
            std::ifstream in(entry.path());
            std::string line;
            for (int n = 1; std::getline(in, line); ++n) {
                const auto comment = line.find("//");
                if (comment != std::string::npos) line.erase(comment);
                std::smatch m;
                if (std::regex_search(line, m, call))
                    ADD_FAILURE() << entry.path().lexically_relative(root).string() << ":" << n
                                  << ": " << m[1] << " is libm's; pmath has its own";
            }
        }
    }
    EXPECT_GT(files, 50);
}

}  // namespace
}  // namespace pleinair
