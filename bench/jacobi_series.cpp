// bench_jacobi_series: sum_k c_k P_k^(p,q)(x) at 1000 points (a sampled field: punch's pressure
// grid), one point at a time (jacobi_series::operator()) against jacobi_series::evaluate, which
// sorts the points by branch and sums four points' recurrences interleaved. Both give the same
// values bit for bit (tests/quadrature/test_jacobi_series.cpp); this measures only the time, per
// point, for the degrees of punch's densities (20 small alpha, 84 an apex near an edge, 200).
// Measured (this machine, Release, 2026-11-21): 26 -> 15, 164 -> 56, 426 -> 135 ns a point.
// Run:
//   build/bin/bench_jacobi_series --benchmark_min_time=0.2
#include <rhabel/quadrature/jacobi_polynomial.hpp>

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstddef>
#include <vector>

namespace {

constexpr std::size_t sample_count = 1000;

struct series_case {
  rhabel::quadrature::jacobi_series<double> series;
  std::vector<double> x, out;
  explicit series_case(std::size_t degree) : x(sample_count), out(sample_count) {
    std::vector<double> c(degree);
    for (std::size_t k = 0; k < degree; ++k) c[k] = std::cos(static_cast<double>(k)) / static_cast<double>(k + 1);
    series = rhabel::quadrature::jacobi_series<double>(c, 0.3, 0.6);  // exponents of a wedge density
    for (std::size_t i = 0; i < sample_count; ++i) x[i] = -1 + 2 * (static_cast<double>(i) + 0.5) / sample_count;
  }
};

void one_point_at_a_time(benchmark::State& state) {
  series_case c(static_cast<std::size_t>(state.range(0)));
  for (auto _ : state) {
    for (std::size_t i = 0; i < sample_count; ++i) c.out[i] = c.series(c.x[i]);
    benchmark::DoNotOptimize(c.out.data());
  }
  state.SetItemsProcessed(static_cast<long long>(state.iterations() * sample_count));
}

void evaluate_batch(benchmark::State& state) {
  series_case c(static_cast<std::size_t>(state.range(0)));
  for (auto _ : state) {
    c.series.evaluate(c.x.data(), c.out.data(), sample_count);
    benchmark::DoNotOptimize(c.out.data());
  }
  state.SetItemsProcessed(static_cast<long long>(state.iterations() * sample_count));
}

}  // namespace

BENCHMARK(one_point_at_a_time)->Arg(20)->Arg(84)->Arg(200);
BENCHMARK(evaluate_batch)->Arg(20)->Arg(84)->Arg(200);
BENCHMARK_MAIN();
