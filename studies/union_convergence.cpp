// Convergence study of abel::solve_union (paper 41) for nearly touching intervals. Writes CSV to
// stdout (or to the file named by argv[1]; "-": stdout):
//   intervals,gap,alpha,beta,classes,degree,residual,status,load_error,condition,seconds,loads
//
// Configuration: intervals of length 1, [-1, 0], [gap, 1] (and [1 + gap, 2] for three), F = -s
// on every interval (a parabola-like profile); classes "nu0" (bounded leading, unbounded
// trailing edge on every interval: nu = 0, the facing ends are unbounded/bounded) and "nu-1"
// (bounded at both ends: nu = -1, solvability defects reported). For each case the degree
// runs over a ladder (x 1.5 steps from 32) up to 256 at gap 1e-2, argv[2] (default 1024) at gap
// 1e-4 and 512 at gap 1e-6.
//  * residual: the solver's independent residual of the original equation (direct quadrature,
//    never at the collocation points, including points graded toward the facing ends).
//  * load_error: max over the intervals of |int g_i - reference| / max_i |int g_i|, the reference
//    being the same case at the top of the ladder (a self-reference: meaningful only where the
//    top rung's residual is small; compare with the residual column).
//  * seconds: wall time of one solve including the residual (steady_clock, one run).
//  * loads: int g_i of every interval, %.17g, separated by ';' (tests/abel/test_multi_interval.cpp
//    records the gap 1e-4 row at degree 1536 as its reference: run with argv[2] = 1536).
//
// With argv[3] = "layered" it writes instead the boundary-layer route (abel::solve_union_layered,
// abel/detail/layered_union.hpp) side by side with the polynomial route,
// for the same cases, measured in one run:
//   intervals,gap,alpha,beta,classes,route,degree,poles_per_decade,unknowns,residual,status,
//   load_error,seconds,loads
//  * route "layered": (degree, poles per decade) = (16, 6), (24, 8), (32, 12); unknowns per
//    interval (the largest); load_error against the (32, 12) rung.
//  * route "polynomial": the adaptive degree (x 1.5 from 32, residual tolerance 1e-10) up to 256
//    at gap 1e-2, argv[2] at 1e-4, 512 at 1e-6: the last rung; seconds for the whole ladder, as
//    a user of the adaptive solve pays it; load_error against the layered (32, 12) rung (an
//    independent discretisation).
//
// With argv[3] = "gauss_seidel" it writes instead the contraction factor of block Gauss-Seidel
// between two intervals (the alternative to solve_union's direct block solve): each sweep
// solves interval 1 and then interval 2 alone (solve_union on one interval, degree 64) with the
// neighbour's current image subtracted from the data (apply_union, direct quadrature);
// ratio = (load_k - load_{k-1}) / (load_{k-1} - load_{k-2}) of int g_1 at sweep 8:
//   gap,alpha,beta,sweeps,load,ratio
#include "rhabel/abel.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

using namespace rhabel::abel;

namespace {

struct row {
  std::size_t degree;
  multi_solution<double> sol;
  double seconds;
};

/// Calls f(count, gap, alpha, beta, classes) for every case of the study, in the CSV's order.
template <class F>
void for_each_case(F&& f) {
  for (std::size_t count : {2u, 3u})
    for (double gap : {1e-2, 1e-4, 1e-6})
      for (double alpha : {0.0, 0.25, 0.5, 0.9})
        for (double beta : {0.0, 0.3})
          for (const std::string classes : {"nu0", "nu-1"}) f(count, gap, alpha, beta, classes);
}

/// The study's configuration: [-1, 0], [gap, 1] (and [1 + gap, 2]), bounded leading edges and
/// trailing edges of the class ("nu0": unbounded, "nu-1": bounded).
std::vector<interval_spec<double>> case_intervals(std::size_t count, double gap, const std::string& classes) {
  const edge trailing = classes == "nu0" ? edge::unbounded : edge::bounded;
  std::vector<interval_spec<double>> intervals{{-1.0, 0.0, edge::bounded, trailing}, {gap, 1.0, edge::bounded, trailing}};
  if (count == 3) intervals.push_back({1.0 + gap, 2.0, edge::bounded, trailing});
  return intervals;
}

}  // namespace

int main(int argc, char** argv) {
  std::ofstream file;
  const bool to_file = argc > 1 && std::string(argv[1]) != "-";  // "-": standard output
  if (to_file) file.open(argv[1]);
  std::ostream& out = to_file ? static_cast<std::ostream&>(file) : std::cout;
  const std::size_t top = argc > 2 ? static_cast<std::size_t>(std::atol(argv[2])) : 1024;
  if (argc > 3 && std::string(argv[3]) == "gauss_seidel") {
    out << "gap,alpha,beta,sweeps,load,ratio\n";
    for (double gap : {1e-2, 1e-4, 1e-6})
      for (double alpha : {0.0, 0.25, 0.5, 0.9}) {
        const double beta = 0.3;
        const abel_parameters<double> par(alpha, beta);
        const interval_spec<double> I1{-1.0, 0.0, edge::bounded, edge::unbounded};
        const interval_spec<double> I2{gap, 1.0, edge::bounded, edge::unbounded};
        multi_solve_options<double> options;
        options.degree = 64;
        options.residual_points = 0;
        std::vector<jacobi_density<double>> g1, g2;
        double previous = 0, previous_step = 0, ratio = 0, load = 0;
        const int sweeps = 8;
        for (int k = 0; k < sweeps; ++k) {
          g1 = solve_union<double>(par, {I1}, {[&](double s) { return -s - (g2.empty() ? 0.0 : apply_union(par, g2, s)); }},
                                   options).densities;
          g2 = solve_union<double>(par, {I2}, {[&](double s) { return -s - apply_union(par, g1, s); }}, options).densities;
          load = g1[0].integral();
          const double step = load - previous;
          if (k >= 1) ratio = step / previous_step;
          previous_step = step;
          previous = load;
        }
        char line[256];
        std::snprintf(line, sizeof line, "%.0e,%g,%g,%d,%.12f,%.4f\n", gap, alpha, beta, sweeps, load, ratio);
        out << line << std::flush;
      }
    return 0;
  }
  if (argc > 3 && std::string(argv[3]) == "layered") {
    out << "intervals,gap,alpha,beta,classes,route,degree,poles_per_decade,unknowns,residual,status,load_error,seconds,"
           "loads\n";
    for_each_case([&](std::size_t count, double gap, double alpha, double beta, const std::string& classes) {
      const abel_parameters<double> par(alpha, beta);
      const auto intervals = case_intervals(count, gap, classes);
      const std::vector<std::function<double(double)>> F(count, [](double s) { return -s; });
      struct result {
        std::string route;
        std::size_t degree, per_decade, unknowns;
        multi_solution<double> sol;
        double seconds;
      };
      std::vector<result> results;
      // per_decade 0: the polynomial route (solve_union), else solve_union_layered.
      auto timed = [&](const multi_solve_options<double>& options, std::size_t per_decade) {
        const auto start = std::chrono::steady_clock::now();
        auto sol = per_decade > 0 ? solve_union_layered(par, intervals, F, options, per_decade)
                                  : solve_union(par, intervals, F, options);
        return std::make_pair(std::move(sol), std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
      };
      for (const auto& [degree, per_decade] : {std::pair<std::size_t, std::size_t>{16, 6}, {24, 8}, {32, 12}}) {
        multi_solve_options<double> options;
        options.degree = degree;
        options.residual_points = 16;
        auto [sol, seconds] = timed(options, per_decade);
        std::size_t unknowns = 0;
        for (const auto& l : sol.layers)
          unknowns = std::max(unknowns, degree + l.lo_distances.size() + l.hi_distances.size());
        results.push_back({"layered", degree, per_decade, unknowns, std::move(sol), seconds});
      }
      {
        multi_solve_options<double> options;
        options.degree = 32;
        options.max_degree = gap >= 1e-2 ? 256 : (gap >= 1e-4 ? top : 512);
        options.residual_points = 16;
        auto [sol, seconds] = timed(options, 0);
        const std::size_t degree = sol.degree;
        results.push_back({"polynomial", degree, 0, degree, std::move(sol), seconds});
      }
      const auto& ref = results[2].sol;
      double load_scale = 0;
      for (std::size_t i = 0; i < count; ++i) load_scale = std::max(load_scale, std::abs(ref.load(i)));
      for (const auto& r : results) {
        double err = 0;
        for (std::size_t i = 0; i < count; ++i) err = std::max(err, std::abs(r.sol.load(i) - ref.load(i)) / load_scale);
        char line[512];
        std::snprintf(line, sizeof line, "%zu,%.0e,%g,%g,%s,%s,%zu,%zu,%zu,%.3e,%s,%.3e,%.4f,", count, gap, alpha,
                      beta, classes.c_str(), r.route.c_str(), r.degree, r.per_decade, r.unknowns, r.sol.residual,
                      r.sol.status == solve_status::converged ? "converged" : "not_converged",
                      &r == &results[2] ? 0.0 : err, r.seconds);
        out << line;
        for (std::size_t i = 0; i < count; ++i) {
          std::snprintf(line, sizeof line, "%s%.17g", i == 0 ? "" : ";", r.sol.load(i));
          out << line;
        }
        out << std::endl;
      }
    });
    return 0;
  }
  out << "intervals,gap,alpha,beta,classes,degree,residual,status,load_error,condition,seconds,loads\n";
  for_each_case([&](std::size_t count, double gap, double alpha, double beta, const std::string& classes) {
    const abel_parameters<double> par(alpha, beta);
    const auto intervals = case_intervals(count, gap, classes);
    std::vector<std::function<double(double)>> F(count, [](double s) { return -s; });
    // Ladder 32, 48, 72, ... (x 1.5, the adaptive solver's steps) up to the top rung:
    // 256 at gap 1e-2 (converged to rounding there), `top` at 1e-4, 512 at 1e-6 (far
    // from converged: shows the rate only).
    const std::size_t last = gap >= 1e-2 ? 256 : (gap >= 1e-4 ? top : 512);
    std::vector<std::size_t> ladder;
    for (std::size_t n = 32; n < last; n = n * 3 / 2) ladder.push_back(n);
    ladder.push_back(last);
    std::vector<row> rows;
    for (std::size_t n : ladder) {
      multi_solve_options<double> options;
      options.degree = n;
      options.residual_points = 16;
      const auto start = std::chrono::steady_clock::now();
      auto sol = solve_union(par, intervals, F, options);
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      rows.push_back({n, std::move(sol), seconds});
    }
    const auto& ref = rows.back().sol;
    double load_scale = 0;
    for (const auto& g : ref.densities) load_scale = std::max(load_scale, std::abs(g.integral()));
    for (const auto& r : rows) {
      double err = 0;
      for (std::size_t i = 0; i < count; ++i)
        err = std::max(err, std::abs(r.sol.densities[i].integral() - ref.densities[i].integral()) / load_scale);
      char line[512];
      std::snprintf(line, sizeof line, "%zu,%.0e,%g,%g,%s,%zu,%.3e,%s,%.3e,%.3e,%.4f,", count, gap, alpha,
                    beta, classes.c_str(), r.degree, r.sol.residual,
                    r.sol.status == solve_status::converged ? "converged" : "not_converged",
                    &r == &rows.back() ? 0.0 : err, r.sol.condition, r.seconds);
      out << line;
      for (std::size_t i = 0; i < count; ++i) {
        std::snprintf(line, sizeof line, "%s%.17g", i == 0 ? "" : ";", r.sol.densities[i].integral());
        out << line;
      }
      out << std::endl;
    }
  });
  return 0;
}
