// Tests of cauchy_transform (rhabel/quadrature/cauchy_transform.hpp) off the cut against the
// committed 40-digit table tests/data/cauchy_transform_reference.hpp (Boost tanh-sinh in
// cpp_bin_float_50, real and imaginary parts integrated separately,
// tools/reference/cauchy_abel_reference.cpp).
#include <doctest/doctest.h>

#include <rhabel/quadrature.hpp>

#include "data/cauchy_transform_reference.hpp"

#include <cmath>
#include <cstdlib>
#include <complex>
#include <limits>
#include <string>

namespace rq = rhabel::quadrature;
using cd = std::complex<double>;

namespace {

constexpr double eps = std::numeric_limits<double>::epsilon();

template <class Real>
Real h_poly(const Real& t) {
  return 1 - t / 2 + t * t / 3 + t * t * t * t * t * t * t;
}

}  // namespace

TEST_CASE("cauchy_transform: 40-digit table off the cut, z within 1e-12 of the cut and the ends") {
  constexpr double tolerance = 128 * eps;  // as for the principal value
  double worst = 0;
  int checked = 0;
  for (const auto& c : rhabel_test_data::cauchy_transform_cases) {
    const cd reference(std::strtod(c.re, nullptr), std::strtod(c.im, nullptr));
    const cd z(c.re_z, c.im_z);
    const cd value = c.h == 0 ? rq::cauchy_transform([](double t) { return h_poly(t); }, c.p, c.q, z).value
                              : rq::cauchy_transform([](double) { return 1.0; }, c.p, c.q, z).value;
    // Scale: |Phi| + w h near the closest point of the cut (Phi ~ w h / 2 there) + int w |h|.
    const double xr = std::min(1.0, std::max(-1.0, c.re_z));
    const double scale = std::abs(reference) + 3 * rq::jacobi_norm_squared(0, c.p, c.q) +
                         (xr > -1 && xr < 1 ? 3 * std::pow(1 - xr, c.p) * std::pow(1 + xr, c.q) : 0.0);
    const double error = std::abs(value - reference) / scale;
    worst = std::max(worst, error);
    INFO("h = " << c.h << " p = " << c.p << " q = " << c.q << " z = " << z << " value = " << value
                << " reference = " << reference);
    CHECK(error <= tolerance);
    ++checked;
  }
  CHECK(checked >= 40);
  MESSAGE("cauchy_transform worst relative error (double): " << worst / eps << " eps");
}

