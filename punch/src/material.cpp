// punch/src/material.cpp: the material (beta, kappa, E_U, the regime) and the solve context.
// See internal.hpp for the layout of punch/src.
#include "internal.hpp"

#include "rhabel/quadrature/gauss_jacobi.hpp"
#include "rhabel/quadrature/jacobi_polynomial.hpp"
#include "rhabel/riemann/abel_solver.hpp"

#include <Eigen/Dense>
#include <boost/math/constants/constants.hpp>
#include <boost/math/special_functions/beta.hpp>
#include <boost/math/special_functions/gamma.hpp>
#include <boost/math/tools/roots.hpp>
#include <boost/math/tools/minima.hpp>
#include <boost/math/quadrature/tanh_sinh.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace rhabel::punch::detail {
double material_beta(const material& m) {
  return 2 / pi * std::atan(m.coulomb * (1 - 2 * m.poisson) / (2 * (1 - m.poisson)));
}

// alpha + beta/2 - 1/2: the regime parameter.
double regime_offset(const material& m) { return m.alpha + material_beta(m) / 2 - 0.5; }

// kappa = cos((alpha + beta/2) pi)/cos(beta pi/2) = -sin(pi (alpha + beta/2 - 1/2))/cos(beta pi/2):
// the second form keeps full relative accuracy next to the boundary kappa = 0.
double material_kappa(const material& m) {
  const double off = regime_offset(m);
  if (std::abs(off) <= boundary_width) return 0;
  return -std::sin(pi * off) / std::cos(material_beta(m) * pi / 2);
}


// ---------------------------------------------------------------------------------------------
// The context of one solve: the material's derived constants and the options.

// The words name no C++ member: the limit is set as `--time-limit` (command line), `time_limit`
// (Python) or solve_options::time_limit, and each reader knows which one they set.
std::string context::time_limit_message() const {
  if (*interrupted) return "interrupted";
  std::ostringstream os;
  os << "stopped at the time limit of " << options.time_limit << " s";
  return os.str();
}

void context::check_time() const {
  poll_interrupt();
  if (out_of_time()) throw time_limit_reached(time_limit_message());
}

context make_context(const material& m, double speed, const solve_options& options) {
  context cx;
  // alpha below 1e-300 (down to the subnormal 5e-324, where the small-alpha forms divide by alpha)
  // is alpha = 0: the solution depends on alpha like alpha log(L), far below rounding there.
  cx.alpha = m.alpha < alpha_zero ? 0.0 : m.alpha;
  cx.beta = material_beta(m);
  cx.kappa = material_kappa(m);
  cx.offset = regime_offset(m);
  if (std::abs(cx.offset) <= boundary_width) cx.offset = 0;
  cx.gamma_factor = boost::math::tgamma(1 - cx.alpha);
  cx.pressure_scale = pi / 2 * m.effective_modulus(speed);
  cx.options = options;
  if (options.time_limit > 0)
    cx.deadline = std::chrono::steady_clock::now() +
                  std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(options.time_limit));
  cx.set_parameters();
  return cx;
}

}  // namespace rhabel::punch::detail

namespace rhabel::punch {

using namespace detail;

double material::beta() const { return material_beta(*this); }
double material::kappa() const { return material_kappa(*this); }
double material::effective_modulus(double speed) const {
  return E1 * boost::math::tgamma(1 - alpha) * std::pow(speed, alpha) / (1 - poisson * poisson);
}

const char* to_string(shape_kind shape) {
  switch (shape) {
    case shape_kind::parabolic: return "parabolic";
    case shape_kind::wedge: return "wedge";
    case shape_kind::flat: return "flat";
    case shape_kind::general: return "general";
  }
  return "unknown";
}

const char* to_string(status_code code) {
  switch (code) {
    case status_code::ok: return "ok";
    case status_code::not_converged: return "not_converged";
    case status_code::tension: return "tension";
    case status_code::load_mismatch: return "load_mismatch";
    case status_code::contacts_merge: return "contacts_merge";
    case status_code::penetration: return "penetration";
    case status_code::contact_lost: return "contact_lost";
  }
  return "unknown";
}

const char* to_string(regime_kind regime) {
  switch (regime) {
    case regime_kind::below: return "below";
    case regime_kind::boundary: return "boundary";
    case regime_kind::above: return "above";
  }
  return "unknown";
}

regime_kind regime(const material& m) {
  const double off = regime_offset(m);
  if (std::abs(off) <= boundary_width) return regime_kind::boundary;
  return off < 0 ? regime_kind::below : regime_kind::above;
}

}  // namespace rhabel::punch
