// bench_gauss_jacobi: cost of rhabel::quadrature::gauss_jacobi<double> against GSL's fixed
// Jacobi rule (gsl_integration_fixed_jacobi, Golub-Welsch), with the accuracy of both printed
// once, outside the timed loops.
//
// Targets (from the issue; measured, never asserted): n = 10^6 <= 100 ms and n = 10^4 <= 1 ms
// single-threaded, and >= 100x faster than GSL at n = 4000; small rules (n = 8, the recurrence
// path) compared with GSL as well. rhabel_other_exponents covers generic exponents (2p + 1 or
// 2q + 1 outside {0, 1/2, 1, 3/2, 2}: (-0.9, 0.3), (0.3, 0.7), (-0.5, 2.2), (4.5, -0.7)) and
// large ones ((30, 0), (5, 5)); their accuracy at n = 4000 is printed first.
//
// GSL's convention: gsl_integration_fixed_alloc(gsl_integration_fixed_jacobi, n, a, b, alpha, beta)
// integrates with the weight (b - x)^alpha (x - a)^beta on (a, b), so alpha is rhabel's p
// (the exponent at the upper end) and beta is q.
//
// Accuracy reference: rhabel's recurrence path (gauss_jacobi_method::recurrence: Newton on the
// three-term recurrence in long double, O(n^2)), which matches the committed 60-digit table to
// 0.5 eps at n = 101 (tests/quadrature/test_gauss_jacobi.cpp). Run:
//   build/bin/bench_gauss_jacobi --benchmark_min_time=0.2
#include <rhabel/quadrature/gauss_jacobi.hpp>

#include <benchmark/benchmark.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace {

using rhabel::quadrature::gauss_jacobi;
using rhabel::quadrature::gauss_jacobi_method;
using rhabel::quadrature::gauss_jacobi_options;

constexpr double p_exponent = 0.25, q_exponent = -0.5;

void rhabel_rule(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  for (auto _ : state) {
    auto rule = gauss_jacobi<double>(n, p_exponent, q_exponent);
    benchmark::DoNotOptimize(rule.weight.data());
  }
  state.SetComplexityN(state.range(0));
}

void rhabel_legendre(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  for (auto _ : state) {
    auto rule = gauss_jacobi<double>(n, 0.0, 0.0);
    benchmark::DoNotOptimize(rule.weight.data());
  }
}

// The exponent pairs of the performance issue: (p, q) = (-0.5, 0) (range(1) = 0) and (0.25, 0) (= 1).
void rhabel_pairs(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const double p = state.range(1) == 0 ? -0.5 : 0.25;
  for (auto _ : state) {
    auto rule = gauss_jacobi<double>(n, p, 0.0);
    benchmark::DoNotOptimize(rule.weight.data());
  }
}

// Generic exponents (2p + 1, 2q + 1 not in {0, 1/2, 1, 3/2, 2}: the interior weight factor
// s^(2p+1) c^(2q+1) is formed per batch, detail/gauss_jacobi_power.hpp) and large ones:
// range(1) indexes other_pairs.
constexpr double other_pairs[][2] = {{-0.9, 0.3}, {0.3, 0.7}, {-0.5, 2.2}, {4.5, -0.7}, {30.0, 0.0}, {5.0, 5.0}};

void rhabel_other_exponents(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const double p = other_pairs[state.range(1)][0], q = other_pairs[state.range(1)][1];
  for (auto _ : state) {
    auto rule = gauss_jacobi<double>(n, p, q);
    benchmark::DoNotOptimize(rule.weight.data());
  }
  state.SetLabel("p = " + std::to_string(p).substr(0, 5) + ", q = " + std::to_string(q).substr(0, 5));
}

void gsl_fixed_jacobi(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  for (auto _ : state) {
    gsl_integration_fixed_workspace* workspace =
        gsl_integration_fixed_alloc(gsl_integration_fixed_jacobi, n, -1.0, 1.0, p_exponent, q_exponent);
    benchmark::DoNotOptimize(gsl_integration_fixed_weights(workspace));
    gsl_integration_fixed_free(workspace);
  }
}

BENCHMARK(rhabel_rule)->Arg(8)->Arg(40)->Arg(41)->Arg(100)->Arg(101)->Arg(1000)->Arg(4000)->Arg(10000)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond);
BENCHMARK(rhabel_legendre)->Arg(10000)->Arg(1000000)->Unit(benchmark::kMillisecond);
BENCHMARK(rhabel_pairs)
    ->ArgsProduct({{8, 100, 1000, 10000, 1000000}, {0, 1}})
    ->Unit(benchmark::kMillisecond);
BENCHMARK(rhabel_other_exponents)
    ->ArgsProduct({{10000, 1000000}, {0, 1, 2, 3, 4, 5}})
    ->Unit(benchmark::kMillisecond);
BENCHMARK(gsl_fixed_jacobi)->Arg(8)->Arg(100)->Arg(1000)->Arg(4000)->Unit(benchmark::kMillisecond);

// Max relative weight error of rhabel's default rule and of GSL's rule at n, against the
// recurrence path; also the max relative error of min(1 - x, 1 + x) (GSL gives only x).
void print_accuracy(std::size_t n, double p, double q, bool with_gsl) {
  const auto reference = gauss_jacobi<double>(n, p, q, gauss_jacobi_options{gauss_jacobi_method::recurrence});
  const auto rule = gauss_jacobi<double>(n, p, q);
  gsl_integration_fixed_workspace* workspace =
      with_gsl ? gsl_integration_fixed_alloc(gsl_integration_fixed_jacobi, n, -1.0, 1.0, p, q) : nullptr;
  const double* gsl_x = with_gsl ? gsl_integration_fixed_nodes(workspace) : nullptr;
  const double* gsl_w = with_gsl ? gsl_integration_fixed_weights(workspace) : nullptr;
  double rhabel_weight = 0, gsl_weight = 0, rhabel_node = 0, gsl_node = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double w = reference.weight[i];
    rhabel_weight = std::max(rhabel_weight, std::fabs(rule.weight[i] / w - 1));
    const bool right = reference.hi_minus_x[i] <= reference.x_minus_lo[i];
    const double near = right ? reference.hi_minus_x[i] : reference.x_minus_lo[i];
    const double rhabel_near = right ? rule.hi_minus_x[i] : rule.x_minus_lo[i];
    rhabel_node = std::max(rhabel_node, std::fabs(rhabel_near / near - 1));
    if (with_gsl) {
      gsl_weight = std::max(gsl_weight, std::fabs(gsl_w[i] / w - 1));
      const double gsl_near = right ? 1 - gsl_x[i] : 1 + gsl_x[i];
      gsl_node = std::max(gsl_node, std::fabs(gsl_near / near - 1));
    }
  }
  if (with_gsl) {
    gsl_integration_fixed_free(workspace);
    std::printf("n = %zu, p = %g, q = %g: max relative weight error rhabel %.2e, GSL %.2e; "
                "max relative error of min(1-x, 1+x) rhabel %.2e, GSL %.2e\n",
                n, p, q, rhabel_weight, gsl_weight, rhabel_node, gsl_node);
  } else {
    std::printf("n = %zu, p = %g, q = %g: max relative weight error rhabel %.2e; "
                "max relative error of min(1-x, 1+x) rhabel %.2e\n",
                n, p, q, rhabel_weight, rhabel_node);
  }
}

}  // namespace

int main(int argc, char** argv) {
  gsl_set_error_handler_off();
  print_accuracy(1000, p_exponent, q_exponent, true);
  print_accuracy(4000, p_exponent, q_exponent, true);
  for (const auto& pair : other_pairs) print_accuracy(4000, pair[0], pair[1], false);
  std::fflush(stdout);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
