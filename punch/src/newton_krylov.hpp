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
//   F'(x) v ~ (F(x + h v) - r) / h,   h = relative_step / max_k (|v_k| / scale_k),
// i.e. no unknown moves by more than relative_step of its scale (the edges: 1e-7 of the contact's
// length, 1e-5 once steps at 1e-7 have stalled: coupled_newton.cpp, krylov_wide_step). A forward
// move that F refuses (throws: a gap would close) is taken backward, -h.
// Accuracy: the difference error is O(h |F''| |v|^2) / |F'(x) v|, ~ relative_step for F of unit
// curvature on the unknowns' scales, plus F's own error over h (F evaluated to an accuracy eps
// errs by ~ eps / h), so rtol far above both is met as stated; below them the step is as good as
// the differences. At most max_products + 1 evaluations of F (GMRES's last true
// residual); when they do not reach rtol, the iterate of least residual in the products' space
// (reached = false).
#pragma once

#include "rhabel/abel/gmres.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cstddef>
#include <exception>

namespace rhabel::punch::detail {

/// F(x + dx) = moved(dx); r = F(x); precondition(v) ~ F'(x)^-1 v. Returns dx (see the top).
template <class Moved, class Precondition>
Eigen::VectorXd newton_krylov_step(const Moved& moved, const Eigen::VectorXd& r, const Eigen::VectorXd& scale,
                                   const Precondition& precondition, double rtol, std::size_t max_products,
                                   double relative_step, bool* reached = nullptr) {
  const Eigen::Index m = r.size();
  auto difference = [&](const Eigen::VectorXd& v, double h) { return Eigen::VectorXd((moved(Eigen::VectorXd(h * v)) - r) / h); };
  auto apply = [&](const Eigen::VectorXd& v) -> Eigen::VectorXd {
    const double largest = (v.array().abs() / scale.array()).maxCoeff();  // move per unit h
    if (!(largest > 0)) return Eigen::VectorXd::Zero(m);
    try {
      return difference(v, relative_step / largest);
    } catch (const std::exception&) {  // the forward move is refused: backward
      return difference(v, -relative_step / largest);
    }
  };
  Eigen::VectorXd dx = Eigen::VectorXd::Zero(m);
  // One restart cycle of max_products (the Krylov space of every product taken).
  const bool ok = abel::gmres(apply, precondition, Eigen::VectorXd(-r), dx, rtol, max_products, std::max<std::size_t>(max_products, 1));
  if (reached) *reached = ok;
  return dx;
}

}  // namespace rhabel::punch::detail
