// punch/src/panel_grid.hpp: the boundary-element discretisation of a sampled profile on one rigid
// body, and its active-set solve (internal to punch/src: used by coarse_contact.cpp, the first
// guess of the spectral search, and by profile_bem.cpp, the boundary-element solver).
//
// DISCRETISATION. The window [lo, lo + length] (finite: the samples' range; periodic: one period)
// mapped to [0, 1] and cut into n uniform panels of width h = 1/n; the density g piecewise
// constant, collocation at theta = 3/4 of each panel (the checkerboard mode then stays away from
// the odd part of Psi's null space at kappa = -1). The surface displacement at collocation point i
// of a unit density on panel j is Gamma(1 - alpha) int_panel Psi(t, x_i) dt (docs/theory.md
// section 7), Psi in closed form per panel, so the matrix depends on j - i only:
//   finite   a Toeplitz matrix (2n - 1 values);
//   periodic a circulant (n values): the panel and its images j lambda summed, the images |j| <= 4
//            in closed form, the rest by the Taylor series of Psi about j lambda summed over j with
//            Hurwitz zeta values (GSL), the divergent k = 1 sum by the zeta function's continuation
//            (docs/theory.md section 10: this drops the q = 0 mode, which only moves the rigid
//            level); constants independent of the collocation point are dropped for the same reason.
// With x = lo + length x', Psi(length d) = length^alpha Psi(d) + const, so the kernel is scaled by
// Gamma(1 - alpha) length^alpha and the density on [0, 1] is g' = length g (int g' dx' = P).
//
// THE ACTIVE SET (`settle`). Unknowns g on the active panels and the level D:
//     A g - D = z on the active panels,   >= D at the others,   g >= 0,   h sum g = P,
// each step's linear solve by active_solve.hpp (one LU, or GMRES with a two-level preconditioner,
// started from the last solve). Each step drops every panel with g < 0, and when none is negative
// adds every panel that penetrates (w - z < D by more than 1e-9 of the profile's span), until
// neither happens after a deciding solve (at most max_steps: a grid started from the last grid's
// set settles in a few; the first grid, started with every panel active, sheds the panels
// outside the contacts a few per step: measured ~130 steps for one contact of 1/30 of the window
// at alpha 0.7).
// Each step and each GMRES product checks solve_options::time_limit (time_limit_reached).
#pragma once

#include "internal.hpp"
#include "profile_curve.hpp"
#include "toeplitz_product.hpp"

#include <Eigen/Dense>

#include <cstddef>
#include <memory>
#include <utility>
#include <vector>

namespace rhabel::punch::detail {

/// Collocation point in each panel (see the top of the file).
constexpr double collocation_theta = 0.75;

/// One level of the discretisation.
struct panel_grid {
  std::size_t n = 0;
  double h = 0;
  bool periodic = false;
  double lo = 0, length = 0;   ///< the window [lo, lo + length] (periodic: one period)
  std::vector<double> kernel;  ///< A(i, j) = kernel[j - i + n - 1]: panel j at collocation point i
  std::vector<double> z;       ///< z - max z at the collocation points
  std::vector<double> rise;    ///< z(t1) - z(t0) over each panel (int z' exactly)
  std::unique_ptr<toeplitz_product> product;  ///< A by FFT
  double A(std::size_t i, std::size_t j) const { return kernel[j + n - 1 - i]; }
  /// Abscissa of the panel edge k (k = 0 .. n).
  double edge(std::size_t k) const { return lo + length * static_cast<double>(k) * h; }
};

/// The finite (Toeplitz) kernel of n panels over a window of the given length: A(i, j) =
/// out[j - i + n - 1] (see the top of the file); also coarse_bodies.cpp's.
std::vector<double> finite_panel_kernel(std::size_t n, double length, const context& cx);

/// The grid of n panels over the curve's window (periodic when curve.period() > 0); `top` = max z.
panel_grid make_panel_grid(const profile_curve& curve, std::size_t n, const context& cx, double top);

/// The periodic displacement / Gamma(1 - alpha) at sigma in [0, 1) of a unit density on [0, h] and
/// its images [j, j + h] (period 1), up to a constant independent of sigma (see the top of the
/// file). Exposed for the tests of the kernel (test_profile_bem.cpp).
class periodic_panel_kernel {
 public:
  periodic_panel_kernel(double alpha, double kappa, double one_minus_kappa_over_alpha);
  double operator()(double h, double sigma) const;
  /// The images' part of a unit POINT load at t seen at sigma, v = t - sigma in (-1, 1): the sum
  /// over j != 0 of Psi(v + j) (regularised as above, up to the same constant) and its
  /// derivative in v. Smooth on (-1, 1) (the nearest image, j = -+1, is singular at v = +-1):
  /// periodic_images.hpp adds it to a finite window's direct kernel.
  std::pair<double, double> images(double v) const;

 private:
  double alpha_, kappa_, c1_;
  std::vector<double> coef_;  ///< coef_[k]: the far images' coefficient of int (t - sigma)^k dt
};

struct warm_start;

/// Runs of consecutive indices in idx (sorted): [start, end) positions into idx.
std::vector<std::pair<Eigen::Index, Eigen::Index>> runs_of(const std::vector<std::size_t>& idx);

/// The active-set solve on one grid from `active` (see the top of the file): on success g (on the
/// active panels idx, in units of int g per unit x') and the level D; false when max_steps steps
/// do not settle it or a linear solve fails. `steps` accumulates the steps taken.
bool settle(panel_grid& gr, double load, double span, std::vector<char>& active, Eigen::VectorXd& g,
            std::vector<std::size_t>& idx, double& D, const context& cx, std::size_t& steps, std::size_t max_steps,
            warm_start& ws);

/// Steps of `settle` on the first grid (every panel active) and on a grid started from a coarser
/// one's set.
constexpr std::size_t first_grid_steps = 1000, refined_grid_steps = 60;

/// `active` of a grid of n panels carried to one of `next` panels (a panel is active where the
/// centre of its panel on the coarser grid was).
std::vector<char> refine_active(const std::vector<char>& active, std::size_t next);

}  // namespace rhabel::punch::detail
