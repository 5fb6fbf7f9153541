// Tests of rhabel::materials (master curve -> local power law). Oracles: curves generated here from
// closed forms (E* = E1 Gamma(1 - alpha) (i omega)^alpha, two spliced power laws), WLF values
// computed by hand, and a fixed point whose contact length is a closed form of (alpha, E1).
#include "rhabel/materials.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>
#include <string>

namespace {

using namespace rhabel::materials;

// The contract for a curve sampled from an exact power law (rounding of the CSV's
// 17-digit values and of log/exp over omega up to 1e10 stays two orders below it).
constexpr double exact_fit_tolerance = 1e-12;
// WLF: a handful of roundings in -C1 dT / (C2 + dT).
constexpr double wlf_tolerance = 8 * 2.220446049250313e-16;

std::string row(double a, double b, double c) {
  char buf[128];
  std::snprintf(buf, sizeof buf, "%.17g,%.17g,%.17g\n", a, b, c);
  return buf;
}

// Exact power-law master curve, omega = 10^(k/10) for k in [k0, k1], E' and E'' columns.
std::string power_law_csv(double alpha, double E1, int k0, int k1, bool hertz = false) {
  std::string text = "# exact power law\n";
  text += hertz ? "f_hz,E_storage,E_loss\n" : "omega,E_storage,E_loss\n";
  for (int k = k0; k <= k1; ++k) {
    const double omega = std::pow(10.0, k / 10.0);
    const double m = E1 * std::tgamma(1 - alpha) * std::pow(omega, alpha);
    const double phase = alpha * std::numbers::pi / 2;
    text += row(hertz ? omega / (2 * std::numbers::pi) : omega, m * std::cos(phase), m * std::sin(phase));
  }
  return text;
}

// Two power laws meeting at omega_k: |E*| = A omega^a1 below, continuous, exponent a2 above;
// tan delta = tan(a pi/2) of each branch (a knee, as a master curve with a sharp change of slope).
constexpr double knee_omega = 1e3, knee_a1 = 0.1, knee_a2 = 0.45, knee_A = 2e6;
double knee_modulus(double omega) {
  return omega <= knee_omega ? knee_A * std::pow(omega, knee_a1)
                             : knee_A * std::pow(knee_omega, knee_a1) * std::pow(omega / knee_omega, knee_a2);
}
std::string knee_csv() {
  std::string text = "omega,E_abs,tan_delta\n";
  for (int k = -30; k <= 90; ++k) {
    const double omega = std::pow(10.0, k / 10.0);
    const double a = omega <= knee_omega ? knee_a1 : knee_a2;
    text += row(omega, knee_modulus(omega), std::tan(a * std::numbers::pi / 2));
  }
  return text;
}

std::string error_of(const std::string& csv) {
  try {
    parse_master_curve(csv, "bad.csv");
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

TEST_CASE("exact power-law curve: alpha and E1 to 1e-12 anywhere in its range") {
  double worst_alpha = 0, worst_E1 = 0;  // reported with -s (the header's measured figures)
  for (const double alpha : {0.0, 0.05, 0.31, 0.5, 0.8}) {
    for (const bool hertz : {false, true}) {
      const double E1 = 2.7e6;
      const auto curve = parse_master_curve(power_law_csv(alpha, E1, -20, 100, hertz), "exact");
      for (const double omega0 : {0.05, 3.7, 3.7e4, 1e9}) {
        CAPTURE(alpha);
        CAPTURE(omega0);
        const auto f = fit_at(curve, omega0);
        CHECK(std::fabs(f.alpha - alpha) <= exact_fit_tolerance);
        CHECK(std::fabs(f.alpha_tan_delta - alpha) <= exact_fit_tolerance);
        CHECK(std::fabs(f.E1 / E1 - 1) <= exact_fit_tolerance);
        worst_alpha = std::max({worst_alpha, std::fabs(f.alpha - alpha), std::fabs(f.alpha_tan_delta - alpha)});
        worst_E1 = std::max(worst_E1, std::fabs(f.E1 / E1 - 1));
        CHECK(f.status == fit_status::ok);
        CHECK(f.window_lo == doctest::Approx(omega0 / std::sqrt(10.0)).epsilon(1e-13));
        CHECK(f.window_hi == doctest::Approx(omega0 * std::sqrt(10.0)).epsilon(1e-13));
      }
      // Next to the end of the range the window is clipped: still exact, but said so.
      const auto f = fit_at(curve, 5e9);
      CHECK(f.status == fit_status::window_clipped);
      CHECK(!f.warning.empty());
      CHECK(std::fabs(f.alpha - alpha) <= exact_fit_tolerance);
      CHECK(std::fabs(f.E1 / E1 - 1) <= exact_fit_tolerance);
    }
  }
  MESSAGE("exact power law, omega 0.01 .. 1e10: worst alpha error " << worst_alpha << ", worst relative E1 error "
                                                                    << worst_E1);
}

TEST_CASE("a knee (two power laws) is flagged next to it and fitted on its right side away from it") {
  const auto curve = parse_master_curve(knee_csv(), "knee");
  for (const double decades : {-0.3, -0.2, -0.1, 0.1, 0.25}) {  // the window straddles the knee
    CAPTURE(decades);
    const auto f = fit_at(curve, knee_omega * std::pow(10.0, decades));
    CHECK(f.status == fit_status::poor_power_law);
    CHECK(f.warning.find("power law is poor") != std::string::npos);
    CHECK(std::fabs(f.alpha_slope - f.alpha_tan_delta) > fit_options{}.warning_threshold);
  }
  for (const double decades : {0.7, 1.5, 3.0}) {  // right side, the window clear of the knee
    CAPTURE(decades);
    const double omega0 = knee_omega * std::pow(10.0, decades);
    const auto f = fit_at(curve, omega0);
    CHECK(f.status == fit_status::ok);
    CHECK(std::fabs(f.alpha - knee_a2) <= exact_fit_tolerance);
    // Right branch: |E*| = B omega^a2, B = A omega_k^(a1 - a2), so E1 = B / Gamma(1 - a2).
    const double E1 = knee_A * std::pow(knee_omega, knee_a1 - knee_a2) / std::tgamma(1 - knee_a2);
    CHECK(std::fabs(f.E1 / E1 - 1) <= exact_fit_tolerance);
  }
  const auto left = fit_at(curve, knee_omega * 1e-2);
  CHECK(left.status == fit_status::ok);
  CHECK(std::fabs(left.alpha - knee_a1) <= exact_fit_tolerance);
}

TEST_CASE("WLF shift against hand-computed values") {
  const wlf_shift wlf{8.86, 101.6, 20.0};
  // -8.86 * 20 / 121.6 = -177.2 / 121.6 and 177.2 / 81.6, by hand (long division).
  CHECK(std::fabs(wlf_log10_shift(wlf, 40.0) - -1.4572368421052631) <= wlf_tolerance * 1.46);
  CHECK(std::fabs(wlf_log10_shift(wlf, 0.0) - 2.1715686274509804) <= wlf_tolerance * 2.17);
  CHECK(wlf_log10_shift(wlf, 20.0) == 0.0);
  CHECK_THROWS_AS(wlf_log10_shift(wlf, 20.0 - 101.6), std::domain_error);
  CHECK_THROWS_AS(wlf_log10_shift(wlf, -100.0), std::domain_error);
  // The shifted curve: at 40 degC (a_T = 10^-1.457...) every frequency is multiplied by 10^1.457...
  const auto curve = parse_master_curve(power_law_csv(0.3, 1e6, 0, 40), "wlf");
  const auto hot = shift_to_temperature(curve, wlf, 40.0);
  for (std::size_t i = 0; i < curve.omega.size(); ++i) {
    CHECK(hot.omega[i] == doctest::Approx(curve.omega[i] * 28.657403727762718).epsilon(1e-14));  // 10^(177.2/121.6), 40 digits: 28.6574037277627182748988978
    CHECK(hot.modulus[i] == curve.modulus[i]);
  }
  // A power law at T: |E*(omega; T)| = |E*(omega a_T; T_ref)|, so E1(T) = E1 a_T^alpha.
  const auto f = fit_at(hot, 100.0);
  CHECK(std::fabs(f.E1 / (1e6 * std::pow(10.0, -1.4572368421052631 * 0.3)) - 1) <= exact_fit_tolerance);
}

TEST_CASE("bad curves: one-line errors naming row and column") {
  const std::string header = "omega,E_storage,E_loss\n";
  auto has = [](const std::string& message, const std::string& part) {
    CAPTURE(message);
    CHECK(message.find(part) != std::string::npos);
    CHECK(message.find('\n') == std::string::npos);
  };
  has(error_of(header + "1,1,0\n2,2,0\n"), "2 data row(s), at least 3");
  has(error_of(header + "1,1,0\n3,2,0\n2,3,0\n"), "row 4, column 1 (omega)");
  has(error_of(header + "1,1,0\n3,2,0\n2,3,0\n"), "increase strictly");
  has(error_of(header + "1,1,0\n2,-2,0\n3,3,0\n"), "row 3, column 2 (E_storage)");
  has(error_of(header + "1,1,0\n2,2,-1e3\n3,3,0\n"), "row 3, column 3 (E_loss)");
  has(error_of(header + "1,1,0\n2,2,nan\n3,3,0\n"), "row 3, column 3 (E_loss): 'nan' is not a finite number");
  has(error_of(header + "1,1,0\n2,2,0\n3,inf,0\n"), "row 4, column 2 (E_storage)");
  has(error_of(header + "1,1,0\n2,2x,0\n3,3,0\n"), "'2x' is not a number");
  has(error_of(header + "1,1,0\n2,2\n3,3,0\n"), "row 3: 2 column(s), expected 3");
  has(error_of("omega,E_store,E_loss\n1,1,0\n2,2,0\n3,3,0\n"), "row 1, column 2 ('E_store'): unknown column");
  has(error_of("freq,E_storage,E_loss\n1,1,0\n2,2,0\n3,3,0\n"), "row 1, column 1 ('freq'): unknown column");
  has(error_of("omega,E_storage,E_loss,T\n1,1,0,0\n"), "row 1, column 4 ('T'): unknown column");
  has(error_of("# only a comment\n"), "no header");
  has(error_of("omega,E_abs,tan_delta\n1,1,0\n2,2,-0.1\n3,3,0\n"), "row 3, column 3 (tan_delta)");
  has(error_of(header + "0,1,0\n2,2,0\n3,3,0\n"), "row 2, column 1 (omega): frequency 0 must be > 0");
  CHECK_THROWS_AS(read_master_curve("/nonexistent/curve.csv"), std::invalid_argument);
}

// Regression (issue 31): C's hexadecimal floats were read by strtod; a byte-order mark made the
// header an unknown column with an invisible character in the message.
TEST_CASE("hexadecimal numbers refused, a byte-order mark at the start skipped") {
  const std::string rows = "1,1,0.5\n10,2,1\n100,4,2\n";
  CHECK(error_of("omega,E_storage,E_loss\n1,1,0\n10,0x1p+23,0\n100,4,0\n")
            .find("row 3, column 2 (E_storage): '0x1p+23' is a hexadecimal number") != std::string::npos);
  const auto plain = parse_master_curve("omega,E_storage,E_loss\n" + rows, "plain");
  const auto bom = parse_master_curve("\xEF\xBB\xBFomega,E_storage,E_loss\n" + rows, "bom");
  CHECK(bom.omega == plain.omega);
  CHECK(bom.modulus == plain.modulus);
  // elsewhere it is an ordinary (unknown) byte
  CHECK(error_of("omega,\xEF\xBB\xBF" "E_storage,E_loss\n" + rows).find("unknown column") != std::string::npos);
}

// Regression (issue 31): a directory failed inside the stream library, /dev/zero was read until
// memory ran out, a FIFO without a writer blocked forever, a NUL in the name read another file.
TEST_CASE("read_text_file: only regular files, bounded") {
  auto refusal = [](const std::string& path, std::size_t limit = max_text_file_bytes) {
    try {
      (void)read_text_file(path, "master curve", limit);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("(accepted)");
  };
  CHECK(refusal("/tmp").find("cannot read master curve '/tmp': it is a directory") != std::string::npos);
  CHECK(refusal("/dev/zero").find("it is a device") != std::string::npos);
  CHECK(refusal(std::string("/etc/hostname\0junk", 18)).find("the name contains a NUL byte") != std::string::npos);
  CHECK(refusal("/nonexistent/curve.csv").find("No such file") != std::string::npos);
  const std::string file = "test_master_curve_bounded.csv";
  if (std::FILE* f = std::fopen(file.c_str(), "wb")) {
    std::fputs("omega,E_storage,E_loss\n", f);
    std::fclose(f);
    CHECK(refusal(file, 8).find("larger than the limit of 8 bytes") != std::string::npos);
    CHECK(read_text_file(file, "master curve") == "omega,E_storage,E_loss\n");
    std::remove(file.c_str());
  }
}

TEST_CASE("fit outside the range or with a slope outside [0, 1) is refused") {
  const auto curve = parse_master_curve(power_law_csv(0.3, 1e6, 0, 40), "range");
  CHECK_THROWS_AS(fit_at(curve, 0.5), std::domain_error);
  CHECK_THROWS_AS(fit_at(curve, 2e4), std::domain_error);
  const auto falling = parse_master_curve("omega,E_abs,tan_delta\n1,3,0\n10,2,0\n100,1,0\n", "falling");
  CHECK_THROWS_AS(fit_at(falling, 10.0), std::domain_error);
  // Regression (fuzz_master_curve): moduli near the top of the double range at frequencies near its
  // bottom give E1 = |E*| / (Gamma(1 - alpha) omega0^alpha) = inf; refused, not returned.
  const auto extreme = parse_master_curve(
      "omega,E_storage,E_loss\n1e-308,1e300,1e300\n1e-200,1e305,1e300\n1e-154,1e30,0\n", "extreme");
  CHECK_THROWS_AS(fit_at(extreme, std::sqrt(1e-308) * std::sqrt(1e-154)), std::domain_error);
}

TEST_CASE("fixed point omega0 = U / L(alpha, E1) against a closed-form contact length") {
  // L = (P / E_U)^(1/(1 - alpha)) with E_U = E1 Gamma(1 - alpha) U^alpha (a dimensionally consistent
  // stand-in for a contact length, which is all the iteration needs); on an exact power law the fit
  // does not depend on omega0, so the fixed point is omega0 = U / L in closed form.
  const double alpha = 0.3, E1 = 5e6, U = 0.01, P = 500.0;
  const auto curve = parse_master_curve(power_law_csv(alpha, E1, -40, 120), "exact");
  auto length = [&](const local_fit& f) {
    return std::pow(P / (f.E1 * std::tgamma(1 - f.alpha) * std::pow(U, f.alpha)), 1 / (1 - f.alpha));
  };
  const double L = std::pow(P / (E1 * std::tgamma(1 - alpha) * std::pow(U, alpha)), 1 / (1 - alpha));
  const auto r = fit_fixed_point(curve, U, length);
  CHECK(r.converged);
  CHECK(r.fit.omega0 == doctest::Approx(U / L).epsilon(1e-9));
  CHECK(r.contact_length == doctest::Approx(L).epsilon(1e-9));
  // On the knee curve the fixed point moves with the fit: check self-consistency only.
  const auto knee = parse_master_curve(knee_csv(), "knee");
  for (const double speed : {1e-4, 1e-2, 1.0}) {
    auto knee_length = [&](const local_fit& f) {
      return 1e-3 * std::pow(knee_modulus(1e3) / f.modulus, 1 / (2 - f.alpha));
    };
    const auto k = fit_fixed_point(knee, speed, knee_length);
    CAPTURE(speed);
    CHECK(k.converged);
    CHECK(std::fabs(std::log(k.fit.omega0 * k.contact_length / speed)) <= 1e-9);
  }
  // A fixed point beyond the measured range is an error, not an extrapolation.
  CHECK_THROWS_AS(fit_fixed_point(curve, 1e9, length), std::domain_error);
}

TEST_CASE("regression: fixed point at the lowest measured frequency (exp(ln omega) rounded below the range)") {
  // A sweep at 40 degC refused omega0 = 2.86574e-05 rad/s as "outside [2.86574e-05, ...]": the
  // iteration works in ln omega and exp(ln omega_min) can round below omega_min.
  double low = 0;
  for (int k = 0; k < 1000 && low == 0; ++k) {
    const double v = 2.8657403727762718e-5 * (1 + k * 1e-3);
    if (std::exp(std::log(v)) < v) low = v;
  }
  REQUIRE(low > 0);
  std::string text = "omega,E_abs,tan_delta\n" + row(low, 1e6, 0.5) + row(low * 10, 2e6, 0.5) + row(low * 100, 4e6, 0.5);
  const auto curve = parse_master_curve(text, "low end");
  const double speed = 1e-6;
  const auto r = fit_fixed_point(curve, speed, [&](const local_fit&) { return speed / low; }, {}, speed / low);
  CHECK(r.converged);
  CHECK(r.fit.omega0 == low);
  CHECK(r.fit.status == fit_status::window_clipped);
}
