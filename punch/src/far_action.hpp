// punch/src/far_action.hpp: sums over all contacts of int k(t - x) g_o(t) dt at single points x,
// in O(p log N) kernel values per point instead of one quadrature per contact, for scenes of many
// contacts (internal to punch/src: the report's residual of (8) and the surface displacement).
//
// The contacts' Jacobi series enter abel::far_field's treecode (far_field::at_point)
// through their moments (exact Gauss-Jacobi quadrature; the knots' terms by their composite rules,
// contact_density::kink_moments); every contact the tree finds near x, a
// contact with an apex enrichment (whose moments the series does not carry) and a line load are
// summed by the caller's own quadrature (`direct`). The far part is accurate to ~eps/100 of the
// kernel's size (p = 26; tests/abel/test_far_field.cpp), so the sums are those of the direct
// quadratures to rounding. With fewer than far_action::from contacts, or contacts that are not
// disjoint (a failed coupled solve's report), nothing is built and every contact is direct.
#pragma once

#include "internal.hpp"

#include "rhabel/abel.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <functional>
#include <memory>
#include <numeric>
#include <vector>

namespace rhabel::punch::detail {

class far_action {
 public:
  /// From this many contacts on the tree is built (below it the direct sums are cheap).
  static constexpr std::size_t from = 6;

  /// kernel(t - x) of the sum; st: the contacts (their densities g).
  far_action(const std::vector<indentor_state>& st, std::function<double(const double&)> kernel) : count_(st.size()) {
    if (st.size() < from) return;
    std::vector<std::size_t> order;
    for (std::size_t o = 0; o < st.size(); ++o)
      if (!st[o].g.line_load && st[o].g.length() > 0) order.push_back(o);
    std::sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) { return st[i].g.a() < st[j].g.a(); });
    std::vector<abel::far_field<double>::box> boxes;
    for (std::size_t k = 0; k < order.size(); ++k) {
      if (k > 0 && !(st[order[k]].g.a() > st[order[k - 1]].g.b())) return;  // not disjoint: all direct
      boxes.push_back({st[order[k]].g.a(), st[order[k]].g.b()});
    }
    if (boxes.size() < 2) return;
    field_ = std::make_unique<abel::far_field<double>>(std::move(kernel), boxes, 26, false);
    state_of_ = order;
    always_direct_.assign(st.size(), true);
    std::vector<Eigen::VectorXd> W;
    for (std::size_t k = 0; k < order.size(); ++k) {
      const auto& g = st[order[k]].g;
      const bool plain = !g.has_apex && !g.jacobi.coefficients.empty();
      always_direct_[order[k]] = !plain;
      W.push_back(plain ? field_->density_moments(k, g.jacobi) : Eigen::VectorXd::Zero(static_cast<Eigen::Index>(field_->order())));
      if (plain) W.back() += g.kink_moments(*field_);
    }
    moments_ = field_->upward(W);
  }

  /// sum over contacts o of direct(o) (the caller's quadrature of contact o at x, or 0 for a
  /// contact it leaves out), the far ones through the tree.
  template <class Direct>
  double sum(double x, Direct&& direct) const {
    double total = 0;
    if (!field_) {
      for (std::size_t o = 0; o < count_; ++o) total += direct(o);
      return total;
    }
    total = field_->at_point(moments_, x, [&](std::size_t leaf) {
      const std::size_t o = state_of_[leaf];
      return always_direct_[o] ? 0.0 : direct(o);
    });
    for (std::size_t o = 0; o < count_; ++o)
      if (always_direct_[o]) total += direct(o);
    return total;
  }

 private:
  std::size_t count_;
  std::unique_ptr<abel::far_field<double>> field_;
  std::vector<std::size_t> state_of_;  // leaf -> contact
  std::vector<bool> always_direct_;    // per contact: not in the tree's moments
  std::vector<Eigen::VectorXd> moments_;
};

}  // namespace rhabel::punch::detail
