// studies/quadrature_convergence.cpp -> build/bin/study_quadrature_convergence
//
// Convergence study: accuracy against cost of five ways to compute
//
//     I(p, q; f) = int_{-1}^{1} (1 - x)^p (1 + x)^q f(x) dx          (p at x = +1, q at x = -1)
//
// for endpoint-singular Jacobi weights and smooth or nearly singular f:
//
//   weights (p, q): (-0.5, 0), (-0.9, 0), (-0.99, 0) and (-0.99, -0.5) (both ends singular,
//                   deliberately asymmetric so that a p <-> q swap in any parameterisation shows);
//   functions f:    exp(x), cos(3x), 1/(2 - x)                        (entire / pole far away),
//                   1/(1.01 - x)   (pole 0.01 beyond the singular end x = +1),
//                   1/(x^2 + 1e-2) (poles at +-0.1i, Runge-type).
//
// Methods compared (all in double precision):
//   rhabel_gauss_jacobi      rhabel::quadrature::gauss_jacobi<double>(n, p, q), n = 1, 2, 4, ...
//                            `seconds` includes building the rule; `seconds_reuse` is the sum alone.
//   gsl_fixed_jacobi         gsl_integration_fixed_alloc(gsl_integration_fixed_jacobi, n, -1, 1,
//                            alpha = p, beta = q): GSL's weight is (b - x)^alpha (x - a)^beta on
//                            [a, b], so its alpha is our p (checked at start-up, see below).
//                            The alloc computes the rule: `seconds` = alloc + sum + free,
//                            `seconds_reuse` = gsl_integration_fixed on an existing workspace.
//   gsl_qaws                 gsl_integration_qaws with gsl_integration_qaws_table_alloc(q, p, 0, 0):
//                            GSL's weight is (x - a)^alpha (b - x)^beta, so alpha = q, beta = p.
//                            epsabs = 0, epsrel swept from 1e-2 down to 1.2e-14 (GSL rejects
//                            epsrel < 50 eps); workspace limit 1000 subintervals. The table (its
//                            modified moments) and the workspace are allocated once, outside the timing.
//   boost_tanh_sinh_naive    boost::math::quadrature::tanh_sinh<double> with the one-argument functor
//                            f(x) pow(1 - x, p) pow(1 + x, q): 1 - x is formed from the rounded node,
//                            so the weight loses relative accuracy next to the end (the usual trap).
//   boost_tanh_sinh_complement  the two-argument functor f(x, xc): Boost passes the distance to the
//                            nearer end (xc = 1 - x for x >= 0, xc = -(1 + x) for x < 0) computed
//                            without cancellation; the weight is evaluated from it (the accurate way).
//   Both tanh-sinh variants sweep the termination tolerance 1e-2 ... 1e-15; the integrator object is
//   built once outside the timing (Boost's own recommendation: it caches the abscissae).
//   Expected floor of tanh-sinh (and what the CSV shows): the rule stops where the distance s to
//   the end falls below some delta, and the neglected int_0^delta s^p ds = delta^(1+p)/(1+p) is,
//   relative to an integral dominated by that end (~ C/(1+p)), about delta^(1+p). Naive form:
//   delta ~ eps (1 - x is formed from the rounded x), floor eps^0.5 = 1.5e-8, eps^0.1 = 0.027 and
//   eps^0.01 = 0.70 for p = -0.5, -0.9, -0.99. Two-argument form: delta ~ 1e-275 (the smallest
//   complement Boost 1.74 stores for double), harmless except for p = -0.99: 1e-275^0.01 ~ 2e-3.
//
// Reference values (independent of every compared method; 50 significant digits,
// boost::multiprecision::cpp_bin_float_50). Route R1, used for every case:
//   split [-1, 1] at -1/2 and 1/2. On [1/2, 1] put 1 - x = s = u^m with m = 1/(1 + p): then
//   s^p ds = m du exactly, and the integrand m (2 - s)^q f(1 - s) is analytic in u because every m
//   used here is (up to the rounding of the double p) an integer: 2, 10, 100. Likewise on
//   [-1, -1/2] with 1 + x = u^(1/(1+q)). The middle piece has an analytic weight. Each piece is
//   integrated by composite 32-point Gauss-Legendre (nodes computed here by Newton's method on the
//   Legendre recurrence at 50 digits, not by any library rule), doubling the number of equal panels
//   until two successive sums agree to 1e-40 relative (or reporting failure).
//   The exponents of the reference are the double values p, q converted exactly, so the reference
//   integral is the one the double-precision methods are asked for (for p = -0.99 a 1e-17 change of p
//   moves I by ~1e-15 relative, so this matters).
// Route R2, an independent cross-check where a convergent closed form exists (x = -1 + 2t and
// Euler's integrals, DLMF 13.4.1 and 15.6.1):
//   int w e^x     = 2^(p+q+1) B(q+1, p+1) e^-1  1F1(q+1; p+q+2; 2)
//   int w cos(3x) = Re[ 2^(p+q+1) B(q+1, p+1) e^-3i 1F1(q+1; p+q+2; 6i) ]
//   int w/(c - x) = 2^(p+q+1) B(q+1, p+1) / (c+1)  2F1(1, q+1; p+q+2; 2/(c+1))      (c > 1)
//   summed as power series at 50 digits. The study prints the largest R1 - R2 disagreement
//   (measured: 2.2e-49; a value above 1e-30 aborts the study).
//
// Timing (support/study_support.hpp, min_time_per_call): steady_clock; a batch of calls long enough
// to resolve (>= 0.2 ms) is repeated for a time budget (default 30 ms per measurement, --quick 2 ms)
// and the MINIMUM per-call wall time is reported. The value and error are computed once, outside
// the timed loop.
//
// Output: CSV on stdout (columns documented in studies/README.md; an empty cell = no value), progress,
// the machine and its load, markdown summary tables and the run's wall and CPU time on stderr.
// Options: --quick (< 20 s), --budget-ms X, --nmax N, --help.
#include <rhabel/quadrature.hpp>

#include <boost/math/constants/constants.hpp>
#include <boost/math/quadrature/tanh_sinh.hpp>
#include <boost/math/special_functions/beta.hpp>
#include <boost/multiprecision/cpp_bin_float.hpp>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <iterator>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "support/study_support.hpp"

namespace {

using R50 = boost::multiprecision::cpp_bin_float_50;
using rhabel_study::format_duration;
using rhabel_study::format_number;
constexpr double eps = std::numeric_limits<double>::epsilon();
constexpr double nan = std::numeric_limits<double>::quiet_NaN();

// Minimum wall time per call (support/study_support.hpp).
template <class F>
double min_seconds_per_call(F&& call, double budget_seconds) {
  return rhabel_study::min_time_per_call(std::forward<F>(call), budget_seconds).seconds;
}

// ---------------------------------------------------------------------------------------------
// 50-digit reference, route R1: composite Gauss-Legendre on singularity-free substituted pieces.
struct gauss_legendre_50 {
  std::vector<R50> node, weight;  // on [-1, 1]
  explicit gauss_legendre_50(int n) {
    using boost::multiprecision::abs;
    using boost::multiprecision::cos;
    // P_n(x) and P_n'(x) by the recurrence (k+1) P_{k+1} = (2k+1) x P_k - k P_{k-1} and
    // (x^2 - 1) P_n' = n (x P_n - P_{n-1}).
    auto legendre = [n](const R50& x) {
      R50 p0 = 1, p1 = x;
      for (int k = 1; k < n; ++k) {
        R50 p2 = ((2 * k + 1) * x * p1 - k * p0) / (k + 1);
        p0 = p1;
        p1 = p2;
      }
      return std::pair<R50, R50>{p1, n * (x * p1 - p0) / (x * x - 1)};
    };
    const R50 pi = boost::math::constants::pi<R50>();
    for (int i = 1; i <= n; ++i) {
      R50 x = cos(pi * (R50(i) - R50(0.25)) / (R50(n) + R50(0.5)));  // Tricomi's initial guess
      for (int iteration = 0; iteration < 20; ++iteration) {       // Newton, quadratic from here
        const auto [value, slope] = legendre(x);
        const R50 step = value / slope;
        x -= step;
        if (abs(step) < R50(1e-48)) break;  // the next step would be rounding (50 digits)
      }
      const R50 slope = legendre(x).second;
      node.push_back(x);
      weight.push_back(2 / ((1 - x * x) * slope * slope));
    }
  }
};

const gauss_legendre_50& legendre32() {
  static const gauss_legendre_50 rule(32);
  return rule;
}

struct reference_piece {
  R50 value;
  R50 change;  // |last doubling change| / |value|
  int panels;
};

// int_lo^hi g(u) du by composite 32-point Gauss-Legendre, panels doubled until converged.
template <class G>
reference_piece composite_legendre(G&& g, const R50& lo, const R50& hi) {
  using boost::multiprecision::abs;
  const auto& gl = legendre32();
  auto sum_with = [&](int panels) {
    R50 total = 0;
    const R50 width = (hi - lo) / panels;
    for (int j = 0; j < panels; ++j) {
      const R50 centre = lo + width * (R50(j) + R50(0.5));
      R50 panel = 0;
      for (std::size_t i = 0; i < gl.node.size(); ++i) panel += gl.weight[i] * g(centre + width / 2 * gl.node[i]);
      total += panel * width / 2;
    }
    return total;
  };
  R50 previous = sum_with(4);
  for (int panels = 8; panels <= 8192; panels *= 2) {
    const R50 current = sum_with(panels);
    const R50 change = abs(current - previous) / (abs(current) > 0 ? abs(current) : R50(1));
    if (change < R50(1e-40)) return {current, change, panels};
    previous = current;
  }
  throw std::runtime_error("reference: composite Gauss-Legendre did not converge to 1e-40");
}

// Route R1 for int_{-1}^{1} (1-x)^p (1+x)^q f(x) dx.
template <class F50>
R50 reference_r1(double p_double, double q_double, F50 f) {
  using boost::multiprecision::pow;
  const R50 p = p_double, q = q_double;  // exact conversion of the double exponents
  const R50 half = R50(1) / 2;
  // [1/2, 1]: 1 - x = s = u^mp, s^p ds = mp du.
  const R50 mp = 1 / (1 + p);
  auto right = [&](const R50& u) {
    const R50 s = pow(u, mp);
    return mp * pow(2 - s, q) * f(1 - s);
  };
  // [-1, -1/2]: 1 + x = s = u^mq, s^q ds = mq du.
  const R50 mq = 1 / (1 + q);
  auto left = [&](const R50& u) {
    const R50 s = pow(u, mq);
    return mq * pow(2 - s, p) * f(s - 1);
  };
  auto middle = [&](const R50& x) { return pow(1 - x, p) * pow(1 + x, q) * f(x); };
  return composite_legendre(right, R50(0), pow(half, 1 / mp)).value +
         composite_legendre(left, R50(0), pow(half, 1 / mq)).value +
         composite_legendre(middle, -half, half).value;
}

// Route R2 series. 1F1(a; c; z) for real z and for z = i y (returns real and imaginary part).
struct complex50 {
  R50 re, im;
};

complex50 hypergeometric_1f1_imaginary(const R50& a, const R50& c, const R50& y) {
  using boost::multiprecision::abs;
  // sum_k (a)_k / (c)_k (i y)^k / k!; i^k cycles 1, i, -1, -i.
  R50 term = 1, re = 0, im = 0;
  for (int k = 0; k < 100000; ++k) {
    switch (k % 4) {
      case 0: re += term; break;
      case 1: im += term; break;
      case 2: re -= term; break;
      default: im -= term; break;
    }
    term *= (a + k) / (c + k) * y / (k + 1);
    if (k > 10 && abs(term) < R50(1e-60)) break;
  }
  return {re, im};
}

R50 hypergeometric_1f1(const R50& a, const R50& c, const R50& z) {
  using boost::multiprecision::abs;
  R50 term = 1, sum = 0;
  for (int k = 0; k < 100000; ++k) {
    sum += term;
    term *= (a + k) / (c + k) * z / (k + 1);
    if (k > 10 && abs(term) < R50(1e-60) * abs(sum)) break;
  }
  return sum;
}

// 2F1(1, b; c; z), 0 <= z < 1.
R50 hypergeometric_2f1_one(const R50& b, const R50& c, const R50& z) {
  using boost::multiprecision::abs;
  R50 term = 1, sum = 0;
  for (int k = 0; k < 10000000; ++k) {
    sum += term;
    term *= (b + k) / (c + k) * z;  // (1)_k / k! = 1
    if (k > 10 && abs(term) < R50(1e-60) * abs(sum)) break;
  }
  return sum;
}

// ---------------------------------------------------------------------------------------------
// The cases.
struct weight_case {
  double p, q;
};

enum class function_kind { exp, cos3, pole_2, pole_1_01, runge };

struct function_case {
  function_kind kind;
  const char* name;
};

const function_case all_functions[] = {{function_kind::exp, "exp(x)"},
                                       {function_kind::cos3, "cos(3x)"},
                                       {function_kind::pole_2, "1/(2-x)"},
                                       {function_kind::pole_1_01, "1/(1.01-x)"},
                                       {function_kind::runge, "1/(x^2+1e-2)"}};

// The constants 1.01 and 1e-2 enter as the double values (converted exactly for T = R50), so that
// the reference integrand is the double one: near the pole, I changes by ~1e-15 relative under a
// 1e-17 change of 1.01, the size of its rounding.
template <class T>
T evaluate(function_kind kind, const T& x) {
  using std::cos;
  using std::exp;
  using boost::multiprecision::cos;
  using boost::multiprecision::exp;
  switch (kind) {
    case function_kind::exp: return exp(x);
    case function_kind::cos3: return cos(3 * x);
    case function_kind::pole_2: return 1 / (2 - x);
    case function_kind::pole_1_01: return 1 / (T(1.01) - x);
    case function_kind::runge: return 1 / (x * x + T(1e-2));
  }
  return T(0);
}

// Double-precision integrands as distinct types so that every method gets an inlinable call.
template <function_kind Kind>
struct integrand {
  double operator()(double x) const {
    if constexpr (Kind == function_kind::exp) return std::exp(x);
    else if constexpr (Kind == function_kind::cos3) return std::cos(3 * x);
    else if constexpr (Kind == function_kind::pole_2) return 1 / (2 - x);
    else if constexpr (Kind == function_kind::pole_1_01) return 1 / (1.01 - x);
    else return 1 / (x * x + 1e-2);
  }
};

struct reference_value {
  R50 value;
  R50 r1_minus_r2;  // relative; negative if no R2 route exists
};

reference_value compute_reference(const weight_case& w, function_kind kind) {
  using boost::multiprecision::abs;
  using boost::multiprecision::cos;
  using boost::multiprecision::exp;
  using boost::multiprecision::pow;
  using boost::multiprecision::sin;
  const R50 r1 = reference_r1(w.p, w.q, [kind](const R50& x) { return evaluate<R50>(kind, x); });
  const R50 p = w.p, q = w.q;
  const R50 scale = pow(R50(2), p + q + 1) * boost::math::beta(q + 1, p + 1);
  R50 r2 = 0;
  bool have_r2 = true;
  switch (kind) {
    case function_kind::exp: r2 = scale * exp(R50(-1)) * hypergeometric_1f1(q + 1, p + q + 2, R50(2)); break;
    case function_kind::cos3: {
      const complex50 h = hypergeometric_1f1_imaginary(q + 1, p + q + 2, R50(6));
      // Re[e^{-3i} (re + i im)] = cos(3) re + sin(3) im
      r2 = scale * (cos(R50(3)) * h.re + sin(R50(3)) * h.im);
      break;
    }
    case function_kind::pole_2:
    case function_kind::pole_1_01: {
      const R50 c = kind == function_kind::pole_2 ? R50(2) : R50(1.01);  // the double 1.01, exactly
      r2 = scale / (c + 1) * hypergeometric_2f1_one(q + 1, p + q + 2, 2 / (c + 1));
      break;
    }
    case function_kind::runge: have_r2 = false; break;
  }
  return {r1, have_r2 ? R50(abs(r1 - r2) / abs(r1)) : R50(-1)};
}

// ---------------------------------------------------------------------------------------------
// Output.
// NaN marks "no value" (an empty CSV cell): no error estimate (fixed rules), no reuse time
// (adaptive methods), no value or error (a run that threw).
struct row {
  std::string case_id, f_name, method, setting;
  double p = 0, q = 0;
  std::size_t n_or_evaluations = 0;
  double value = 0, reference = 0, rel_error = 0, rel_error_estimate = nan;
  std::string status = "ok";
  double seconds = 0, seconds_reuse = nan;
};

rhabel_study::csv_writer& csv() {
  static rhabel_study::csv_writer writer(
      std::cout, {"case", "p", "q", "f", "method", "setting", "n_or_evaluations", "value", "reference", "rel_error",
                  "rel_error_estimate", "status", "seconds", "seconds_reuse"});
  return writer;
}

void print_row(const row& r) {
  csv().row({r.case_id, format_number(r.p, 6), format_number(r.q, 6), r.f_name, r.method, r.setting,
             std::to_string(r.n_or_evaluations), format_number(r.value), format_number(r.reference),
             format_number(r.rel_error, 4), format_number(r.rel_error_estimate, 4), r.status,
             format_number(r.seconds, 4), format_number(r.seconds_reuse, 4)});
}

// ---------------------------------------------------------------------------------------------
// The methods.
struct options {
  double budget_seconds = 0.03;
  std::size_t n_max = 1024;
};

// GSL callback that counts evaluations.
template <class F>
struct gsl_counted {
  F f;
  std::size_t count = 0;
  static double call(double x, void* self) {
    auto* me = static_cast<gsl_counted*>(self);
    ++me->count;
    return me->f(x);
  }
};

// |value - reference| / |reference| in 50 digits, so that rounding the reference to double adds
// nothing (errors of ~1e-16 are reported); NaN for a non-finite value.
double rel_error_of(double value, const R50& reference) {
  return std::isfinite(value) ? rhabel_study::relative_error<R50>(value, reference) : nan;
}

std::string tolerance_label(double tol) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "tol=%.1e", tol);
  return buffer;
}

template <function_kind Kind>
void run_case(const weight_case& w, const char* f_name, const R50& reference, const options& opt,
              std::vector<row>& rows) {
  const integrand<Kind> f{};
  const double p = w.p, q = w.q;
  std::ostringstream id;
  id << f_name << " @ p=" << p << " q=" << q;
  auto base = [&](const char* method, std::string setting) {
    row r;
    r.case_id = id.str();
    r.f_name = f_name;
    r.method = method;
    r.setting = std::move(setting);
    r.p = p;
    r.q = q;
    r.reference = reference.convert_to<double>();
    return r;
  };
  auto emit = [&](row r) {
    print_row(r);
    rows.push_back(std::move(r));
  };

  // Fixed rules: n = 1, 2, 4, ... up to one doubling past the first n at the rounding floor.
  auto sweep_n = [&](const char* method, auto&& run_with_n) {
    bool at_floor = false;
    for (std::size_t n = 1; n <= opt.n_max; n *= 2) {
      row r = base(method, "n=" + std::to_string(n));
      r.n_or_evaluations = n;
      try {
        run_with_n(n, r);
        r.rel_error = rel_error_of(r.value, reference);
      } catch (const std::exception& e) {
        r.status = std::string("exception: ") + e.what();
        r.value = r.rel_error = nan;
      }
      emit(r);
      if (at_floor) break;
      at_floor = r.rel_error < 64 * eps;  // 64 eps: below this only rounding is left
    }
  };

  sweep_n("rhabel_gauss_jacobi", [&](std::size_t n, row& r) {
    const auto rule = rhabel::quadrature::gauss_jacobi<double>(n, p, q);
    r.value = rule.integrate(f);
    r.seconds = min_seconds_per_call(
        [&] { return rhabel::quadrature::gauss_jacobi<double>(n, p, q).integrate(f); }, opt.budget_seconds);
    r.seconds_reuse = min_seconds_per_call([&] { return rule.integrate(f); }, opt.budget_seconds);
  });

  sweep_n("gsl_fixed_jacobi", [&](std::size_t n, row& r) {
    gsl_counted<integrand<Kind>> counted{f};
    gsl_function F{&gsl_counted<integrand<Kind>>::call, &counted};
    auto once = [&] {
      gsl_integration_fixed_workspace* work = gsl_integration_fixed_alloc(gsl_integration_fixed_jacobi, n, -1, 1, p, q);
      if (work == nullptr) throw std::runtime_error("gsl_integration_fixed_alloc failed");
      double result = nan;
      const int status = gsl_integration_fixed(&F, &result, work);
      gsl_integration_fixed_free(work);
      if (status != GSL_SUCCESS) throw std::runtime_error(gsl_strerror(status));
      return result;
    };
    r.value = once();
    r.seconds = min_seconds_per_call(once, opt.budget_seconds);
    gsl_integration_fixed_workspace* work = gsl_integration_fixed_alloc(gsl_integration_fixed_jacobi, n, -1, 1, p, q);
    r.seconds_reuse = min_seconds_per_call(
        [&] {
          double result = 0;
          gsl_integration_fixed(&F, &result, work);
          return result;
        },
        opt.budget_seconds);
    gsl_integration_fixed_free(work);
  });

  // QAWS: tolerance sweep.
  {
    gsl_integration_qaws_table* table = gsl_integration_qaws_table_alloc(q, p, 0, 0);
    const std::size_t limit = 1000;
    gsl_integration_workspace* work = gsl_integration_workspace_alloc(limit);
    std::vector<double> tolerances;
    for (int k = 2; k <= 13; ++k) tolerances.push_back(std::pow(10.0, -k));
    tolerances.push_back(1.2e-14);  // just above GSL's floor 50 eps
    for (double tol : tolerances) {
      row r = base("gsl_qaws", tolerance_label(tol));
      gsl_counted<integrand<Kind>> counted{f};
      gsl_function F{&gsl_counted<integrand<Kind>>::call, &counted};
      double result = 0, abserr = 0;
      int status = gsl_integration_qaws(&F, -1, 1, table, 0, tol, limit, work, &result, &abserr);
      r.n_or_evaluations = counted.count;
      r.value = result;
      r.rel_error = rel_error_of(result, reference);
      r.rel_error_estimate = abserr / std::abs(result);
      if (status != GSL_SUCCESS) r.status = std::string("gsl: ") + gsl_strerror(status);
      r.seconds = min_seconds_per_call(
          [&] {
            double value = 0, error = 0;
            gsl_integration_qaws(&F, -1, 1, table, 0, tol, limit, work, &value, &error);
            return value;
          },
          opt.budget_seconds);
      emit(r);
    }
    gsl_integration_workspace_free(work);
    gsl_integration_qaws_table_free(table);
  }

  // Boost tanh-sinh, both functor forms.
  {
    // Built once, abscissae cached. Not const: Boost 1.74 declares integrate() const but defines the
    // overloads without const, so a const object finds no match.
    static boost::math::quadrature::tanh_sinh<double> integrator;
    std::size_t count = 0;
    auto naive = [&](double x) {
      ++count;
      return f(x) * std::pow(1 - x, p) * std::pow(1 + x, q);
    };
    auto complement = [&](double x, double xc) {
      ++count;
      // Boost's xc: 1 - x for x >= 0 (xc >= 0) and -(1 + x) for x < 0 (xc < 0), cancellation-free.
      const double one_minus_x = xc >= 0 ? xc : 1 - x;
      const double one_plus_x = xc >= 0 ? 1 + x : -xc;
      return f(x) * std::pow(one_minus_x, p) * std::pow(one_plus_x, q);
    };
    auto sweep_tolerance = [&](const char* method, auto&& functor) {
      for (int k = 2; k <= 15; ++k) {
        const double tol = std::pow(10.0, -k);
        row r = base(method, tolerance_label(tol));
        try {
          double error = 0, l1 = 0;
          std::size_t levels = 0;
          count = 0;
          r.value = integrator.integrate(functor, tol, &error, &l1, &levels);
          r.n_or_evaluations = count;
          r.rel_error = rel_error_of(r.value, reference);
          r.rel_error_estimate = error / std::abs(r.value);
          r.seconds = min_seconds_per_call([&] { return integrator.integrate(functor, tol); }, opt.budget_seconds);
        } catch (const std::exception& e) {
          r.status = std::string("exception: ") + e.what();
          r.value = r.rel_error = nan;
        }
        emit(r);
      }
    };
    sweep_tolerance("boost_tanh_sinh_naive", naive);
    sweep_tolerance("boost_tanh_sinh_complement", complement);
  }
}

// ---------------------------------------------------------------------------------------------
// Start-up checks of the parameterisation of GSL's two Jacobi-weight routines against the exact
// moments  m0 = 2^(p+q+1) B(p+1, q+1),  m1 = int x w = m0 (q - p)/(p + q + 2)  for an asymmetric
// weight: a p <-> q swap flips the sign of m1.
void check_gsl_parameterisation() {
  const double p = -0.7, q = 0.3;
  const double m0 = std::pow(2.0, p + q + 1) * std::tgamma(p + 1) * std::tgamma(q + 1) / std::tgamma(p + q + 2);
  const double m1 = m0 * (q - p) / (p + q + 2);
  auto identity = [](double x, void*) { return x; };
  gsl_function F{identity, nullptr};
  double fixed = 0;
  gsl_integration_fixed_workspace* work = gsl_integration_fixed_alloc(gsl_integration_fixed_jacobi, 3, -1, 1, p, q);
  gsl_integration_fixed(&F, &fixed, work);
  gsl_integration_fixed_free(work);
  gsl_integration_qaws_table* table = gsl_integration_qaws_table_alloc(q, p, 0, 0);
  gsl_integration_workspace* w = gsl_integration_workspace_alloc(100);
  double qaws = 0, abserr = 0;
  gsl_integration_qaws(&F, -1, 1, table, 0, 1e-12, 100, w, &qaws, &abserr);
  gsl_integration_workspace_free(w);
  gsl_integration_qaws_table_free(table);
  const double tolerance = 1e-11;  // both are exact for x up to rounding; a swap gives an O(1) error
  if (std::abs(fixed - m1) > tolerance * m0 || std::abs(qaws - m1) > tolerance * m0) {
    std::cerr << "GSL parameterisation check FAILED: fixed " << fixed << ", qaws " << qaws << ", expected " << m1
              << "\n";
    std::exit(1);
  }
  std::cerr << "GSL parameterisation check: int x (1-x)^-0.7 (1+x)^0.3 = " << m1 << "; fixed_jacobi "
            << fixed << ", qaws " << qaws << " (ok)\n";
}

// ---------------------------------------------------------------------------------------------
// Markdown summaries on stderr.
const char* const all_methods[] = {"rhabel_gauss_jacobi", "gsl_fixed_jacobi", "gsl_qaws", "boost_tanh_sinh_naive",
                                   "boost_tanh_sinh_complement"};

// Of the runs of one method on one case with a finite error: the cheapest (least time) that reached
// `target`, and the most accurate (ties: the faster); either may be null.
struct chosen_runs {
  const row* cheapest = nullptr;
  const row* best = nullptr;
};

chosen_runs choose_runs(const std::vector<row>& rows, const std::string& case_id, const char* method, double target) {
  chosen_runs c;
  for (const row& r : rows) {
    if (r.case_id != case_id || r.method != method || !std::isfinite(r.rel_error)) continue;
    if (r.rel_error <= target && (c.cheapest == nullptr || r.seconds < c.cheapest->seconds)) c.cheapest = &r;
    if (c.best == nullptr || r.rel_error < c.best->rel_error ||
        (r.rel_error == c.best->rel_error && r.seconds < c.best->seconds))
      c.best = &r;
  }
  return c;
}

// Per method, the cheapest run reaching `target` and the most accurate run.
void print_summary(const std::vector<row>& rows, const std::string& case_id, double target) {
  std::cerr << "\n#### " << case_id << "\n\n"
            << "| method | setting | evaluations | rel. error | time per integral |\n"
            << "| --- | --- | ---: | ---: | ---: |\n";
  for (const char* method : all_methods) {
    const chosen_runs c = choose_runs(rows, case_id, method, target);
    auto line = [&](const row* r, const char* note) {
      std::cerr << "| " << method << note << " | " << r->setting << " | " << r->n_or_evaluations << " | "
                << format_number(r->rel_error, 2) << " | " << format_duration(r->seconds) << " |\n";
    };
    if (c.cheapest != nullptr) line(c.cheapest, " (cheapest to 1e-10)");
    else std::cerr << "| " << method << " (cheapest to 1e-10) | never reached | | | |\n";
    if (c.best != nullptr && c.best != c.cheapest) line(c.best, " (most accurate)");
  }
}

// One line per case: for each method the time of the cheapest run that reached `target`, with its
// n or evaluation count, or "never" and the best error reached.
void print_overview(const std::vector<row>& rows, const std::vector<std::string>& case_ids, double target) {
  std::cerr << "\n| f | p | q |";
  for (const char* m : all_methods) std::cerr << ' ' << m << " |";
  std::cerr << "\n| --- | ---: | ---: |";
  for (std::size_t i = 0; i < std::size(all_methods); ++i) std::cerr << " ---: |";
  std::cerr << '\n';
  for (const std::string& id : case_ids) {
    const auto any = std::find_if(rows.begin(), rows.end(), [&](const row& r) { return r.case_id == id; });
    if (any == rows.end()) continue;
    std::cerr << "| " << any->f_name << " | " << any->p << " | " << any->q << " |";
    for (const char* method : all_methods) {
      const chosen_runs c = choose_runs(rows, id, method, target);
      char cell[96];
      if (c.cheapest != nullptr) {
        std::snprintf(cell, sizeof cell, "%s (%zu)", format_duration(c.cheapest->seconds).c_str(),
                      c.cheapest->n_or_evaluations);
      } else if (c.best != nullptr) {
        std::snprintf(cell, sizeof cell, "never; best %.1e", c.best->rel_error);
      } else {
        std::snprintf(cell, sizeof cell, "failed");
      }
      std::cerr << ' ' << cell << " |";
    }
    std::cerr << '\n';
  }
}

// The README's headline: per method, for each of two cases, the cheapest run reaching `target`
// (or, if none did, the most accurate run), side by side.
void print_headline(const std::vector<row>& rows, const std::string& case_a, const std::string& case_b,
                    double target) {
  auto cells = [&](const std::string& id, const char* method) {
    const chosen_runs c = choose_runs(rows, id, method, target);
    const row* shown = c.cheapest != nullptr ? c.cheapest : c.best;
    if (shown == nullptr) return std::string("| failed | | | ");
    std::string time = format_duration(shown->seconds);
    if (!std::isnan(shown->seconds_reuse)) time += " (" + format_duration(shown->seconds_reuse) + " reused)";
    return "| " + shown->setting + (c.cheapest == nullptr ? " (never reached; most accurate)" : "") + " | " +
           std::to_string(shown->n_or_evaluations) + " | " + format_number(shown->rel_error, 2) + " | " + time + " ";
  };
  std::cerr << "\n| method | " << case_a << ": setting | evals | rel. error | time | " << case_b
            << ": setting | evals | rel. error | time |\n| --- | --- | ---: | ---: | ---: | --- | ---: | ---: | ---: |\n";
  for (const char* method : all_methods)
    std::cerr << "| " << method << ' ' << cells(case_a, method) << cells(case_b, method) << "|\n";
}

// Sweep table of one case (the README's headline): every n >= 4 of the fixed rules and the
// tolerances 1e-3, 1e-6, 1e-9, 1e-12 and the smallest one of the adaptive methods.
void print_sweep(const std::vector<row>& rows, const std::string& case_id) {
  std::cerr << "\n#### " << case_id << "\n\n"
            << "| method | n or tol | evaluations | rel. error | error estimate | time | time, rule reused |\n"
            << "| --- | --- | ---: | ---: | ---: | ---: | ---: |\n";
  const char* shown_tolerances[] = {"tol=1.0e-03", "tol=1.0e-06", "tol=1.0e-09", "tol=1.0e-12", "tol=1.2e-14",
                                    "tol=1.0e-15"};
  auto or_dash = [](const std::string& cell) { return cell.empty() ? std::string("-") : cell; };
  for (const row& r : rows) {
    if (r.case_id != case_id) continue;
    const bool fixed = r.setting.rfind("n=", 0) == 0;
    if (fixed && r.n_or_evaluations < 4) continue;
    if (!fixed && std::find(std::begin(shown_tolerances), std::end(shown_tolerances), r.setting) ==
                      std::end(shown_tolerances))
      continue;
    std::cerr << "| " << r.method << " | " << r.setting << " | " << r.n_or_evaluations << " | "
              << or_dash(format_number(r.rel_error, 2)) << (r.status == "ok" ? "" : " (" + r.status + ")") << " | "
              << or_dash(format_number(r.rel_error_estimate, 2)) << " | " << format_duration(r.seconds) << " | "
              << format_duration(r.seconds_reuse) << " |\n";
  }
}

}  // namespace

int main(int argc, char** argv) {
  options opt;
  const int exit_code = rhabel_study::parse_command_line(
      argc, argv, "study_quadrature_convergence", "CSV on stdout; progress and markdown summaries on stderr.",
      {rhabel_study::switch_option("--quick", "2 ms timing budget per measurement, n <= 512 (runs in < 20 s)",
                                   [&] { opt.budget_seconds = 0.002; opt.n_max = 512; }),
       rhabel_study::budget_ms_option(opt.budget_seconds, "timing budget per measurement"),
       rhabel_study::size_option("--nmax", opt.n_max, "largest n for the fixed rules")});
  if (exit_code >= 0) return exit_code;
  const rhabel_study::run_record run;
  std::cerr << rhabel_study::run_record::machine_and_load() << '\n';
  gsl_set_error_handler_off();  // statuses are recorded in the CSV, never abort
  check_gsl_parameterisation();

  const weight_case weights[] = {{-0.5, 0}, {-0.9, 0}, {-0.99, 0}, {-0.99, -0.5}};
  csv();  // the CSV header
  std::vector<row> rows;
  double worst_cross_check = 0;
  for (const weight_case& w : weights) {
    for (const function_case& fc : all_functions) {
      const reference_value ref = compute_reference(w, fc.kind);
      if (ref.r1_minus_r2 >= 0) worst_cross_check = std::max(worst_cross_check, ref.r1_minus_r2.convert_to<double>());
      if (ref.r1_minus_r2 > R50(1e-30)) {
        std::cerr << "reference routes disagree for " << fc.name << " p=" << w.p << " q=" << w.q << ": "
                  << ref.r1_minus_r2 << "\n";
        return 1;
      }
      const R50& reference = ref.value;
      std::cerr << "case " << fc.name << " p=" << w.p << " q=" << w.q << ": reference "
                << ref.value.str(25) << "\n";
      switch (fc.kind) {
        case function_kind::exp: run_case<function_kind::exp>(w, fc.name, reference, opt, rows); break;
        case function_kind::cos3: run_case<function_kind::cos3>(w, fc.name, reference, opt, rows); break;
        case function_kind::pole_2: run_case<function_kind::pole_2>(w, fc.name, reference, opt, rows); break;
        case function_kind::pole_1_01: run_case<function_kind::pole_1_01>(w, fc.name, reference, opt, rows); break;
        case function_kind::runge: run_case<function_kind::runge>(w, fc.name, reference, opt, rows); break;
      }
    }
  }
  std::cerr << "reference cross-check: largest |R1 - R2|/|R1| over the series cases = " << worst_cross_check
            << "\n";
  std::cerr << "\n### Summary (target rel. error 1e-10; times are minima over repetitions)\n";
  std::vector<std::string> seen;
  for (const row& r : rows)
    if (std::find(seen.begin(), seen.end(), r.case_id) == seen.end()) seen.push_back(r.case_id);
  for (const std::string& id : seen) print_summary(rows, id, 1e-10);
  std::cerr << "\n### Overview: time per integral of the cheapest run reaching rel. error 1e-10 (n or evaluations)\n";
  print_overview(rows, seen, 1e-10);
  std::cerr << "\n### Headline: cheapest run reaching rel. error 1e-10 (time per integral, minimum over repetitions)\n";
  print_headline(rows, "cos(3x) @ p=-0.9 q=0", "1/(1.01-x) @ p=-0.99 q=0", 1e-10);
  std::cerr << "\n### Headline sweeps\n";
  print_sweep(rows, "cos(3x) @ p=-0.9 q=0");
  print_sweep(rows, "1/(1.01-x) @ p=-0.99 q=0");
  std::cerr << '\n' << run.totals() << '\n';
  return 0;
}
