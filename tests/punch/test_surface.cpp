// The surface displacement of solved contacts (punch/src/surface.hpp, internal): the batched
// evaluation that the penetration check of a sampled profile uses (every point relative to its own
// reference contact, one pass over the contacts) against the same quantity point by point, by the
// direct quadrature of each contact's moment (height(i, x)). Three contacts of unequal lengths and
// loads at alpha 0.3 and 0; their densities are series of the bounded class with arbitrary
// coefficients (the evaluation does not need them solved).
#include <doctest/doctest.h>

#include "../punch/src/surface.hpp"
#include "rhabel/punch.hpp"

#include <boost/math/special_functions/gamma.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

namespace {
namespace d = rhabel::punch::detail;

// The batched moments are Chebyshev interpolants on graded panels, good to ~5e-16 of a panel's
// values (surface::moments), summed over three contacts with the datum subtracted: 64 eps of the
// largest height (measured 19 eps at alpha 0.3, 4 eps at 0).
constexpr double tolerance = 64 * std::numeric_limits<double>::epsilon();

d::context make_context(double alpha) {
  d::context cx;
  cx.alpha = alpha;
  cx.beta = 0;
  cx.kappa = rhabel::abel::abel_parameters<double>(alpha, 0.0).kappa();
  cx.set_parameters();
  cx.gamma_factor = boost::math::tgamma(1 - alpha);
  return cx;
}

/// A flat-faced state (its rigid profile plays no part off the contacts) on [a, b] with a series
/// of end exponents kappa and 1 - kappa (1 and 0 at alpha = 0; any above -1 will do here).
d::indentor_state state(double a, double b, const std::vector<double>& c, const d::context& cx) {
  d::indentor_state s;
  s.k = d::kind::flat;
  s.apex = (a + b) / 2;
  const double gam = cx.par.kappa(), del = 1 - cx.par.kappa();  // any exponents above -1
  s.g.jacobi = {a, b, gam, del, c};
  s.g.nu = 1;
  return s;
}
}  // namespace

TEST_CASE("surface::heights of points each relative to its own contact == height(reference, x) one by one") {
  for (const double alpha : {0.3, 0.0}) {
    CAPTURE(alpha);
    const d::context cx = make_context(alpha);
    const std::vector<d::indentor_state> st{state(0.10, 0.13, {1.0, -0.3, 0.1, 0.02}, cx),
                                            state(0.20, 0.21, {0.2, 0.05, -0.01}, cx),
                                            state(0.50, 0.62, {3.0, 0.4, -0.2, 0.1, 0.03}, cx)};
    const d::surface surface(st, cx);
    // Sorted points off the contacts, each referred to its nearest contact (as the check does).
    std::vector<double> xs;
    std::vector<std::size_t> reference;
    for (std::size_t k = 0; k < 400; ++k) {
      const double x = -0.2 + 1.2 * (double(k) + 0.5) / 400;
      std::size_t nearest = 0;
      double distance = 1e300;
      bool inside = false;
      for (std::size_t i = 0; i < st.size(); ++i) {
        const double a = st[i].g.a(), b = st[i].g.b();
        if (x >= a && x <= b) inside = true;
        const double dist = x < a ? a - x : x - b;
        if (dist < distance) distance = dist, nearest = i;
      }
      if (inside) continue;
      xs.push_back(x);
      reference.push_back(nearest);
    }
    const auto batched = surface.heights(xs, reference);
    double scale = 0, worst = 0;
    std::vector<std::size_t> seen(st.size(), 0);
    for (std::size_t k = 0; k < xs.size(); ++k) {
      const double direct = surface.height(reference[k], xs[k]);
      scale = std::max(scale, std::abs(direct));
      worst = std::max(worst, std::abs(batched[k] - direct));
      ++seen[reference[k]];
    }
    for (const std::size_t n : seen) CHECK(n > 20);  // every contact is some points' reference
    CHECK(worst <= tolerance * scale);
    // Relative to another contact, the heights differ by the difference of the two data.
    const auto from_first = surface.heights(0, xs);
    for (std::size_t k = 0; k < xs.size(); ++k) {
      const double shift = surface.height(0, xs[k]) - surface.height(reference[k], xs[k]);
      CHECK(std::abs((from_first[k] - batched[k]) - shift) <= tolerance * scale);
    }
  }
}
