// studies/gauss_jacobi_timing.cpp -> build/bin/study_gauss_jacobi_timing
//
// Node-generation study: time to build an n-point Gauss-Jacobi rule for the weight
// (1 - x)^p (1 + x)^q on [-1, 1], n = 10^2 ... 10^6, for
//   rhabel    rhabel::quadrature::gauss_jacobi<double>(n, p, q)
//   gsl       gsl_integration_fixed_alloc(gsl_integration_fixed_jacobi, n, -1, 1, p, q)
//             (GSL's weight is (b - x)^alpha (x - a)^beta, so alpha = p, beta = q; GSL computes the
//             rule by the Golub-Welsch method, an implicit QL sweep over the Jacobi matrix, O(n^2)).
//
// Every size is attempted unless the time predicted from the two previous sizes (local power law,
// exponent clamped to [1, 2]) exceeds the cap (default 20 s per rule, --quick 3 s); a skipped size
// is written as a row with status "skipped" and the predicted time, so the CSV says where each
// library stopped. A rule that takes longer than the timing budget is timed once; faster ones are
// repeated and the minimum is reported (steady_clock).
//
// Accuracy columns (computed outside the timing):
//   weight_sum_rel_error    |sum w_i - m0| / m0,  m0 = 2^(p+q+1) B(p+1, q+1)       (exact oracle)
//   first_moment_error      |sum w_i x_i - m1| / m0,  m1 = m0 (q - p)/(p + q + 2)    (exact oracle)
//   max_rel_weight_diff_vs_rhabel  max_i |w_gsl,i - w_rhabel,i| / w_rhabel,i, and
//   max_node_diff_vs_rhabel         max_i |x_gsl,i - x_rhabel,i| / min(1 - x_i, 1 + x_i):
//     for the sizes where both libraries ran. These compare two computed rules: informative, NOT a
//     reference (neither rule is exact).
// m0, m1 are evaluated in 50-digit arithmetic (cpp_bin_float_50) from Boost's beta function.
//
// Output: CSV on stdout, progress on stderr, then a markdown table on stderr.
// Options: --quick (< 20 s), --cap-seconds X, --nmax N, --budget-ms X, --help.
#include <rhabel/quadrature.hpp>

#include <boost/math/special_functions/beta.hpp>
#include <boost/multiprecision/cpp_bin_float.hpp>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace {

using R50 = boost::multiprecision::cpp_bin_float_50;
using clock_type = std::chrono::steady_clock;

struct options {
  double cap_seconds = 20;
  double budget_seconds = 0.5;
  std::size_t n_max = 1000000;
};

struct rule_arrays {
  std::vector<double> x, w;
};

struct measurement {
  double seconds = 0;
  int repetitions = 0;
  rule_arrays rule;
};

// A built rule, and the time the library call itself took (copying GSL's arrays out and sorting
// them is not GSL's cost and is excluded).
struct built_rule {
  rule_arrays rule;
  double seconds;
};

double seconds_since(clock_type::time_point t0) {
  return std::chrono::duration<double>(clock_type::now() - t0).count();
}

// Time build(): the first call is timed and kept; if it was quicker than the budget, further calls
// are timed and the minimum is reported.
template <class Build>
measurement time_build(Build&& build, double budget_seconds) {
  measurement m;
  built_rule first = build();
  m.rule = std::move(first.rule);
  m.seconds = first.seconds;
  m.repetitions = 1;
  const auto start = clock_type::now();
  while (seconds_since(start) < budget_seconds && m.repetitions < 1000) {
    m.seconds = std::min(m.seconds, build().seconds);
    ++m.repetitions;
  }
  return m;
}

built_rule build_rhabel(std::size_t n, double p, double q) {
  const auto t0 = clock_type::now();
  auto rule = rhabel::quadrature::gauss_jacobi<double>(n, p, q);
  const double seconds = seconds_since(t0);
  return {{std::move(rule.x), std::move(rule.weight)}, seconds};
}

built_rule build_gsl(std::size_t n, double p, double q) {
  const auto t0 = clock_type::now();
  gsl_integration_fixed_workspace* work = gsl_integration_fixed_alloc(gsl_integration_fixed_jacobi, n, -1, 1, p, q);
  const double seconds = seconds_since(t0);  // the alloc computes the rule
  if (work == nullptr) throw std::runtime_error("gsl_integration_fixed_alloc failed");
  const double* nodes = gsl_integration_fixed_nodes(work);
  const double* weights = gsl_integration_fixed_weights(work);
  std::vector<std::pair<double, double>> pairs(n);
  for (std::size_t i = 0; i < n; ++i) pairs[i] = {nodes[i], weights[i]};
  gsl_integration_fixed_free(work);
  std::sort(pairs.begin(), pairs.end());  // IQPACK sorts already; this makes sure, ours is increasing
  built_rule out{{}, seconds};
  out.rule.x.resize(n);
  out.rule.w.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    out.rule.x[i] = pairs[i].first;
    out.rule.w[i] = pairs[i].second;
  }
  return out;
}

struct moments {
  double m0, m1;
};

moments exact_moments(double p_double, double q_double) {
  const R50 p = p_double, q = q_double;
  const R50 m0 = boost::multiprecision::pow(R50(2), p + q + 1) * boost::math::beta(p + 1, q + 1);
  return {m0.convert_to<double>(), (m0 * (q - p) / (p + q + 2)).convert_to<double>()};
}

std::string fmt(double v, int digits = 4) {
  if (std::isnan(v)) return "";
  char buffer[48];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, v);
  return buffer;
}

struct result_row {
  std::string library;
  double p, q;
  std::size_t n;
  std::string status;
  double seconds = std::numeric_limits<double>::quiet_NaN();
  int repetitions = 0;
  double sum_error = std::numeric_limits<double>::quiet_NaN();
  double moment_error = std::numeric_limits<double>::quiet_NaN();
  double weight_diff = std::numeric_limits<double>::quiet_NaN();
  double node_diff = std::numeric_limits<double>::quiet_NaN();
};

void print_row(const result_row& r) {
  std::cout << r.library << ',' << fmt(r.p, 6) << ',' << fmt(r.q, 6) << ',' << r.n << ',' << r.status << ','
            << fmt(r.seconds) << ',' << r.repetitions << ',' << fmt(r.sum_error, 3) << ','
            << fmt(r.moment_error, 3) << ',' << fmt(r.weight_diff, 3) << ',' << fmt(r.node_diff, 3) << '\n';
  std::cout.flush();
}

// Predicted time for size n from the last two measured sizes.
double predict(const std::vector<std::pair<double, double>>& history, double n) {
  if (history.empty()) return 0;
  const auto [n1, t1] = history.back();
  double exponent = 2;  // assume the worst (quadratic) until two sizes have measurable times
  if (history.size() >= 2) {
    const auto [n0, t0] = history[history.size() - 2];
    if (t0 > 1e-3) exponent = std::clamp(std::log(t1 / t0) / std::log(n1 / n0), 1.0, 2.0);
  }
  return t1 * std::pow(n / n1, exponent);
}

}  // namespace

int main(int argc, char** argv) {
  options opt;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--quick") {
      opt.cap_seconds = 3;
      opt.budget_seconds = 0.05;
    } else if (arg == "--cap-seconds" && i + 1 < argc) {
      opt.cap_seconds = std::atof(argv[++i]);
    } else if (arg == "--budget-ms" && i + 1 < argc) {
      opt.budget_seconds = std::atof(argv[++i]) / 1000;
    } else if (arg == "--nmax" && i + 1 < argc) {
      opt.n_max = static_cast<std::size_t>(std::atol(argv[++i]));
    } else {
      std::cerr << "usage: study_gauss_jacobi_timing [--quick] [--cap-seconds X] [--budget-ms X] [--nmax N]\n"
                   "  CSV on stdout; progress and a markdown table on stderr.\n"
                   "  --quick          cap 3 s per rule, 50 ms repetition budget (runs in < 20 s)\n"
                   "  --cap-seconds X  skip a size whose predicted time exceeds X s (default 20)\n"
                   "  --budget-ms X    repeat rules faster than X ms, report the minimum (default 500)\n"
                   "  --nmax N         largest n (default 1e6)\n";
      return arg == "--help" ? 0 : 2;
    }
  }
  gsl_set_error_handler_off();
  std::cout << "library,p,q,n,status,seconds,repetitions,weight_sum_rel_error,first_moment_error,"
               "max_rel_weight_diff_vs_rhabel,max_node_diff_vs_rhabel\n";
  const std::pair<double, double> exponents[] = {{-0.5, 0.0}, {-0.99, -0.5}};
  std::vector<result_row> all;
  for (const auto& [p, q] : exponents) {
    const moments m = exact_moments(p, q);
    std::map<std::string, std::vector<std::pair<double, double>>> history;
    for (std::size_t n = 100; n <= opt.n_max; n *= 10) {
      rule_arrays ours;
      for (const std::string library : {"rhabel", "gsl"}) {
        result_row r{library, p, q, n, "ok"};
        const double predicted = predict(history[library], static_cast<double>(n));
        if (predicted > opt.cap_seconds) {
          r.status = "skipped: predicted " + fmt(predicted, 2) + " s > cap " + fmt(opt.cap_seconds, 2) + " s";
        } else {
          std::cerr << library << " p=" << p << " q=" << q << " n=" << n << " ..." << std::flush;
          try {
            measurement t = library == "rhabel" ? time_build([&] { return build_rhabel(n, p, q); }, opt.budget_seconds)
                                                : time_build([&] { return build_gsl(n, p, q); }, opt.budget_seconds);
            r.seconds = t.seconds;
            r.repetitions = t.repetitions;
            history[library].push_back({static_cast<double>(n), t.seconds});
            // Sums in long double with the nodes in order: rounding of the check is << eps.
            long double sum = 0, first = 0;
            for (std::size_t i = 0; i < t.rule.x.size(); ++i) {
              sum += t.rule.w[i];
              first += static_cast<long double>(t.rule.w[i]) * t.rule.x[i];
            }
            r.sum_error = static_cast<double>(std::fabs(sum - m.m0) / m.m0);
            r.moment_error = static_cast<double>(std::fabs(first - m.m1) / m.m0);
            if (library == "rhabel") {
              ours = std::move(t.rule);
            } else if (ours.x.size() == n) {
              double wd = 0, xd = 0;
              for (std::size_t i = 0; i < n; ++i) {
                wd = std::max(wd, std::abs(t.rule.w[i] - ours.w[i]) / ours.w[i]);
                const double end_distance = std::min(1 - ours.x[i], 1 + ours.x[i]);
                xd = std::max(xd, std::abs(t.rule.x[i] - ours.x[i]) / end_distance);
              }
              r.weight_diff = wd;
              r.node_diff = xd;
            }
            std::cerr << ' ' << r.seconds << " s\n";
          } catch (const std::exception& e) {
            r.status = std::string("exception: ") + e.what();
            std::cerr << ' ' << r.status << '\n';
          }
        }
        print_row(r);
        all.push_back(r);
      }
    }
  }
  // Markdown summary.
  std::cerr << "\n| p | q | n | rhabel build time | GSL build time | sum-of-weights error rhabel / GSL "
               "| max rel. weight diff GSL vs rhabel |\n| ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n";
  auto time_cell = [](const result_row& r) {
    if (r.status.rfind("skipped: predicted ", 0) == 0)
      return "skipped (predicted " + r.status.substr(19, r.status.find(" s >") - 19) + " s)";
    if (r.status != "ok") return std::string("failed");
    char buffer[32];
    if (r.seconds < 1e-3) std::snprintf(buffer, sizeof buffer, "%.3g us", r.seconds * 1e6);
    else if (r.seconds < 1) std::snprintf(buffer, sizeof buffer, "%.3g ms", r.seconds * 1e3);
    else std::snprintf(buffer, sizeof buffer, "%.3g s", r.seconds);
    return std::string(buffer);
  };
  for (std::size_t i = 0; i + 1 < all.size(); i += 2) {
    const result_row& a = all[i];
    const result_row& b = all[i + 1];
    std::cerr << "| " << a.p << " | " << a.q << " | " << a.n << " | " << time_cell(a) << " | " << time_cell(b) << " | "
              << (a.status == "ok" ? fmt(a.sum_error, 2) : "-") << " / " << (b.status == "ok" ? fmt(b.sum_error, 2) : "-")
              << " | " << (std::isnan(b.weight_diff) ? std::string("-") : fmt(b.weight_diff, 2)) << " |\n";
  }
  return 0;
}
