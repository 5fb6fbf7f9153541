// materials/src/master_curve.cpp: see rhabel/materials/master_curve.hpp.
#include "rhabel/materials/master_curve.hpp"
#include "rhabel/materials/text_file.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>

namespace rhabel::materials {
namespace {

std::string short_num(double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6g", x);
  return buf;
}

// Printable excerpt of a field (control characters escaped, at most 40 bytes).
std::string excerpt(std::string_view text) { return printable(text, 40); }

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t start = 0;
  for (;;) {
    const auto comma = line.find(',', start);
    out.push_back(trim(line.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start)));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return out;
}

enum class layout { storage_loss, abs_tan };

// Linear interpolation of ys in xs (xs increasing) at x, x inside [xs.front(), xs.back()].
double interpolate(const std::vector<double>& xs, const std::vector<double>& ys, double x) {
  if (x <= xs.front()) return ys.front();
  if (x >= xs.back()) return ys.back();
  const auto it = std::upper_bound(xs.begin(), xs.end(), x);
  const auto i = static_cast<std::size_t>(it - xs.begin()) - 1;
  const double t = (x - xs[i]) / (xs[i + 1] - xs[i]);
  return ys[i] + t * (ys[i + 1] - ys[i]);
}

struct log_curve {
  std::vector<double> x, lnE, phase;
  explicit log_curve(const master_curve& c) {
    for (std::size_t i = 0; i < c.omega.size(); ++i) {
      x.push_back(std::log(c.omega[i]));
      lnE.push_back(std::log(c.modulus[i]));
      phase.push_back(std::atan(c.tan_delta[i]));
    }
  }
};

}  // namespace

master_curve parse_master_curve(std::string_view text, const std::string& source) {
  const std::string where = "master curve '" + excerpt(source) + "'";
  auto fail = [&](const std::string& what) { throw std::invalid_argument(where + ": " + what); };
  text = without_bom(text);
  master_curve curve;
  curve.source = source;
  std::vector<std::string> names;
  bool hertz = false;
  layout kind = layout::storage_loss;
  std::size_t line_no = 0, start = 0;
  while (start <= text.size()) {
    auto end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view raw = text.substr(start, end - start);
    start = end + 1;
    ++line_no;
    const auto line = trim(raw);
    if (line.empty() || line.front() == '#') {
      if (end == text.size()) break;
      continue;
    }
    if (line.find('\0') != std::string_view::npos) fail("row " + std::to_string(line_no) + " contains a NUL byte");
    const auto fields = split(line);
    if (names.empty()) {  // the header
      const char* first_valid = "omega or f_hz";
      for (std::size_t j = 0; j < fields.size(); ++j) {
        const std::string name(fields[j]);
        const std::string col = "row " + std::to_string(line_no) + ", column " + std::to_string(j + 1) + " ('" +
                                excerpt(name) + "')";
        if (j == 0) {
          if (name == "omega") hertz = false;
          else if (name == "f_hz") hertz = true;
          else fail(col + ": unknown column, expected " + first_valid +
                    " (headers: omega,E_storage,E_loss | f_hz,E_storage,E_loss | omega,E_abs,tan_delta | f_hz,E_abs,tan_delta)");
        } else if (j == 1) {
          if (name == "E_storage") kind = layout::storage_loss;
          else if (name == "E_abs") kind = layout::abs_tan;
          else fail(col + ": unknown column, expected E_storage or E_abs");
        } else if (j == 2) {
          const char* want = kind == layout::storage_loss ? "E_loss" : "tan_delta";
          if (name != want) fail(col + ": unknown column, expected " + want);
        } else {
          fail(col + ": unknown column (a master curve has exactly 3 columns)");
        }
        names.push_back(name);
      }
      if (names.size() < 3) {
        fail("row " + std::to_string(line_no) + ": the header has " + std::to_string(names.size()) +
             " column(s), expected 3 (e.g. omega,E_storage,E_loss)");
      }
      if (end == text.size()) break;
      continue;
    }
    if (fields.size() != 3) {
      fail("row " + std::to_string(line_no) + ": " + std::to_string(fields.size()) + " column(s), expected 3 (" +
           names[0] + "," + names[1] + "," + names[2] + ")");
    }
    double v[3];
    for (std::size_t j = 0; j < 3; ++j) {
      const std::string col = "row " + std::to_string(line_no) + ", column " + std::to_string(j + 1) + " (" + names[j] + ")";
      const std::string field(fields[j]);
      char* stop = nullptr;
      errno = 0;
      const double x = field.empty() ? 0 : std::strtod(field.c_str(), &stop);
      if (field.empty() || stop != field.c_str() + field.size()) fail(col + ": '" + excerpt(field) + "' is not a number");
      // strtod also reads C's hexadecimal floats (0x1p+23), which no measurement file contains.
      if (field.find_first_of("xX") != std::string::npos) {
        fail(col + ": '" + excerpt(field) + "' is a hexadecimal number (decimal numbers only)");
      }
      if (!std::isfinite(x) || (errno == ERANGE && std::fabs(x) > 1)) {
        fail(col + ": '" + excerpt(field) + "' is not a finite number");
      }
      v[j] = x;
    }
    const std::string row = "row " + std::to_string(line_no) + ", column ";
    if (!(v[0] > 0)) fail(row + "1 (" + names[0] + "): frequency " + short_num(v[0]) + " must be > 0");
    const double omega = hertz ? 2 * std::numbers::pi * v[0] : v[0];
    if (!curve.omega.empty() && !(omega > curve.omega.back())) {
      fail(row + "1 (" + names[0] + "): frequency " + short_num(v[0]) +
           " is not greater than the previous row's (frequencies must increase strictly)");
    }
    double modulus = 0, tan_delta = 0;
    if (kind == layout::storage_loss) {
      if (!(v[1] > 0)) fail(row + "2 (E_storage): " + short_num(v[1]) + " must be > 0 (storage modulus, Pa)");
      if (!(v[2] >= 0)) fail(row + "3 (E_loss): " + short_num(v[2]) + " must be >= 0 (loss modulus, Pa)");
      modulus = std::hypot(v[1], v[2]);
      tan_delta = v[2] / v[1];
    } else {
      if (!(v[1] > 0)) fail(row + "2 (E_abs): " + short_num(v[1]) + " must be > 0 (|E*|, Pa)");
      if (!(v[2] >= 0)) fail(row + "3 (tan_delta): " + short_num(v[2]) + " must be >= 0");
      modulus = v[1];
      tan_delta = v[2];
    }
    if (!std::isfinite(modulus) || !std::isfinite(tan_delta)) {
      fail("row " + std::to_string(line_no) + ": |E*| or tan delta overflows a double");
    }
    curve.omega.push_back(omega);
    curve.modulus.push_back(modulus);
    curve.tan_delta.push_back(tan_delta);
    if (end == text.size()) break;
  }
  if (names.empty()) fail("no header line (expected e.g. omega,E_storage,E_loss)");
  if (curve.omega.size() < 3) {
    fail("has " + std::to_string(curve.omega.size()) + " data row(s), at least 3 are needed");
  }
  return curve;
}

master_curve read_master_curve(const std::string& path) {
  return parse_master_curve(read_text_file(path, "master curve"), path);
}

double wlf_log10_shift(const wlf_shift& wlf, double temperature) {
  if (!std::isfinite(wlf.C1) || !std::isfinite(wlf.C2) || !std::isfinite(wlf.T_ref) || !std::isfinite(temperature)) {
    throw std::domain_error("rhabel::materials::wlf_log10_shift: C1, C2, T_ref and the temperature must be finite");
  }
  const double dT = temperature - wlf.T_ref;
  const double denominator = wlf.C2 + dT;
  if (!(denominator > 0)) {
    throw std::domain_error("rhabel::materials::wlf_log10_shift: C2 + T - T_ref = " + short_num(denominator) +
                            " must be > 0 (temperature " + short_num(temperature) + " is below T_ref - C2 = " +
                            short_num(wlf.T_ref - wlf.C2) + ", where the WLF equation has no meaning)");
  }
  return -wlf.C1 * dT / denominator + 0.0;  // + 0.0: T = T_ref gives +0, not -0
}

master_curve shift_to_temperature(const master_curve& curve, const wlf_shift& wlf, double temperature) {
  const double log10_aT = wlf_log10_shift(wlf, temperature);
  const double factor = std::pow(10.0, -log10_aT);  // omega_T = omega_ref / a_T
  master_curve out = curve;
  for (auto& w : out.omega) w *= factor;
  if (!std::isfinite(out.omega.back()) || !(out.omega.front() > 0)) {
    throw std::domain_error("rhabel::materials::shift_to_temperature: the WLF shift 10^" + short_num(-log10_aT) +
                            " takes the frequencies beyond the double range");
  }
  return out;
}

const char* to_string(fit_status status) {
  switch (status) {
    case fit_status::ok: return "ok";
    case fit_status::poor_power_law: return "poor_power_law";
    case fit_status::window_clipped: return "window_clipped";
    case fit_status::not_converged: return "not_converged";
  }
  return "unknown";
}

local_fit fit_at(const master_curve& curve, double omega0, const fit_options& options) {
  if (curve.omega.size() < 2) throw std::invalid_argument("rhabel::materials::fit_at: the master curve has fewer than 2 points");
  if (!(options.half_window_decades > 0) || !(options.warning_threshold > 0)) {
    throw std::invalid_argument("rhabel::materials::fit_at: half_window_decades and warning_threshold must be > 0");
  }
  const double lo = curve.omega.front(), hi = curve.omega.back();
  if (!(omega0 >= lo && omega0 <= hi)) {
    throw std::domain_error("rhabel::materials::fit_at: omega0 = " + short_num(omega0) + " rad/s is outside the master curve's range [" +
                            short_num(lo) + ", " + short_num(hi) + "] rad/s (no extrapolation)");
  }
  const log_curve c(curve);
  const double x0 = std::log(omega0);
  const double h = options.half_window_decades * std::numbers::ln10;
  double xl = x0 - h, xh = x0 + h;
  const bool clipped = xl < c.x.front() || xh > c.x.back();
  xl = std::max(xl, c.x.front());
  xh = std::min(xh, c.x.back());
  local_fit f;
  f.omega0 = omega0;
  f.window_lo = std::exp(xl);
  f.window_hi = std::exp(xh);
  if (xh - xl > 1e-9) {
    f.alpha_slope = (interpolate(c.x, c.lnE, xh) - interpolate(c.x, c.lnE, xl)) / (xh - xl);
  } else {  // degenerate window (should not happen: h > 0 and the range has 2 distinct points)
    const auto it = std::upper_bound(c.x.begin(), c.x.end() - 1, x0);
    const auto i = std::max<std::ptrdiff_t>(0, it - c.x.begin() - 1);
    f.alpha_slope = (c.lnE[i + 1] - c.lnE[i]) / (c.x[i + 1] - c.x[i]);
  }
  f.alpha_tan_delta = 2 / std::numbers::pi * interpolate(c.x, c.phase, x0);
  f.modulus = std::exp(interpolate(c.x, c.lnE, x0));
  if (!(f.alpha_slope >= 0 && f.alpha_slope < 1)) {
    throw std::domain_error("rhabel::materials::fit_at: the slope d ln|E*|/d ln omega of " + curve.source + " around omega0 = " +
                            short_num(omega0) + " rad/s is " + short_num(f.alpha_slope) +
                            ", outside [0, 1): no power law E(t) = E1 t^-alpha fits there");
  }
  f.alpha = f.alpha_slope;
  f.E1 = f.modulus / (std::tgamma(1 - f.alpha) * std::pow(omega0, f.alpha));
  // |E*| and omega0 are doubles, but E1 = |E*| / (Gamma(1 - alpha) omega0^alpha) can leave their
  // range (fuzzed: |E*| ~ 1e300 at omega0 ~ 1e-231 rad/s gives E1 = inf).
  if (!std::isfinite(f.E1) || !(f.E1 > 0)) {
    throw std::domain_error("rhabel::materials::fit_at: the power law's E1 = |E*| / (Gamma(1 - alpha) omega0^alpha) = " +
                            short_num(f.modulus) + " / (Gamma(" + short_num(1 - f.alpha) + ") " + short_num(omega0) + "^" +
                            short_num(f.alpha) + ") of " + curve.source + " is outside the double range");
  }
  const double gap = std::fabs(f.alpha_slope - f.alpha_tan_delta);
  if (gap > options.warning_threshold) {
    f.status = fit_status::poor_power_law;
    f.warning = "the power law is poor at omega0 = " + short_num(omega0) + " rad/s: alpha from the slope of |E*| = " +
                short_num(f.alpha_slope) + ", from tan delta = " + short_num(f.alpha_tan_delta) + " (differ by " +
                short_num(gap) + " > " + short_num(options.warning_threshold) + ")";
  } else if (clipped) {
    f.status = fit_status::window_clipped;
    f.warning = "the fit window around omega0 = " + short_num(omega0) + " rad/s was clipped to [" +
                short_num(f.window_lo) + ", " + short_num(f.window_hi) + "] rad/s by the end of the measured range";
  }
  return f;
}

fixed_point_fit fit_fixed_point(const master_curve& curve, double speed,
                                const std::function<double(const local_fit&)>& contact_length,
                                const fit_options& options, std::optional<double> initial_length, double tolerance,
                                std::size_t max_iterations) {
  if (!(speed > 0) || !std::isfinite(speed)) throw std::invalid_argument("rhabel::materials::fit_fixed_point: speed must be > 0 and finite");
  const double xmin = std::log(curve.omega.front()), xmax = std::log(curve.omega.back());
  fixed_point_fit out;
  // g(x) = ln(U / L(fit at e^x)); x* = g(x*).
  double last_length = 0;
  local_fit last_fit;
  auto g = [&](double x) {
    // exp(ln omega) may round just outside the range at its ends: clamp to the measured values.
    last_fit = fit_at(curve, std::clamp(std::exp(x), curve.omega.front(), curve.omega.back()), options);
    last_length = contact_length(last_fit);
    ++out.iterations;
    if (!(last_length > 0) || !std::isfinite(last_length)) {
      throw std::domain_error("rhabel::materials::fit_fixed_point: the contact length " + short_num(last_length) +
                              " m is not positive (no contact frequency U/L)");
    }
    return std::log(speed / last_length);
  };
  auto clamp = [&](double x) { return std::clamp(x, xmin, xmax); };
  double x0 = initial_length ? clamp(std::log(speed / *initial_length)) : 0.5 * (xmin + xmax);
  double g0 = g(x0);
  double x1 = clamp(g0);
  bool stuck_low = false, stuck_high = false;
  while (out.iterations < max_iterations) {
    const double g1 = g(x1);
    const double h0 = g0 - x0, h1 = g1 - x1;
    if (std::fabs(h1) <= tolerance) {
      out.converged = true;
      break;
    }
    double x2 = clamp(g1);  // substitution
    if (h1 != h0) {
      const double secant = x1 - h1 * (x1 - x0) / (h1 - h0);
      if (std::isfinite(secant)) x2 = clamp(secant);
    }
    // The fixed point lies beyond the range when the map pushes out at a bound: x - g(x) is
    // increasing (g has slope about alpha/(1 - alpha) < 1 in magnitude, top of the header), so no
    // root lies inside once it has the wrong sign at the bound.
    stuck_low = x1 == xmin && g1 < xmin;
    stuck_high = x1 == xmax && g1 > xmax;
    if (stuck_low || stuck_high) {
      throw std::domain_error("rhabel::materials::fit_fixed_point: the contact frequency U/L = " + short_num(std::exp(g1)) +
                              " rad/s lies outside the master curve's range [" + short_num(curve.omega.front()) +
                              ", " + short_num(curve.omega.back()) + "] rad/s");
    }
    if (x2 == x1) x2 = clamp(g1);
    x0 = x1;
    g0 = g1;
    x1 = x2;
  }
  out.fit = last_fit;
  out.contact_length = last_length;
  return out;
}

}  // namespace rhabel::materials
