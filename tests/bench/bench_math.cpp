// What the same bytes on every platform cost: pleinair's own elementary functions
// (shading/portable_math.h) against glibc's, in nanoseconds per call over the same 4096
// arguments, double and float, measured in one run. Figures: BENCHMARKS.md.
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "shading/portable_math.h"

namespace {

template <typename T>
const std::vector<T>& args(double lo, double hi) {
    static std::vector<T> v;
    v.resize(4096);
    for (size_t i = 0; i < v.size(); ++i)
        v[i] = static_cast<T>(lo + (hi - lo) * (static_cast<double>(i) + 0.5) / 4096.0);
    return v;
}

template <typename T, typename F>
void run(benchmark::State& state, double lo, double hi, F f) {
    const std::vector<T> x = args<T>(lo, hi);
    for (auto _ : state)
        for (T v : x) benchmark::DoNotOptimize(f(v));
    // Seconds per call, printed in ns.
    state.counters["per_call"] =
        benchmark::Counter(static_cast<double>(state.iterations() * x.size()),
                           benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

namespace pm = pleinair::pmath;

double pm_sincos(double x) {
    double s, c;
    pm::sincos(x, s, c);
    return s + c;
}

#define PAIR(name, T, lo, hi, mine, libm)            \
    void BM_##name##_pleinair(benchmark::State& s) { \
        run<T>(s, lo, hi, [](T x) { return mine; }); \
    }                                                \
    void BM_##name##_libm(benchmark::State& s) {     \
        run<T>(s, lo, hi, [](T x) { return libm; }); \
    }                                                \
    BENCHMARK(BM_##name##_pleinair);                 \
    BENCHMARK(BM_##name##_libm);

PAIR(sin, double, -10, 10, pm::sin(x), std::sin(x))
PAIR(sincos, double, -10, 10, pm_sincos(x), std::sin(x) + std::cos(x))
PAIR(exp, double, -20, 20, pm::exp(x), std::exp(x))
PAIR(log, double, 1e-3, 1e3, pm::log(x), std::log(x))
PAIR(pow, double, 1e-3, 1, pm::pow(x, 2.4), std::pow(x, 2.4))
PAIR(atan2, double, -5, 5, pm::atan2(x, 0.7), std::atan2(x, 0.7))
PAIR(sinf, float, -10, 10, pm::sin(x), std::sin(x))
PAIR(powf, float, 1e-3, 1, pm::pow(x, 1.0f / 2.4f), std::pow(x, 1.0f / 2.4f))

}  // namespace

BENCHMARK_MAIN();
