// libFuzzer target for the master-curve reader of rhabel::materials (tests/fuzz/README.md).
//
// Each input is the text of a master-curve CSV. parse_master_curve must either refuse it with a
// std::invalid_argument (the command line's exit code 2, one line naming row and column) or return
// a curve that keeps the reader's promises (rhabel/materials/master_curve.hpp): at least 3 rows,
// frequencies finite, > 0 and strictly increasing, |E*| finite and > 0, tan delta finite and
// >= 0. A curve that parses is then fitted at its geometric middle frequency (fit_at), which may
// refuse it with std::domain_error (no power law there) or std::invalid_argument. Anything else is
// a finding: a sanitizer report, another exception, a broken promise, or a fit with a non-finite
// alpha or E1.
#include "fuzz_support.hpp"

#include <rhabel/materials.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <stdexcept>
#include <string_view>

namespace {

[[noreturn]] void finding(const char* what, const char* message = "") {
  rhabel::fuzz::finding("fuzz_master_curve", what, message);
}

void check_curve(const rhabel::materials::master_curve& c) {
  if (c.omega.size() < 3 || c.modulus.size() != c.omega.size() || c.tan_delta.size() != c.omega.size()) {
    finding("a curve of fewer than 3 rows or of columns of different lengths");
  }
  for (std::size_t i = 0; i < c.omega.size(); ++i) {
    if (!(std::isfinite(c.omega[i]) && c.omega[i] > 0)) finding("a frequency not finite and > 0");
    if (i > 0 && !(c.omega[i] > c.omega[i - 1])) finding("frequencies not strictly increasing");
    if (!(std::isfinite(c.modulus[i]) && c.modulus[i] > 0)) finding("|E*| not finite and > 0");
    if (!(std::isfinite(c.tan_delta[i]) && c.tan_delta[i] >= 0)) finding("tan delta not finite and >= 0");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  rhabel::materials::master_curve curve;
  auto parse = [&] { curve = rhabel::materials::parse_master_curve(text, "fuzz.csv"); };
  if (!rhabel::fuzz::accepted<std::invalid_argument>("fuzz_master_curve", "parse_master_curve", parse)) {
    return 0;  // refused: exit code 2
  }
  check_curve(curve);
  const double middle = std::sqrt(curve.omega.front()) * std::sqrt(curve.omega.back());
  try {
    const auto fit = rhabel::materials::fit_at(curve, std::clamp(middle, curve.omega.front(), curve.omega.back()));
    if (!std::isfinite(fit.alpha) || !std::isfinite(fit.E1)) finding("a fit with a non-finite alpha or E1");
  } catch (const std::domain_error&) {
  } catch (const std::invalid_argument&) {
  } catch (const std::exception& e) {
    finding("fit_at threw something other than std::domain_error or std::invalid_argument", e.what());
  }
  return 0;
}
