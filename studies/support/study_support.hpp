// studies/support/study_support.hpp
//
// The plumbing the study executables share, so that every study times, formats, writes CSV and
// reads its command line the same way:
//
//   min_time_per_call(call, budget)   minimum time per call of call(): calls are batched until a
//                                     batch lasts >= 0.2 ms (steady_clock resolution and call
//                                     overhead become negligible), batches are repeated until
//                                     `budget` seconds have passed, and the MINIMUM per-call time
//                                     over the batches is reported (the least disturbed run on a
//                                     shared machine), with the process CPU time per call of the
//                                     same batch. A call slower than the budget runs once.
//   relative_error(value, reference)  |value - reference| / |reference| evaluated in the type of
//                                     the arguments (pass 50-digit numbers to keep the reference's
//                                     digits); NaN for a non-finite value.
//   format_number(v, digits)          printf %.<digits>g; NaN -> "" (an empty cell = no value).
//   format_duration(seconds)          "12.3 us", "4.56 ms", "7.89 s" (3 digits); NaN or < 0 -> "-".
//   csv_writer                        header + rows, RFC 4180 quoting where a cell needs it, a flush
//                                     after every row (a long study shows progress in its CSV).
//   parse_command_line(...)           --flag and --flag VALUE options with a generated usage text;
//                                     switch_option, budget_ms_option, size_option build the
//                                     common ones (the latter two print the code's default).
//   run_record                        wall and CPU time of the run, CPU model and load average
//                                     (/proc), for the head and foot of a study's markdown output.
//   wedge_moment_reference<Big>(...)  eps, 1 - eps and the contact length L of the isolated wedge
//                                     below the boundary, in the precision Big (pass
//                                     cpp_bin_float_50): the wedge studies' reference for eps and L.
//   wedge_friction, wedge_friction_error  C_f of a wedge from int g and int_a^apex g; its error
//                                     relative to max(|C_f|, min(S1, S2)).
//
// Header-only; beyond the standard library it needs Boost.Math (incomplete beta and its inverse,
// for wedge_moment_reference only; a template, so a study that does not call it instantiates
// nothing of it). A study that calls it with cpp_bin_float_50 must #define
// BOOST_MATH_DISABLE_FLOAT128 before its first include: ibeta_inv at 50 digits instantiates erf_inv
// initialisers that reference libquadmath otherwise (the studies link no libquadmath).
// Include it from a studies/*.cpp as "support/study_support.hpp" (quoted includes resolve relative
// to the including file, so the studies need no extra include directory; studies/CMakeLists.txt
// builds only studies/*.cpp).
#pragma once

#include <boost/math/constants/constants.hpp>
#include <boost/math/special_functions/beta.hpp>
#include <boost/math/special_functions/gamma.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <functional>
#include <initializer_list>
#include <iostream>
#include <limits>
#include <ostream>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace rhabel_study {

// ---------------------------------------------------------------------------------------------
// Timing.

/// Result of min_time_per_call: the minimum wall time per call, the process CPU time per call
/// in the same batch (CPU well below wall: the process waited for a core), and how many calls
/// were timed.
struct timing {
  double seconds;
  double cpu_seconds;
  std::size_t calls;
};

/// CPU time of this process so far (std::clock: all threads; 1 us resolution on Linux/glibc).
inline double process_cpu_seconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

namespace detail {
/// Results of timed calls are added here so that the compiler cannot drop the calls.
inline volatile double timing_sink = 0;
}  // namespace detail

/// Minimum time per call of call() (which returns something convertible to double, added to a
/// volatile sink so the call is not optimised away); see the top of this header. budget_seconds
/// >= 0; at most 100000 batches and batches of at most 2^24 calls.
template <class Call>
timing min_time_per_call(Call&& call, double budget_seconds) {
  using clock = std::chrono::steady_clock;
  constexpr double resolvable_seconds = 2e-4;  // >> steady_clock's resolution and call overhead
  const auto start = clock::now();
  std::size_t batch = 1, calls = 0;
  double best = std::numeric_limits<double>::infinity(), best_cpu = best;
  for (int repetition = 0; repetition < 100000; ++repetition) {
    const double cpu0 = process_cpu_seconds();
    const auto t0 = clock::now();
    double sum = 0;
    for (std::size_t i = 0; i < batch; ++i) sum += static_cast<double>(call());
    const double dt = std::chrono::duration<double>(clock::now() - t0).count();
    const double cpu = process_cpu_seconds() - cpu0;
    detail::timing_sink = detail::timing_sink + sum;
    calls += batch;
    if (dt < resolvable_seconds && batch < (std::size_t{1} << 24)) {  // too short to resolve: grow the batch
      batch *= 2;
      continue;
    }
    if (dt / static_cast<double>(batch) < best) {
      best = dt / static_cast<double>(batch);
      best_cpu = cpu / static_cast<double>(batch);
    }
    if (std::chrono::duration<double>(clock::now() - start).count() > budget_seconds) break;
  }
  return {best, best_cpu, calls};
}

// ---------------------------------------------------------------------------------------------
// Where and how a study ran, for the head of its markdown output.

/// Wall and CPU time since construction, and a description of the machine and its load.
class run_record {
 public:
  run_record() : wall0_(std::chrono::steady_clock::now()), cpu0_(process_cpu_seconds()) {}

  double wall_seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0_).count();
  }
  double cpu_seconds() const { return process_cpu_seconds() - cpu0_; }

  /// "machine: <cpu model>, <n> hardware threads; load average (1, 5, 15 min): a b c" from
  /// /proc (Linux); parts that cannot be read are left out.
  static std::string machine_and_load() {
    std::string model, load;
    if (std::FILE* f = std::fopen("/proc/cpuinfo", "r")) {
      char line[512];
      while (std::fgets(line, sizeof line, f) != nullptr) {
        const std::string s = line;
        if (s.rfind("model name", 0) == 0 && s.find(':') != std::string::npos) {
          model = s.substr(s.find(':') + 2);
          model.erase(model.find_last_not_of(" \n") + 1);
          break;
        }
      }
      std::fclose(f);
    }
    if (std::FILE* f = std::fopen("/proc/loadavg", "r")) {
      double a = 0, b = 0, c = 0;
      if (std::fscanf(f, "%lf %lf %lf", &a, &b, &c) == 3) {
        char buffer[96];
        std::snprintf(buffer, sizeof buffer, "load average (1, 5, 15 min): %.2f %.2f %.2f", a, b, c);
        load = buffer;
      }
      std::fclose(f);
    }
    std::string out = "machine: " + (model.empty() ? std::string("unknown CPU") : model) + ", " +
                      std::to_string(std::thread::hardware_concurrency()) + " hardware threads";
    return load.empty() ? out : out + "; " + load;
  }

  /// "run: wall W s, CPU C s" (CPU well below wall: the machine was busy with other work).
  std::string totals() const {
    char buffer[96];
    std::snprintf(buffer, sizeof buffer, "run: wall %.1f s, CPU %.1f s", wall_seconds(), cpu_seconds());
    return buffer;
  }

 private:
  std::chrono::steady_clock::time_point wall0_;
  double cpu0_;
};

// ---------------------------------------------------------------------------------------------
// Accuracy.

/// |value - reference| / |reference| in Real (use cpp_bin_float_50 for a 50-digit reference:
/// then rounding the reference to double adds nothing and errors of 1e-17 are reported).
/// NaN if value is not finite; reference must be non-zero.
template <class Real>
double relative_error(const Real& value, const Real& reference) {
  using std::abs;
  using std::isfinite;
  if (!isfinite(value)) return std::numeric_limits<double>::quiet_NaN();
  return static_cast<double>(Real(abs(value - reference) / abs(reference)));
}

// ---------------------------------------------------------------------------------------------
// Formatting.

/// printf("%.<digits>g", v); NaN gives the empty string (an empty CSV cell means "no value").
inline std::string format_number(double v, int digits = 17) {
  if (std::isnan(v)) return "";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, v);
  return buffer;
}

/// A time for a markdown table, 3 significant digits in us below 1 ms, ms below 1 s, else s.
/// NaN or negative (not measured) gives "-".
inline std::string format_duration(double seconds) {
  if (!(seconds >= 0)) return "-";
  char buffer[32];
  if (seconds < 1e-3)
    std::snprintf(buffer, sizeof buffer, "%.3g us", seconds * 1e6);
  else if (seconds < 1)
    std::snprintf(buffer, sizeof buffer, "%.3g ms", seconds * 1e3);
  else
    std::snprintf(buffer, sizeof buffer, "%.3g s", seconds);
  return buffer;
}

// ---------------------------------------------------------------------------------------------
// The isolated wedge below the boundary: eps and L at high precision.

/// eps = (apex - a)/L, 1 - eps = (b - apex)/L and L = b - a of the isolated wedge (slopes S1 ahead
/// of the apex, S2 behind it) under `load`, below the boundary alpha + beta/2 < 1/2 (gam > 0).
template <class Big>
struct wedge_moments {
  Big eps, one_minus_eps, L;
};

/// The reference of study_scene_timing and study_wedge_near_edge for eps and L, every operation
/// in Big (pass cpp_bin_float_50; see the top of this header for BOOST_MATH_DISABLE_FLOAT128):
///   eps from I_eps(del, gam) = S2/(S1 + S2), 1 - eps from I_(1-eps)(gam, del) = S1/(S1 + S2)
///   (each accurate where it is tiny), gam = (1 - 2 alpha - beta)/2, del = (1 + beta)/2 (docs/theory.md
///   section 5);
///   L from the load moment int g = (cos(beta pi/2)/(pi Gamma(1-alpha))) L^(1-alpha)
///   [S1 B_eps(P, Q) - S2 (B(P, Q) - B_eps(P, Q))], P = (1 + beta)/2, Q = (3 - beta)/2 - alpha (the
///   moment formula for int_a^b g of the Riemann-Hilbert route, riemann/abel_solver.hpp, for
///   piecewise constant F), and load = (pi/2) E_U int g. The solver (punch/src/contact.cpp) takes
///   L from the cancellation-free form (S1 + S2) eps^del (1-eps)^gam / (1 - alpha) of the same
///   integral: a different formula. The bracket here amplifies the rounding of the beta
///   functions by up to max(S1, S2)/min(S1, S2) (1e6 at the slope ratios 1e-6 and 1e6 of the
///   studies, checked at 80 digits): 50 digits leave far more than double needs.
/// E_U = E1 Gamma(1 - alpha) U^alpha / (1 - nu^2) (material::effective_modulus). Throws
/// std::domain_error if alpha + beta/2 >= 1/2 or a slope, the load or E_U is not positive.
template <class Big>
wedge_moments<Big> wedge_moment_reference(const Big& alpha, const Big& beta, const Big& S1, const Big& S2,
                                          const Big& load, const Big& E_U) {
  using std::cos;
  using std::pow;
  auto require = [](bool ok, const char* parameter, const Big& value, const char* range) {
    if (!ok)
      throw std::domain_error(std::string("wedge_moment_reference: ") + parameter + " = " +
                              format_number(static_cast<double>(value)) + " outside " + range);
  };
  require(alpha + beta / 2 < Big(0.5), "alpha + beta/2", alpha + beta / 2, "(-inf, 1/2) (below the boundary)");
  require(S1 > 0, "S1", S1, "(0, inf)");
  require(S2 > 0, "S2", S2, "(0, inf)");
  require(load > 0, "load", load, "(0, inf)");
  require(E_U > 0, "E_U", E_U, "(0, inf)");
  const Big pi = boost::math::constants::pi<Big>();
  const Big gam = (1 - 2 * alpha - beta) / 2, del = (1 + beta) / 2;
  const Big ratio = S2 / (S1 + S2);
  wedge_moments<Big> out;
  out.eps = boost::math::ibeta_inv(del, gam, ratio);
  out.one_minus_eps = boost::math::ibeta_inv(gam, del, 1 - ratio);
  const Big P = (1 + beta) / 2, Q = (3 - beta) / 2 - alpha;
  const Big B = boost::math::beta(P, Q), Be = boost::math::beta(P, Q, out.eps);
  const Big unit = cos(beta * pi / 2) / (pi * boost::math::tgamma(1 - alpha)) * (S1 * Be - S2 * (B - Be));
  out.L = pow(load / (pi / 2 * E_U * unit), 1 / (1 - alpha));
  return out;
}

/// C_f of a wedge from its density g: (S1 int_a^apex g - S2 int_apex^b g) / int_a^b g, given
/// total = int_a^b g and ahead = int_a^apex g (the definition used by tests/punch/support.hpp's
/// wedge_oracle and by the wedge studies' references).
inline double wedge_friction(double S1, double S2, double total, double ahead) {
  return (S1 * ahead - S2 * (total - ahead)) / total;
}

/// Error of a wedge's C_f relative to max(|C_f_ref|, min(S1, S2)): C_f vanishes for the elastic
/// frictionless wedge, and min(S1, S2) is the scale of its two faces' shares.
inline double wedge_friction_error(double cf, double cf_ref, double S1, double S2) {
  return std::abs(cf - cf_ref) / std::max(std::abs(cf_ref), std::min(S1, S2));
}

// ---------------------------------------------------------------------------------------------
// CSV.

/// Writes a header on construction and then rows of already formatted cells. A cell holding a
/// comma, a double quote or a newline is quoted (RFC 4180); every row is flushed. A row whose
/// length differs from the header's throws std::logic_error (a study bug, never a data problem).
class csv_writer {
 public:
  csv_writer(std::ostream& out, std::initializer_list<std::string> columns) : out_(out), columns_(columns.size()) {
    write(columns);
  }

  void row(std::initializer_list<std::string> cells) {
    if (cells.size() != columns_)
      throw std::logic_error("csv_writer::row: " + std::to_string(cells.size()) + " cells for " +
                             std::to_string(columns_) + " columns");
    write(cells);
  }

  static std::string quote(const std::string& cell) {
    if (cell.find_first_of(",\"\n") == std::string::npos) return cell;
    std::string out = "\"";
    for (char c : cell) {
      if (c == '"') out += '"';
      out += c;
    }
    return out + "\"";
  }

 private:
  void write(std::initializer_list<std::string> cells) {
    bool first = true;
    for (const std::string& cell : cells) {
      if (!first) out_ << ',';
      out_ << quote(cell);
      first = false;
    }
    out_ << '\n';
    out_.flush();
  }

  std::ostream& out_;
  std::size_t columns_;
};

// ---------------------------------------------------------------------------------------------
// Command line.

/// One option of a study: `flag` alone (value_name empty) or `flag VALUE` (a number, strtod
/// syntax, e.g. 1e6). `apply` receives the value (0 for a switch).
struct option {
  std::string flag;
  std::string value_name;
  std::string help;
  std::function<void(double)> apply;
};

/// A switch: `flag` alone runs `apply`.
inline option switch_option(const std::string& flag, const std::string& help, std::function<void()> apply) {
  return {flag, "", help, [apply = std::move(apply)](double) { apply(); }};
}

/// `--budget-ms X`: the timing budget per measurement, stored in seconds; the help line ends with
/// the current value of `budget_seconds` as the default (so it cannot drift from the code).
inline option budget_ms_option(double& budget_seconds, const std::string& help) {
  return {"--budget-ms", "X", help + " (default " + format_number(budget_seconds * 1000, 6) + ")",
          [&budget_seconds](double x) { budget_seconds = x / 1000; }};
}

/// `flag N`: a size (largest n, ...); the help line ends with the current value as the default.
inline option size_option(const std::string& flag, std::size_t& value, const std::string& help) {
  return {flag, "N", help + " (default " + std::to_string(value) + ")",
          [&value](double x) { value = static_cast<std::size_t>(x); }};
}

/// Applies the options in argv[1..argc). Returns -1 to go on; otherwise the usage text
/// ("usage: <program> [options]", `summary`, one line per option) has been written to stderr
/// and the study should exit with the returned code: 0 after --help, 2 after an unknown flag,
/// a missing value or a value that is not a number.
inline int parse_command_line(int argc, char** argv, const std::string& program, const std::string& summary,
                              const std::vector<option>& options) {
  auto usage = [&](int code) {
    std::cerr << "usage: " << program;
    for (const option& o : options) std::cerr << " [" << o.flag << (o.value_name.empty() ? "" : " " + o.value_name) << ']';
    std::cerr << "\n  " << summary << '\n';
    std::size_t width = 0;
    for (const option& o : options) width = std::max(width, o.flag.size() + 1 + o.value_name.size());
    for (const option& o : options) {
      const std::string left = o.flag + (o.value_name.empty() ? "" : " " + o.value_name);
      std::cerr << "  " << left << std::string(width + 2 - left.size(), ' ') << o.help << '\n';
    }
    return code;
  };
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--help") return usage(0);
    const auto match = std::find_if(options.begin(), options.end(), [&](const option& o) { return o.flag == arg; });
    if (match == options.end()) {
      std::cerr << program << ": unknown argument '" << arg << "'\n";
      return usage(2);
    }
    if (match->value_name.empty()) {
      match->apply(0);
      continue;
    }
    if (i + 1 >= argc) {
      std::cerr << program << ": " << arg << " needs a value " << match->value_name << '\n';
      return usage(2);
    }
    const char* text = argv[++i];
    char* end = nullptr;
    const double value = std::strtod(text, &end);
    if (end == text || *end != '\0' || !std::isfinite(value)) {
      std::cerr << program << ": " << arg << " " << match->value_name << ": '" << text << "' is not a number\n";
      return usage(2);
    }
    match->apply(value);
  }
  return -1;
}

}  // namespace rhabel_study
