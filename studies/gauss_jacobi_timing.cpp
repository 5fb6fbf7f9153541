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
// library stopped.
//
// Timing (support/study_support.hpp, min_time_per_call): the library call alone (for GSL the
// alloc, which computes the rule, and the free), batched to >= 0.2 ms and repeated for the budget
// (default 0.5 s, --quick 50 ms); the minimum wall time per build is reported with the process CPU
// time of the same batch (CPU < wall: the process waited for a core). A rule slower than the
// budget is built once. Each rule is built once more, untimed, for the accuracy columns.
//
// Accuracy columns:
//   rel_error               |sum w_i - m0| / m0,  m0 = 2^(p+q+1) B(p+1, q+1)       (exact oracle)
//   first_moment_error      |sum w_i x_i - m1| / m0,  m1 = m0 (q - p)/(p + q + 2)    (exact oracle)
//   max_rel_weight_diff_vs_rhabel  max_i |w_gsl,i - w_rhabel,i| / w_rhabel,i, and
//   max_node_diff_vs_rhabel         max_i |x_gsl,i - x_rhabel,i| / min(1 - x_i, 1 + x_i):
//     for the sizes where both libraries ran. These compare two computed rules: informative, NOT a
//     reference (neither rule is exact).
// m0, m1 are evaluated in 50-digit arithmetic (cpp_bin_float_50) from Boost's beta function; the
// sums in long double with the nodes in increasing order (their rounding is << eps).
//
// Output: CSV on stdout (method,p,q,n,status,seconds,cpu_seconds,timed_calls,rel_error,
// first_moment_error,max_rel_weight_diff_vs_rhabel,max_node_diff_vs_rhabel; an empty cell = no
// value), progress on stderr, then the machine, its load, a markdown table and the run's wall and
// CPU time on stderr. Options: --quick (< 20 s), --cap-seconds X, --nmax N, --budget-ms X, --help.
#include <rhabel/quadrature.hpp>

#include <boost/math/special_functions/beta.hpp>
#include <boost/multiprecision/cpp_bin_float.hpp>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <iostream>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "support/study_support.hpp"

namespace {

using R50 = boost::multiprecision::cpp_bin_float_50;
using rhabel_study::format_duration;
using rhabel_study::format_number;

struct options {
  double cap_seconds = 20;
  double budget_seconds = 0.5;
  std::size_t n_max = 1000000;
};

struct rule_arrays {
  std::vector<double> x, w;
};

rule_arrays build_rhabel(std::size_t n, double p, double q) {
  auto rule = rhabel::quadrature::gauss_jacobi<double>(n, p, q);
  return {std::move(rule.x), std::move(rule.weight)};
}

// GSL's rule, copied out in increasing x (IQPACK sorts already; this makes sure, ours is increasing).
rule_arrays build_gsl(std::size_t n, double p, double q) {
  gsl_integration_fixed_workspace* work = gsl_integration_fixed_alloc(gsl_integration_fixed_jacobi, n, -1, 1, p, q);
  if (work == nullptr) throw std::runtime_error("gsl_integration_fixed_alloc failed");
  const double* nodes = gsl_integration_fixed_nodes(work);
  const double* weights = gsl_integration_fixed_weights(work);
  std::vector<std::pair<double, double>> pairs(n);
  for (std::size_t i = 0; i < n; ++i) pairs[i] = {nodes[i], weights[i]};
  gsl_integration_fixed_free(work);
  std::sort(pairs.begin(), pairs.end());
  rule_arrays out;
  out.x.resize(n);
  out.w.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    out.x[i] = pairs[i].first;
    out.w[i] = pairs[i].second;
  }
  return out;
}

// The timed calls: the library's own work only (no copying or sorting of GSL's arrays).
rhabel_study::timing time_rhabel(std::size_t n, double p, double q, double budget_seconds) {
  return rhabel_study::min_time_per_call(
      [&] { return rhabel::quadrature::gauss_jacobi<double>(n, p, q).weight[0]; }, budget_seconds);
}

rhabel_study::timing time_gsl(std::size_t n, double p, double q, double budget_seconds) {
  return rhabel_study::min_time_per_call(
      [&] {
        gsl_integration_fixed_workspace* work = gsl_integration_fixed_alloc(gsl_integration_fixed_jacobi, n, -1, 1, p, q);
        if (work == nullptr) throw std::runtime_error("gsl_integration_fixed_alloc failed");
        const double w0 = gsl_integration_fixed_weights(work)[0];
        gsl_integration_fixed_free(work);
        return w0;
      },
      budget_seconds);
}

struct moments {
  double m0, m1;
};

moments exact_moments(double p_double, double q_double) {
  const R50 p = p_double, q = q_double;
  const R50 m0 = boost::multiprecision::pow(R50(2), p + q + 1) * boost::math::beta(p + 1, q + 1);
  return {m0.convert_to<double>(), (m0 * (q - p) / (p + q + 2)).convert_to<double>()};
}

struct result_row {
  std::string method;
  double p, q;
  std::size_t n;
  std::string status;
  double seconds = std::numeric_limits<double>::quiet_NaN();
  double cpu_seconds = std::numeric_limits<double>::quiet_NaN();
  std::size_t timed_calls = 0;
  double sum_error = std::numeric_limits<double>::quiet_NaN();
  double moment_error = std::numeric_limits<double>::quiet_NaN();
  double weight_diff = std::numeric_limits<double>::quiet_NaN();
  double node_diff = std::numeric_limits<double>::quiet_NaN();
  double predicted_seconds = std::numeric_limits<double>::quiet_NaN();  // skipped sizes only
};

void print_row(rhabel_study::csv_writer& csv, const result_row& r) {
  csv.row({r.method, format_number(r.p, 6), format_number(r.q, 6), std::to_string(r.n), r.status,
           format_number(r.seconds, 4), format_number(r.cpu_seconds, 4), std::to_string(r.timed_calls),
           format_number(r.sum_error, 3), format_number(r.moment_error, 3), format_number(r.weight_diff, 3),
           format_number(r.node_diff, 3)});
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
  const int exit_code = rhabel_study::parse_command_line(
      argc, argv, "study_gauss_jacobi_timing", "CSV on stdout; progress and a markdown table on stderr.",
      {rhabel_study::switch_option("--quick", "cap 3 s per rule, 50 ms timing budget (runs in < 20 s)",
                                   [&] { opt.cap_seconds = 3; opt.budget_seconds = 0.05; }),
       {"--cap-seconds", "X", "skip a size whose predicted time exceeds X s (default 20)",
        [&](double x) { opt.cap_seconds = x; }},
       rhabel_study::budget_ms_option(opt.budget_seconds, "repeat rules faster than X ms, report the minimum"),
       rhabel_study::size_option("--nmax", opt.n_max, "largest n")});
  if (exit_code >= 0) return exit_code;
  const rhabel_study::run_record run;
  std::cerr << rhabel_study::run_record::machine_and_load() << '\n';
  gsl_set_error_handler_off();
  rhabel_study::csv_writer csv(std::cout, {"method", "p", "q", "n", "status", "seconds", "cpu_seconds", "timed_calls",
                                           "rel_error", "first_moment_error", "max_rel_weight_diff_vs_rhabel",
                                           "max_node_diff_vs_rhabel"});
  const std::pair<double, double> exponents[] = {{-0.5, 0.0}, {-0.99, -0.5}};
  std::vector<result_row> all;
  for (const auto& [p, q] : exponents) {
    const moments m = exact_moments(p, q);
    std::map<std::string, std::vector<std::pair<double, double>>> history;
    for (std::size_t n = 100; n <= opt.n_max; n *= 10) {
      rule_arrays ours;
      for (const std::string method : {"rhabel", "gsl"}) {
        result_row r{method, p, q, n, "ok"};
        const bool is_rhabel = method == "rhabel";
        const double predicted = predict(history[method], static_cast<double>(n));
        if (predicted > opt.cap_seconds) {
          r.status = "skipped: predicted " + format_number(predicted, 2) + " s > cap " +
                     format_number(opt.cap_seconds, 2) + " s";
          r.predicted_seconds = predicted;
        } else {
          std::cerr << method << " p=" << p << " q=" << q << " n=" << n << " ..." << std::flush;
          try {
            const rhabel_study::timing t = is_rhabel ? time_rhabel(n, p, q, opt.budget_seconds)
                                                     : time_gsl(n, p, q, opt.budget_seconds);
            r.seconds = t.seconds;
            r.cpu_seconds = t.cpu_seconds;
            r.timed_calls = t.calls;
            history[method].push_back({static_cast<double>(n), t.seconds});
            rule_arrays rule = is_rhabel ? build_rhabel(n, p, q) : build_gsl(n, p, q);
            long double sum = 0, first = 0;
            for (std::size_t i = 0; i < rule.x.size(); ++i) {
              sum += rule.w[i];
              first += static_cast<long double>(rule.w[i]) * rule.x[i];
            }
            r.sum_error = rhabel_study::relative_error<long double>(sum, m.m0);
            r.moment_error = static_cast<double>(std::fabs(first - m.m1) / m.m0);  // relative to m0: m1 may vanish
            if (is_rhabel) {
              ours = std::move(rule);
            } else if (ours.x.size() == n) {
              double wd = 0, xd = 0;
              for (std::size_t i = 0; i < n; ++i) {
                wd = std::max(wd, rhabel_study::relative_error(rule.w[i], ours.w[i]));
                const double end_distance = std::min(1 - ours.x[i], 1 + ours.x[i]);
                xd = std::max(xd, std::abs(rule.x[i] - ours.x[i]) / end_distance);
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
        print_row(csv, r);
        all.push_back(r);
      }
    }
  }
  // Markdown summary: wall time of one build (process CPU time of the same builds in parentheses).
  std::cerr << "\n| p | q | n | rhabel build time, wall (CPU) | GSL build time, wall (CPU) | sum-of-weights error "
               "rhabel / GSL | max rel. weight diff GSL vs rhabel |\n| ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n";
  auto time_cell = [](const result_row& r) {
    if (!std::isnan(r.predicted_seconds)) return "skipped (predicted " + format_number(r.predicted_seconds, 2) + " s)";
    if (r.status != "ok") return std::string("failed");
    return format_duration(r.seconds) + " (" + format_duration(r.cpu_seconds) + ")";
  };
  auto error_cell = [](const result_row& r, double value) {
    return r.status == "ok" && !std::isnan(value) ? format_number(value, 2) : std::string("-");
  };
  for (std::size_t i = 0; i + 1 < all.size(); i += 2) {
    const result_row& a = all[i];
    const result_row& b = all[i + 1];
    std::cerr << "| " << a.p << " | " << a.q << " | " << a.n << " | " << time_cell(a) << " | " << time_cell(b) << " | "
              << error_cell(a, a.sum_error) << " / " << error_cell(b, b.sum_error) << " | "
              << error_cell(b, b.weight_diff) << " |\n";
  }
  std::cerr << '\n' << run.totals() << '\n';
  return 0;
}
