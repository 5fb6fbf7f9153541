// punch/src/newton_krylov.hpp: one inexact Newton step without a Jacobian (Jacobian-free
// Newton-Krylov), internal to punch/src; used by the coupled solve's edge iteration
// (coupled_newton.cpp, krylov_step) and free of its contact rules.
//
// For F: R^m -> R^m with F(x) = r, the step dx of an inexact Newton method (Dembo, Eisenstat and
// Steihaug, SIAM J. Numer. Anal. 19 (1982) 400-408):
//   |r + F'(x) dx| <= rtol |r|   (2-norm),
// by GMRES right-preconditioned by an approximation P of F'(x) (abel/gmres.hpp), whose products
// are forward differences along the Krylov directions (Knoll and Keyes, J. Comput. Phys. 193
// (2004) 357-397):
//   F'(x) v ~ (F(x + h v) - r) / h,
//   h = min(relative_step / rms_k(|v_k| / scale_k), max_relative_step / max_k(|v_k| / scale_k)),
// i.e. the unknowns move by relative_step of their scales in the root mean square, none by more
// than max_relative_step (the edges: 1e-7 and 1e-5 of the contact's length, and 1e-5 for both
// once steps have stalled: coupled_newton.cpp, krylov_step_size and krylov_wide_step); with
// max_relative_step = relative_step, no unknown moves by more than relative_step. A forward move
// that F refuses (throws: a gap would close) is taken backward, -h.
// Accuracy: the difference error is O(h |F''| |v|^2) / |F'(x) v|, ~ the unknowns' relative move
// for F of unit curvature on their scales, plus F's own error over the move (F evaluated to an
// accuracy eps errs by ~ eps / h), so rtol far above both is met as stated; below them the step is
// as good as the differences. WHY the root mean square: an unknown whose scale is far below the
// others' (a contact 100 times shorter than most) would set h alone, and the others would move by
// so little that F's error swamps their differences (F's rounding in absolute abscissae: see
// coupled_newton.cpp, krylov_step_size). At most max_products + 1 evaluations of F (GMRES's last
// true residual); when they do not reach rtol, the iterate of least residual in the products'
// space (reached = false).
#pragma once

#include "rhabel/abel/gmres.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <exception>

namespace rhabel::punch::detail {

/// F(x + dx) = moved(dx); r = F(x); precondition(v) ~ F'(x)^-1 v; 0 < relative_step <=
/// max_relative_step. Returns dx (see the top).
template <class Moved, class Precondition>
Eigen::VectorXd newton_krylov_step(const Moved& moved, const Eigen::VectorXd& r, const Eigen::VectorXd& scale,
                                   const Precondition& precondition, double rtol, std::size_t max_products,
                                   double relative_step, double max_relative_step, bool* reached = nullptr) {
  const Eigen::Index m = r.size();
  auto difference = [&](const Eigen::VectorXd& v, double h) { return Eigen::VectorXd((moved(Eigen::VectorXd(h * v)) - r) / h); };
  auto apply = [&](const Eigen::VectorXd& v) -> Eigen::VectorXd {
    const Eigen::ArrayXd move = v.array() / scale.array();  // the relative moves per unit h
    const double largest = move.abs().maxCoeff();
    if (!(largest > 0)) return Eigen::VectorXd::Zero(m);
    const double rms = std::sqrt(move.square().mean());
    const double h = std::min(relative_step / rms, max_relative_step / largest);
    try {
      return difference(v, h);
    } catch (const std::exception&) {  // the forward move is refused: backward
      return difference(v, -h);
    }
  };
  Eigen::VectorXd dx = Eigen::VectorXd::Zero(m);
  // One restart cycle of max_products (the Krylov space of every product taken).
  const bool ok = abel::gmres(apply, precondition, Eigen::VectorXd(-r), dx, rtol, max_products, std::max<std::size_t>(max_products, 1));
  if (reached) *reached = ok;
  return dx;
}

}  // namespace rhabel::punch::detail
