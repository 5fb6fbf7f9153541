// bench_solve_loop: 1000 single-parabola scenes solved one after the other by rhabel::punch::solve
// (default options: no grid, residual on; and with the residual off): the C++ side of
// python/bench_solve_loop.py, which times the same loop through rhabel.solve from Python and
// prints the ratio (it runs this binary when it is built).
// The scenes: alpha = 0.3, E1 = 1e6, nu = 0.3, k = 0.5, U = 0.01, R = 0.02, load 50 + 0.1 i N/m.
// Run:
//   build/bin/bench_solve_loop --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include <rhabel/punch/contact.hpp>

#include <benchmark/benchmark.h>

#include <cstddef>
#include <vector>

namespace {

constexpr std::size_t scene_count = 1000;

std::vector<rhabel::punch::scene> parabola_scenes() {
  std::vector<rhabel::punch::scene> out(scene_count);
  for (std::size_t i = 0; i < scene_count; ++i) {
    auto& s = out[i];
    s.material = rhabel::punch::material{0.3, 1.0e6, 0.3, 0.5};
    s.speed = 0.01;
    s.indentors.push_back(rhabel::punch::indentor{rhabel::punch::parabolic{0.02}, 50.0 + 0.1 * static_cast<double>(i), 0.0});
  }
  return out;
}

void solve_loop(benchmark::State& state) {
  const auto scenes = parabola_scenes();
  rhabel::punch::solve_options options;
  options.residual = state.range(0) != 0;
  for (auto _ : state) {
    for (const auto& s : scenes) benchmark::DoNotOptimize(rhabel::punch::solve(s, options));
  }
  state.SetItemsProcessed(static_cast<long long>(state.iterations() * scene_count));
}

}  // namespace

BENCHMARK(solve_loop)->ArgName("residual")->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
