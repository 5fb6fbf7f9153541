// bench_sweep_baseline: the 10^4 single-wedge scenes of bench/sweep_wedges.json solved by
// rhabel::punch::solve alone (default options), one after the other: the baseline of
// scripts/bench_sweep.sh, which times `rhabel sweep` on the same scenes (1 and 2 threads, 1 and 2
// MPI ranks) and prints the ratios. Values as `rhabel sweep` computes a log_range (scene/src/sweep.cpp).
// Run: build/bin/bench_sweep_baseline --benchmark_repetitions=1
#include <rhabel/punch/contact.hpp>

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstddef>
#include <vector>

namespace {

double log_value(double from, double to, std::size_t i, std::size_t n) {
  if (i == 0) return from;
  if (i + 1 == n) return to;
  const double t = static_cast<double>(i) / static_cast<double>(n - 1);
  return std::exp(std::log(from) + t * (std::log(to) - std::log(from)));
}

std::vector<rhabel::punch::scene> wedge_scenes() {
  std::vector<rhabel::punch::scene> out;
  for (std::size_t i = 0; i < 100; ++i) {
    for (std::size_t j = 0; j < 100; ++j) {
      rhabel::punch::scene s;
      s.material = rhabel::punch::material{0.25, 5.0e6, 0.5, 0.0};
      s.speed = 0.01;
      s.indentors.push_back(rhabel::punch::indentor{
          rhabel::punch::wedge{0.02, log_value(0.01, 0.1, i, 100)}, log_value(100, 1000, j, 100), 0.0});
      out.push_back(std::move(s));
    }
  }
  return out;
}

void sweep_baseline(benchmark::State& state) {
  const auto scenes = wedge_scenes();
  for (auto _ : state) {
    for (const auto& s : scenes) benchmark::DoNotOptimize(rhabel::punch::solve(s));
  }
  state.SetItemsProcessed(static_cast<long long>(state.iterations() * scenes.size()));
}

}  // namespace

BENCHMARK(sweep_baseline)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK_MAIN();
