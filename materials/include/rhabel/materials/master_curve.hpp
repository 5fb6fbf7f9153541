// rhabel/materials/master_curve.hpp: power-law parameters (alpha, E1) of E(t) = E1 t^-alpha from a
// measured dynamic master curve, at the frequency a sliding contact excites.
//
// WHAT IS COMPUTED
//   A master curve is the complex modulus E*(omega) = E' + i E'' of a material against angular
//   frequency, shifted to a reference temperature (dynamic mechanical analysis). rhabel's contact
//   solver needs a power-law relaxation modulus E(t) = E1 t^-alpha. This module reads the curve
//   (CSV), shifts it to a temperature (WLF), and fits the power law that matches the curve around a
//   frequency omega0, chosen self-consistently as omega0 = U/L (U: sliding speed, L: contact length,
//   which itself depends on alpha and E1: fit_fixed_point).
//
// THEORY
//   For E(t) = E1 t^-alpha (0 <= alpha < 1) the complex modulus is
//       E*(omega) = i omega int_0^inf E(t) e^{-i omega t} dt = E1 Gamma(1 - alpha) (i omega)^alpha,
//   so |E*| = E1 Gamma(1 - alpha) omega^alpha and the loss angle is constant, delta = alpha pi/2.
//   Two local estimates of alpha follow, equal on an exact power law:
//       alpha_slope     = d ln|E*| / d ln omega, taken as the SECANT slope of the curve over the
//                         window [omega0 / 10^h, omega0 10^h] (h = fit_options::half_window_decades,
//                         default 0.5: one decade, the band a contact of length L excites around
//                         U/L), on the piecewise-linear interpolant of ln|E*| in ln omega;
//       alpha_tan_delta = (2/pi) atan(tan delta) at omega0 (delta interpolated linearly in ln omega).
//   The fit uses alpha = alpha_slope (it fixes how E_U scales across the band) and
//       E1 = |E*(omega0)| / (Gamma(1 - alpha) omega0^alpha),
//   |E*(omega0)| from the log-log interpolant. For a real material the two estimates agree where the
//   curve is locally a power law (for a curve obeying the Kramers-Kronig relations they differ by
//   about (pi^2/12) d^3 ln|E*|/d(ln omega)^3: a few 1e-3 on a smooth transition zone) and disagree
//   next to a knee, a plateau onset or a loss peak, where the power law is a poor description of
//   what the contact feels.
//   Warning threshold (fit_options::warning_threshold, default 0.05): |alpha_slope - alpha_tan_delta|
//   above it gives status "poor_power_law" with a message. A window that had to be clipped at the end
//   of the measured range gives status "window_clipped". Neither is ever silent; the fit is still
//   returned (the caller decides).
//   WLF time-temperature superposition (no vertical shift): log10 a_T = -C1 (T - T_ref)/(C2 + T - T_ref)
//   and E*(omega; T) = E*(omega a_T; T_ref), i.e. the curve at T is the reference curve with every
//   frequency divided by a_T. Valid only for C2 + T - T_ref > 0 (else std::domain_error).
//   Fixed point: omega0 = U / L(alpha(omega0), E1(omega0)) is solved in x = ln omega0 by a secant
//   iteration on x - ln(U/L) (first step: plain substitution); for a power-law material the map has
//   slope about alpha/(1 - alpha) (the contact length of a parabola scales as E_U^(-1/(2 - alpha))),
//   so it is well posed; converged when successive x differ by at most `tolerance` (default 1e-10).
//
// LIMITS
//   * The CSV: header `omega,E_storage,E_loss` (rad/s, Pa, Pa), `f_hz,E_storage,E_loss` (Hz) or
//     `omega,E_abs,tan_delta` / `f_hz,E_abs,tan_delta` (|E*| in Pa), columns in that order; lines
//     starting with '#' and blank lines are ignored; at least 3 data rows; frequencies > 0 and
//     strictly increasing; E_storage > 0, E_loss >= 0, E_abs > 0, tan_delta >= 0; every value a finite
//     decimal number (no hexadecimal floats); a UTF-8 byte-order mark at the start is skipped
//     (materials::without_bom, the rule of every CSV rhabel reads). Any violation: std::invalid_argument, one line naming the source, the row (line number
//     in the file, from 1) and the column (name and position, from 1).
//   * omega0 must lie inside the measured range (no extrapolation: std::domain_error). The slope must
//     give alpha in [0, 1) (else std::domain_error: no such power law).
//   * A power law describes the material only over the window; the fit says nothing about
//     frequencies far from omega0 (a contact excites roughly one to two decades around U/L).
//
// ACCURACY (tests/materials/test_master_curve.cpp)
//   On a curve sampled from an exact power law the fit returns alpha and E1 to rounding (measured
//   1.0e-15 in alpha and 2.8e-14 relative in E1, alpha 0 .. 0.8, omega0 0.05 .. 1e9 rad/s on a curve
//   sampled at 17 digits over 0.01 .. 1e10 rad/s; test tolerance 1e-12); the WLF shift matches
//   hand-computed values to 1e-15. Against a smooth curve the fit is exact to the interpolation of
//   the samples: its accuracy is that of the measurement and of its sampling (10 points per decade
//   in the shipped example).
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rhabel::materials {

/// A master curve at one temperature: |E*| and tan delta against angular frequency.
struct master_curve {
  std::vector<double> omega;      ///< angular frequency [rad/s], > 0, strictly increasing
  std::vector<double> modulus;    ///< |E*(omega)| [Pa], > 0
  std::vector<double> tan_delta;  ///< E''/E' >= 0
  std::string source;             ///< file name (for messages)
};

/// Parses the CSV text of a master curve (format: top of this header). `source` names it in
/// messages. Throws std::invalid_argument: "master curve 'F': row 7, column 2 (E_storage): ...".
master_curve parse_master_curve(std::string_view csv_text, const std::string& source);

/// Reads and parses a master-curve file (materials::read_text_file: a regular file of at most
/// max_text_file_bytes); an unreadable file or a path that is not a regular file is a
/// std::invalid_argument too.
master_curve read_master_curve(const std::string& path);

/// Williams-Landel-Ferry shift: log10 a_T = -C1 (T - T_ref) / (C2 + T - T_ref).
struct wlf_shift {
  double C1 = 0;     ///< dimensionless
  double C2 = 0;     ///< [K] (a temperature difference: degC or K alike)
  double T_ref = 0;  ///< reference temperature of the master curve (same unit as T)
};

/// log10 a_T; throws std::domain_error unless C2 + T - T_ref > 0 and all inputs are finite.
double wlf_log10_shift(const wlf_shift& wlf, double temperature);

/// The curve at `temperature`: every frequency divided by a_T (moduli unchanged).
master_curve shift_to_temperature(const master_curve& curve, const wlf_shift& wlf, double temperature);

struct fit_options {
  double half_window_decades = 0.5;  ///< the secant slope is taken over omega0 10^(-h) .. omega0 10^h
  double warning_threshold = 0.05;   ///< |alpha_slope - alpha_tan_delta| above it: "poor_power_law"
};

/// What the evidence of a local power-law fit says (the pattern of punch::status_code).
enum class fit_status {
  ok,              ///< the two estimates of alpha agree within fit_options::warning_threshold
  poor_power_law,  ///< they do not: the curve is not a power law over the window
  window_clipped,  ///< the window had to be clipped at an end of the measured range
  not_converged,   ///< a scene's fixed point omega0 = U/L did not converge (scene layer)
};

/// "ok", "poor_power_law", "window_clipped", "not_converged".
const char* to_string(fit_status status);

/// The local power law at omega0.
struct local_fit {
  double alpha = 0;            ///< = alpha_slope, in [0, 1)
  double E1 = 0;               ///< [Pa s^alpha]
  double omega0 = 0;           ///< [rad/s]
  double alpha_slope = 0;      ///< secant slope of ln|E*| over the window
  double alpha_tan_delta = 0;  ///< (2/pi) atan(tan delta(omega0))
  double modulus = 0;          ///< |E*(omega0)| [Pa]
  double window_lo = 0;        ///< frequency window actually used [rad/s]
  double window_hi = 0;
  fit_status status = fit_status::ok;  ///< ok, poor_power_law or window_clipped
  std::string warning;         ///< empty when ok, otherwise one line with the numbers
  bool ok() const { return status == fit_status::ok; }
};

/// Fits the local power law at omega0 (inside the curve's range). Throws std::domain_error for
/// omega0 outside the range, a slope outside [0, 1), or an E1 outside the double range (a curve
/// at extreme moduli and frequencies).
local_fit fit_at(const master_curve& curve, double omega0, const fit_options& options = {});

/// Result of the self-consistent fit omega0 = U / L.
struct fixed_point_fit {
  local_fit fit;                ///< at the converged omega0
  double contact_length = 0;    ///< L returned by the callback for the converged fit [m]
  std::size_t iterations = 0;   ///< callback evaluations
  bool converged = false;       ///< successive ln omega0 within tolerance
};

/// Iterates omega0 = speed / contact_length(fit_at(omega0)) to a fixed point (top of this header).
/// `contact_length` solves the contact with the given local fit and returns L > 0. Starts at
/// speed / initial_length if given, else at the geometric centre of the curve's range. Throws
/// std::domain_error if the fixed point lies outside the curve's range or L is not positive.
fixed_point_fit fit_fixed_point(const master_curve& curve, double speed,
                                const std::function<double(const local_fit&)>& contact_length,
                                const fit_options& options = {}, std::optional<double> initial_length = {},
                                double tolerance = 1e-10, std::size_t max_iterations = 60);

}  // namespace rhabel::materials
