// An independent boundary-element oracle for a SAMPLED rigid profile pressed with a total load
// (docs/theory.md section 9): finite window or periodic, the contact set unknown.
//
// SHARES NO CODE WITH RHABEL: this header includes only the C++ standard library, Eigen (dense LU),
// Boost.Math special functions (zeta, Bernoulli numbers) and the test suite's own boundary-element
// oracle bem_oracle.hpp (for its kernel Psi, its collocation point and its Richardson step). Its
// cubic splines are its own.
//
// WHAT IT COMPUTES. One rigid body whose lower surface is given by samples (x_i, z_i) (z in the sign
// convention of bem_oracle.hpp's f: towards the half-space; a parabola with vertex c is
// z = -(x - c)^2/(2R)) slides towards -x (a contact's leading edge is its lower end a) over the
// power-law half-space (alpha in [0, 1), beta in [0, 1), alpha + beta <= 1) and is pressed with the
// load P = int g (per period in periodic mode; pressure p = (pi/2) E_U g, `load_from_pressure`). The
// profile between samples is
//   (a) FINITE: the natural cubic spline of the samples on [x_0, x_n] (the window: the surface
//       points that can touch);
//   (b) PERIODIC with period lambda: the samples lie in [x_0, x_0 + lambda), the profile is the
//       periodic cubic spline closed by the knot (x_0 + lambda, z_0) and repeats.
// Unknowns: the density g >= 0 and ONE rigid approach delta. Conditions (bem_oracle.hpp's height
// formulation, same signs): u(s) + delta = z(s) on the contacts, u(s) + delta - z(s) >= 0 (the gap)
// elsewhere, int g = P (over one period), with u(s) = Gamma(1 - alpha) int g(t) Psi(t, s) dt and
// bem_oracle.hpp's Psi (u' is the slope operator of paper eq. (8) applied to g).
//
// THE PERIODIC KERNEL. u(s) of a periodic g is the image sum over t + j lambda, which diverges (Psi
// grows like d^alpha); its regularisation is the Fourier series without the q = 0 mode: for
// g = e^{iqt}, Gamma(1-alpha) H = Gamma(1-alpha) M(q) e^{iqs},
//     M(q) = Gamma(alpha) |q|^-alpha [e^{i pi alpha s/2} - kappa e^{-i pi alpha s/2}] / (i q),  s = sign q
// (alpha = 0: pi/|q| - i pi tan(beta pi/2)/q), and the mean pressure only moves delta. `periodic_panel`
// evaluates the periodic displacement of a unit-density panel [0, h] EXACTLY in real space: the
// panel and its images |j| <= 4 by bem_oracle.hpp's closed-form panel integrals, the images |j| >= 5
// by the Taylor series of Psi in (t - s)/(j lambda) summed over j in closed form (Hurwitz zeta
// values zeta(k - alpha, 5), k = 1 .. 30, by Euler-Maclaurin; the k = 1 term, divergent as a sum,
// by its continuation, which is what dropping q = 0 does: the slope then has zero mean over a
// period); constants independent of s are dropped (they only move delta). Verified in
// test_bem_profile_oracle.cpp against the Fourier multiplier above summed directly, against the
// alpha = beta = 0 closed form -log|2 sin(pi (t - s)/lambda)|, and its second differences against
// the brute-force image sum (which converges for them).
//
// DISCRETISATION (one level, `solve_level`). n uniform panels over the window (one period),
// piecewise-constant g, collocation at 3/4 of each panel (bem_oracle.hpp's `collocation_theta`: the
// checkerboard mode stays regular as kappa -> -1); the influence matrix is Toeplitz (finite) or
// circulant (periodic) and is tabulated once per level. Active set on panels: solve the active
// panels and delta (dense LU up to 600 active panels; above, GMRES right-preconditioned by the exact
// inverse of each patch's own block, for g = x1 - delta x2 with A x1 = z, A x2 = 1, delta from the
// load; its products dense, O(m^2), or with `options::fft_products` on a periodic level by FFT of
// the circulant, O(n log n): the same values to rounding, C_f per level measured equal to 12
// digits); the gaps at all inactive collocation points (one FFT convolution above 1000 active panels);
// grow every run of active panels into adjacent penetrating panels (up to a quarter of the run per
// side and iteration), seed each penetrating component that touches no run at its deepest panel;
// only when nothing grows drop every panel with g < 0. The first level starts from the highest
// panel, each finer level from the previous one's set (each panel split in two). Per level: the
// patches (runs of active panels; periodic runs may wrap), each with its load int g, its
// C_f = int z' g / int g (panel integrals of z' exact: z(t1) - z(t0)) and its edges: from the gap at
// the two nearest collocation points outside, gap ~ C d^(1 + e) at distance d from a smooth edge
// with the bounded exponent e of docs/theory.md section 3 (the run's end if that fails or moves it
// by more than a panel). Measured on the parabola (24 cases): within 0.6 of a panel; the run's end
// alone is off by up to 0.9.
//
// EXTRAPOLATION (`solve`). Levels n = n0 2^k, n0 = the samples' intervals doubled to >= 256 (panel
// ends on the knots of uniform samples: one cubic per panel), until the last three levels have the
// same patches (matched by overlap), every patch carrying >= 1e-4 of the load spans >= 16 panels on
// the finest, and the body's C_f bar is below 1e-4 x max |z'| (or at 2^18 panels: converged =
// false, the values and bars of the last three levels are still returned). Loads and C_f (per patch
// and of the body): bem_oracle.hpp's `richardson` on the last three levels (observed order; bar =
// the whole correction plus the last difference, or 4 x the largest difference when no order is
// observed), here never below the larger of the last two differences (on a fixed grid the values
// jitter with the grid's alignment, measured: the observed order's correction alone missed C_f's
// error by 15 % on the parabola at alpha 0.7). Edges: the finest level's, bar one panel (or the
// disagreement of the two finest plus a panel when that exceeds three panels). Contact fraction:
// the finest level's, bar the sum of the edge bars. A patch not found on all three levels gets
// bars its own size (edges: its width; load: itself; C_f: max |z'|). All bars are ESTIMATES, not
// bounds.
//
// NARROW PATCHES (`options::bound_narrow`, off by default). A rough profile under a heavy load has
// patches that carry >= 1e-4 of the load and stay narrower than 16 panels far into the levels
// (measured: self_affine(4000, 4) at P_phys 6e-3, 74 patches: at 256000 panels seven of them,
// 4 .. 14 panels, 1.6e-5 .. 5.5e-5 wide, 5e-5 .. 1e-3 of the load; five at 512000; one at
// 1024000), so the rule above does not settle on them below 2^20 panels. With the option such
// patches stand, and their worst case is added to the body's C_f bar (`narrow_share`):
//     sum_i (L_i r_i + dL_i R) / P,
// r_i the range of z' over the patch widened to its edges' bars, R that over the window, dL_i its
// load's bar plus |extrapolated - finest|. Why: C_i = int z' g / int g is a mean of z' weighted by
// g >= 0, on every level and exactly, so it lies in that range however coarsely the patch is
// resolved; a load error moves load from or to the other patches, at most R per unit of load.
// Refinement then stops when Richardson's bar plus this share is below friction_tol x max |z'|.
// The load bars are estimates, so the share is one too; it is conservative (in the case above the
// narrow patches' C_i moved by <= 2.8e-4 between the last levels against ranges r_i of 1e-3 ..
// 1e-2). Measured (test_rough_profile_reference.cpp: max_panels 2^20, bound_narrow, fft_products,
// friction_tol 1e-5; one core of a shared 2-core machine, Release;
// `ctest --test-dir build -R punch.test_rough_profile_reference -V`):
//     seed  patches  C_f                      narrow  their share  finest   time
//     4     74       0.0244682934 +- 1.24e-6  1       5.2e-7       1024000  60 s
//     15    86       0.0215062673 +- 1.16e-6  1       1.4e-7       1024000  62 s
//   (C_f's differences per level for seed 4: 4.1e-5, 1.5e-5, 3.1e-6, 7.2e-7, 2.3e-7 from 64000
//   panels on; with friction_tol 1e-4 it stops at 512000 panels, 24 s: 0.0244684187 +- 8.95e-6,
//   5.8e-6 of it the share of five narrow patches). rhabel's spectral search gives 0.0244683239
//   and 0.0215062617 (3.0e-8 and 5.6e-9 from these), its boundary-element solver 0.0244683204 +-
//   8.3e-8 and 0.0215062538 +- 9.3e-8. Evidence: min g / mean g (>= 0 by construction of the active set), min gap / (max z -
// min z) on the finest level, `touches_end` (finite: the contact reaches an end of the samples,
// where the profile is not known: the answer is that of the window, physically suspect), the
// patches and active-set iterations per level.
//
// USE FROM A TEST (the same samples the product gets):
//     namespace bp = punch_test::bem_profile;
//     const auto sc = bp::make_scene_physical(x, z, E1, alpha, nu, coulomb, speed, load, period);  // period 0: finite
//     const auto r = bp::solve(sc, bp::test_options());
//     // r.converged, r.patches[i].{a, b, load, friction} (estimate: value, error), r.friction (C_f of
//     // the body), r.fraction, r.mean_load (x (pi/2) E_U: mean pressure), r.min_density, r.min_gap,
//     // r.touches_end; loads are int g = 2 (physical load) / (pi E_U).
//   The self-test (test_bem_profile_oracle.cpp) runs in ~8 s in Release on a quiet core (16 s measured
//   on a loaded one), ~6 s under ASan + UBSan at -O1 (one case per loop, coarser self-affine case).
//
// MEASURED ACCURACY (Release; test_bem_profile_oracle.cpp):
//   * periodic kernel: against the Fourier multiplier summed to 2e5 modes 3e-12 .. 3e-15 (alpha > 0,
//     truncation of the series; 3e-10 at alpha 0), against the elastic closed form 1e-11, second
//     differences against the image sum 1e-13 of their size.
//   * Westergaard (alpha = beta = 0, 400 samples a period, default options: 400 .. 1600 panels):
//     half-width errors 5e-5 of the period, bars 6.3e-4 (c/lambda = 0.05, 0.2, 0.4; 0.01 .. 0.5 s);
//     C_f = 0 within 2e-8 (bars 3e-7 .. 6e-6).
//   * Hertz, finite (R = 1, L = 0.2, 201 samples on [-1, 1], 256 .. 8192 panels, 0.2 .. 0.5 s):
//     edges within 7e-4 L (bars one panel, 1.2e-3 L), C_f errors 1e-9 .. 1.3e-7 (bars 1.3e-7 ..
//     2.2e-6), alpha 0, 0.3, 0.7 and beta 0, 0.3. The bars overstate the C_f error 5-100x.
//   * a self-affine profile (the test's, 23 patches): the panel sequences 1000 x 2^k and
//     1024 x 2^k give C_f 0.0185539 +- 4.2e-6 and 0.0185562 +- 1.8e-6.
//   * a bump in periods 1 .. 16 against the isolated contact: C_f's difference shrinks by 0.61 per
//     doubling of the period (2^(alpha - 1) = 0.616 at alpha 0.3).
// MEASURED COST, self-affine profiles (studies/scenes/self_affine_profile.py 1000 SEED, H 0.8,
// rms 1e-3, alpha 0.3, nu 0, E1 = U = 1; load per unit length P_phys, `make_scene_physical`; one
// core of a shared 2-core machine; C_f with its bar; levels 1000 .. 2^k x 1000 panels):
//     seed P_phys  mode      patches  C_f                     finest   time   converged
//     1    5e-4    periodic  6        0.01323981 +- 3.8e-7   256000   1.9 s  yes
//     1    5e-4    finite    6        0.01340683 +- 4.3e-6   255744   1.9 s  yes
//     1    3e-3    periodic  20       0.01593743 +- 2.7e-6   128000   4.5 s  yes
//     1    3e-3    finite    22       0.01592835 +- 3.5e-6   255744    14 s  no (touches the end)
//     2    5e-4    periodic  5        0.01692331 +- 5.7e-6   128000   0.3 s  yes
//     2    5e-4    finite    4        0.01712275 +- 5.8e-6   127872   0.3 s  yes
//     2    3e-3    periodic  20       0.01851486 +- 2.5e-6   128000   3.2 s  yes
//     2    3e-3    finite    21-22    0.01089028 +- 5.6e-6   255744    14 s  no (touches the end; a
//                                                                          tiny patch comes and goes)
//     3    5e-4    periodic  3        0.01734355 +- 9.9e-7   256000   0.6 s  yes
//     3    5e-4    finite    3        0.01848605 +- 4.3e-6   127872   0.2 s  yes
//     3    3e-3    periodic  17       0.02115853 +- 1.8e-6   128000   2.3 s  yes
//     3    3e-3    finite    16       0.01851370 +- 8.6e-7   255744   8.4 s  yes (touches the end)
//   C_f converges roughly like h^2 from ~16 panels a sample spacing on (differences per level
//   2e-5, 6e-6, ...); on coarser levels it is off by up to 2e-3 (1000 panels). Where the stopping
//   rule once stopped early (seed 3, 5e-4, at 32000 panels, bar 1.9e-4) the error was 1.9e-5.
//   The cost is the active set's solves: dense LU (m^3) up to 600 active panels, then GMRES with
//   O(m^2) products: ~1 s a level at m ~ 3500. GMRES takes ~90 products a solve (two solves an
//   active-set iteration, ~3 iterations a level) on the 4000-sample profiles of NARROW PATCHES:
//   at 256000 panels (m ~ 6500) 23 s a level dense, 5 s with fft_products (an FFT pair of 256000
//   points: ~6 ms); at 1024000 (m ~ 26000) 36 s with them. Their first level (4000 panels, from
//   one panel) grows to ~2400 active panels before it shrinks to ~150: 10 .. 17 s dense, 2 .. 4 s
//   by FFT.
//
// LIMITS. alpha + beta <= 1. Smooth profiles (no corners). An active set started on a fine grid at
// kappa = -1 (alpha 0.7, beta 0.3) can settle on a spurious set (measured: the parabola from a single
// panel at 4096 panels); `solve` starts at the samples' spacing and refines, which avoids it in
// every case measured. Patches narrower than a panel of the finest level are not seen (nor, with
// bound_narrow, counted in the narrow share: a patch is counted once it is on the finest level).
#pragma once

#include "punch/bem_oracle.hpp"

#include <Eigen/Dense>
#include <unsupported/Eigen/FFT>
#include <boost/math/special_functions/bernoulli.hpp>
#include <boost/math/special_functions/gamma.hpp>
#include <boost/math/special_functions/zeta.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <complex>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace punch_test::bem_profile {

using bem::pi;
using bem::sanitizer_build;

[[noreturn]] inline void bad(const std::string& fn, const std::string& what) {
  throw std::domain_error("punch_test::bem_profile::" + fn + ": " + what);
}

// ---------------------------------------------------------------------------------------------
// Cubic splines (own implementation: natural, and periodic closed by (x0 + lambda, z0)).
struct spline {
  std::vector<double> x, z, m;  ///< knots (periodic: with the closing knot appended), second derivatives
  bool periodic = false;
  double period = 0;

  double lo() const { return x.front(); }
  double hi() const { return x.back(); }

  std::size_t interval(double& t) const {
    if (periodic) {
      t = t - period * std::floor((t - x.front()) / period);
      if (t >= x.back()) t = x.front();
    }
    const auto it = std::upper_bound(x.begin(), x.end(), t);
    std::size_t i = it == x.begin() ? 0 : static_cast<std::size_t>(it - x.begin()) - 1;
    return std::min(i, x.size() - 2);
  }
  /// z(t) (periodic: any t; finite: t in [x_0, x_n], extrapolated by the end cubic outside).
  double value(double t) const {
    const std::size_t i = interval(t);
    const double h = x[i + 1] - x[i], A = (x[i + 1] - t) / h, B = (t - x[i]) / h;
    return A * z[i] + B * z[i + 1] + ((A * A * A - A) * m[i] + (B * B * B - B) * m[i + 1]) * h * h / 6;
  }
  double slope(double t) const {
    const std::size_t i = interval(t);
    const double h = x[i + 1] - x[i], A = (x[i + 1] - t) / h, B = (t - x[i]) / h;
    return (z[i + 1] - z[i]) / h + (-(3 * A * A - 1) * m[i] + (3 * B * B - 1) * m[i + 1]) * h / 6;
  }
  /// {min z', max z'} on [t0, t1] (t0 <= t1; periodic: t1 - t0 <= period; finite: clipped to the
  /// knots). Exact: z'' is continuous and linear between knots, so z' is extreme at t0, t1 or
  /// where z'' changes sign inside a knot interval.
  std::pair<double, double> slope_range(double t0, double t1) const {
    if (!periodic) {
      t0 = std::clamp(t0, lo(), hi());
      t1 = std::clamp(t1, lo(), hi());
    }
    double lo_s = slope(t0), hi_s = lo_s;
    auto see = [&](double t) {
      const double s = slope(t);
      lo_s = std::min(lo_s, s);
      hi_s = std::max(hi_s, s);
    };
    see(t1);
    double t = t0;
    for (std::size_t k = 0; t < t1 && k < x.size() + 2; ++k) {
      double tm = t;
      const std::size_t i = interval(tm);        // tm: t brought into the knots' range
      const double end = t + (x[i + 1] - tm);    // this knot interval's end, in t's period
      if ((m[i] < 0) != (m[i + 1] < 0)) {        // z'' = 0 inside: an extremum of z'
        const double u = t + (x[i] + (x[i + 1] - x[i]) * m[i] / (m[i] - m[i + 1]) - tm);
        if (u > t0 && u < t1) see(u);
      }
      if (end < t1) see(end);
      if (!(end > t)) break;
      t = end;
    }
    return {lo_s, hi_s};
  }
};

/// The natural cubic spline of (x, z): x strictly increasing, at least 3 samples.
inline spline natural_spline(std::vector<double> x, std::vector<double> z) {
  const std::size_t n = x.size();
  if (n < 3 || z.size() != n) bad("natural_spline", "need >= 3 samples and z.size() == x.size()");
  for (std::size_t i = 0; i + 1 < n; ++i)
    if (!(x[i + 1] > x[i])) bad("natural_spline", "x must be strictly increasing (at index " + std::to_string(i) + ")");
  // Thomas algorithm for m_1 .. m_{n-2}.
  std::vector<double> a(n, 0), b(n, 1), c(n, 0), r(n, 0), m(n, 0);
  for (std::size_t i = 1; i + 1 < n; ++i) {
    const double h0 = x[i] - x[i - 1], h1 = x[i + 1] - x[i];
    a[i] = h0;
    b[i] = 2 * (h0 + h1);
    c[i] = h1;
    r[i] = 6 * ((z[i + 1] - z[i]) / h1 - (z[i] - z[i - 1]) / h0);
  }
  for (std::size_t i = 1; i < n; ++i) {
    const double w = a[i] / b[i - 1];
    b[i] -= w * c[i - 1];
    r[i] -= w * r[i - 1];
  }
  m[n - 1] = r[n - 1] / b[n - 1];
  for (std::size_t i = n - 1; i-- > 0;) m[i] = (r[i] - c[i] * m[i + 1]) / b[i];
  spline s;
  s.x = std::move(x);
  s.z = std::move(z);
  s.m = std::move(m);
  return s;
}

/// The periodic cubic spline of samples in [x_0, x_0 + lambda), closed by (x_0 + lambda, z_0).
inline spline periodic_spline(std::vector<double> x, std::vector<double> z, double lambda) {
  const std::size_t n = x.size();
  if (n < 3 || z.size() != n) bad("periodic_spline", "need >= 3 samples and z.size() == x.size()");
  if (!(lambda > 0) || !(x.back() < x.front() + lambda))
    bad("periodic_spline", "period = " + std::to_string(lambda) + ": the samples must lie in [x_0, x_0 + period)");
  for (std::size_t i = 0; i + 1 < n; ++i)
    if (!(x[i + 1] > x[i])) bad("periodic_spline", "x must be strictly increasing (at index " + std::to_string(i) + ")");
  auto H = [&](std::size_t i) { return i + 1 < n ? x[i + 1] - x[i] : x[0] + lambda - x[n - 1]; };  // interval i
  auto Z = [&](std::size_t i) { return z[i % n]; };
  // Cyclic tridiagonal: H(i-1) m_{i-1} + 2 (H(i-1) + H(i)) m_i + H(i) m_{i+1} = rhs_i (indices mod n),
  // by Sherman-Morrison on the Thomas algorithm.
  std::vector<double> a(n), b(n), c(n), r(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double h0 = H((i + n - 1) % n), h1 = H(i);
    a[i] = h0;
    b[i] = 2 * (h0 + h1);
    c[i] = h1;
    r[i] = 6 * ((Z(i + 1) - Z(i)) / h1 - (Z(i) - Z(i + n - 1)) / h0);
  }
  auto thomas = [&](std::vector<double> bb, std::vector<double> d) {
    std::vector<double> cc = c;
    for (std::size_t i = 1; i < n; ++i) {
      const double w = a[i] / bb[i - 1];
      bb[i] -= w * cc[i - 1];
      d[i] -= w * d[i - 1];
    }
    std::vector<double> y(n);
    y[n - 1] = d[n - 1] / bb[n - 1];
    for (std::size_t i = n - 1; i-- > 0;) y[i] = (d[i] - cc[i] * y[i + 1]) / bb[i];
    return y;
  };
  const double gamma = -b[0], alpha_c = c[n - 1], beta_c = a[0];  // corners A(n-1, 0), A(0, n-1)
  std::vector<double> bb = b;
  bb[0] -= gamma;
  bb[n - 1] -= alpha_c * beta_c / gamma;
  std::vector<double> u(n, 0);
  u[0] = gamma;
  u[n - 1] = alpha_c;
  const auto y = thomas(bb, r), q = thomas(bb, u);
  const double fact = (y[0] + beta_c * y[n - 1] / gamma) / (1 + q[0] + beta_c * q[n - 1] / gamma);
  std::vector<double> m(n + 1);
  for (std::size_t i = 0; i < n; ++i) m[i] = y[i] - fact * q[i];
  m[n] = m[0];
  spline s;
  s.x = std::move(x);
  s.x.push_back(s.x.front() + lambda);
  s.z = std::move(z);
  s.z.push_back(s.z.front());
  s.m = std::move(m);
  s.periodic = true;
  s.period = lambda;
  return s;
}

// ---------------------------------------------------------------------------------------------
// The periodic kernel.
namespace detail {

/// Hurwitz zeta zeta(s, a) for real s != 1, a >= 1 (analytic continuation for s < 1), by
/// Euler-Maclaurin after shifting a by 12; `alpha_times` returns (1 - s) zeta(s, a) instead, which
/// stays finite as s -> 1 (used for s = 1 - alpha: alpha zeta(1 - alpha, a)).
inline double hurwitz_zeta(double s, double a, bool alpha_times = false) {
  const int N = 12;
  const double one_minus_s = 1 - s;
  double sum = 0;
  for (int i = 0; i < N; ++i) sum += std::pow(a + i, -s);
  const double b = a + N;
  if (alpha_times) sum *= one_minus_s;
  // b^(1-s)/(s-1) [x (1 - s): -b^(1 - s)]
  double tail = alpha_times ? -std::pow(b, one_minus_s) : std::pow(b, one_minus_s) / (s - 1);
  double rest = std::pow(b, -s) / 2;
  double poch = s;  // (s)_(2k-1)
  double bpow = std::pow(b, -s - 1);
  double fact = 2;  // (2k)!
  for (int k = 1; k <= 10; ++k) {
    rest += boost::math::bernoulli_b2n<double>(k) / fact * poch * bpow;
    poch *= (s + 2 * k - 1) * (s + 2 * k);
    bpow /= b * b;
    fact *= (2 * k + 1) * (2 * k + 2);
  }
  if (alpha_times) rest *= one_minus_s;
  return sum + tail + rest;
}

}  // namespace detail

/// Periodic displacement kernel: u(sigma) / Gamma(1 - alpha) of a unit density on [0, h] and its
/// images [j lambda, j lambda + h], at sigma (any real; 0 < h < lambda), up to a constant
/// independent of sigma and h-proportional (the q = 0 mode; see the top of the file).
struct periodic_kernel {
  bem::kernel K;
  double lambda;
  static constexpr int near_images = 4, terms = 30;
  std::vector<double> coef;  ///< coef[k]: the tail's coefficient of int (t - sigma)^k dt

  periodic_kernel(double alpha, double beta, double lambda_) : K(alpha, beta), lambda(lambda_) {
    const double a0 = near_images + 1;
    coef.assign(terms + 1, 0);
    // Tail over j >= 5 of Psi(j lambda + u) + Psi(-(j lambda - u)) with u = t - sigma:
    //   -(1/alpha) sum_k binom(alpha, k) (1 + kappa (-1)^k) u^k (j lambda)^(alpha - k).
    // k = 1: -(1 - kappa) lambda^(alpha-1) zeta(1 - alpha, 5) = -c1 lambda^(alpha-1) [alpha zeta(1-alpha, 5)].
    coef[1] = -K.c1 * std::pow(lambda, alpha - 1) * detail::hurwitz_zeta(1 - alpha, a0, true);
    double bc = 1;  // (1/alpha) binom(alpha, k) = prod_{i=1}^{k-1} (alpha - i) / k!
    for (int k = 2; k <= terms; ++k) {
      bc *= (alpha - (k - 1)) / k;
      const double sgn = k % 2 == 0 ? 1.0 : -1.0;
      coef[static_cast<std::size_t>(k)] = -bc * (1 + K.kappa * sgn) * std::pow(lambda, alpha - k) * detail::hurwitz_zeta(k - alpha, a0);
    }
  }
  double operator()(double h, double sigma) const {
    sigma -= lambda * std::floor(sigma / lambda);  // [0, lambda)
    double s = 0;
    for (int j = -near_images; j <= near_images; ++j) s += K.panel(j * lambda, j * lambda + h, sigma);
    // int_0^h (t - sigma)^k dt = ((h - sigma)^(k+1) - (-sigma)^(k+1)) / (k+1)
    double p1 = (h - sigma), p0 = -sigma, tail = 0;
    for (int k = 1; k <= terms; ++k) {
      p1 *= (h - sigma);
      p0 *= -sigma;
      tail += coef[static_cast<std::size_t>(k)] * (p1 - p0) / (k + 1);
    }
    return s + tail;
  }
};

/// The same periodic displacement / Gamma(1 - alpha) by the Fourier series of the multiplier M(q),
/// modes 0 < |m| <= modes (for verification: the truncation error decays like modes^(-1 - alpha)).
inline double periodic_panel_fourier(double alpha, double beta, double lambda, double h, double sigma, long modes) {
  const bem::kernel K(alpha, beta);
  const std::complex<double> I(0, 1);
  const double ga = alpha == 0 ? 0 : boost::math::tgamma(alpha);
  double sum = 0;
  for (long m = 1; m <= modes; ++m)
    for (int sg : {1, -1}) {
      const double q = sg * 2 * pi * static_cast<double>(m) / lambda;
      std::complex<double> M;
      if (alpha == 0) M = pi / std::abs(q) - I * pi * std::tan(beta * pi / 2) / q;
      else M = ga * std::pow(std::abs(q), -alpha) * (std::exp(I * (pi * alpha * sg / 2)) - K.kappa * std::exp(-I * (pi * alpha * sg / 2))) / (I * q);
      const std::complex<double> ghat = (1.0 - std::exp(-I * q * h)) / (I * q) / lambda;
      sum += std::real(M * ghat * std::exp(I * q * sigma));
    }
  return sum;
}

// ---------------------------------------------------------------------------------------------
// Scene
struct scene {
  spline profile;        ///< natural (finite window) or periodic
  double alpha = 0, beta = 0;
  double load = 0;       ///< P = int g over the window / one period, > 0
};

/// p = (pi/2) E_U g: the load int g for a physical load per unit length (per period) and E_U.
inline double load_from_pressure(double physical_load, double E_U) { return 2 * physical_load / (pi * E_U); }
/// E_U = E1 Gamma(1 - alpha) U^alpha / (1 - nu^2) (docs/theory.md section 2).
inline double effective_modulus(double E1, double alpha, double nu, double speed) {
  return E1 * boost::math::tgamma(1 - alpha) * std::pow(speed, alpha) / (1 - nu * nu);
}

/// The scene the product gets from the same samples: natural spline (period <= 0) or periodic spline.
inline scene make_scene(std::vector<double> x, std::vector<double> z, double alpha, double beta, double load, double period = 0) {
  if (!(alpha >= 0 && alpha < 1)) bad("make_scene", "alpha = " + std::to_string(alpha) + " outside [0, 1)");
  if (!(beta >= 0 && beta < 1)) bad("make_scene", "beta = " + std::to_string(beta) + " outside [0, 1)");
  if (alpha + beta > 1 + 1e-12) bad("make_scene", "alpha + beta > 1 (kappa < -1) is outside the validated range");
  if (!(load > 0)) bad("make_scene", "load = " + std::to_string(load) + " must be > 0");
  scene sc;
  sc.profile = period > 0 ? periodic_spline(std::move(x), std::move(z), period) : natural_spline(std::move(x), std::move(z));
  sc.alpha = alpha;
  sc.beta = beta;
  sc.load = load;
  return sc;
}

/// tan(beta pi/2) = k (1 - 2 nu) / (2 (1 - nu)) (docs/theory.md section 1).
inline double friction_parameter(double coulomb, double nu) {
  return 2 / pi * std::atan(coulomb * (1 - 2 * nu) / (2 * (1 - nu)));
}

/// The scene of a product scene in physical units (material E1, alpha, nu, Coulomb k; speed U;
/// body.load per unit length, per period if period > 0): the same samples, beta from (k, nu) and
/// P = int g = 2 load / (pi E_U).
inline scene make_scene_physical(std::vector<double> x, std::vector<double> z, double E1, double alpha, double nu,
                                 double coulomb, double speed, double load, double period = 0) {
  return make_scene(std::move(x), std::move(z), alpha, friction_parameter(coulomb, nu),
                    load_from_pressure(load, effective_modulus(E1, alpha, nu, speed)), period);
}

/// Mean pressure of a result's scene in physical units: (pi/2) E_U P / window.
inline double mean_pressure(double mean_load, double E_U) { return pi / 2 * E_U * mean_load; }

// ---------------------------------------------------------------------------------------------
// One level.
struct patch_values {
  double a = 0, b = 0;       ///< run of active panels [t0 of its first, t1 of its last] (periodic: a may be < x0)
  double ea = 0, eb = 0;     ///< edges to a fraction of a panel (`edges`), or the run's ends
  double load = 0, moment = 0;  ///< int g, int z' g
  double friction() const { return moment / load; }
  int panels = 0;
};

struct level_result {
  int n = 0;                 ///< panels over the window / period
  double h = 0;
  std::vector<double> g;     ///< per panel (0 where inactive)
  std::vector<char> active;
  std::vector<double> gap;   ///< per panel at its collocation point (0 where active)
  double delta = 0;          ///< rigid approach (height convention of bem_oracle.hpp)
  std::vector<patch_values> patches;  ///< in order of a (periodic: the patch through x0 first if any)
  double friction = 0;       ///< int z' g / P
  double fraction = 0;       ///< active length / window
  double min_density = 0;    ///< min g / mean g over the active panels
  double min_gap = 0;        ///< min gap over inactive collocation points / (max z - min z)
  bool touches_end = false;  ///< finite: an end panel of the window is active (the data's end touches)
  int iterations = 0;
  bool converged = false;
};

namespace detail {

struct level_data {
  int n;
  double h, x0, W;
  bool periodic;
  std::vector<double> kern;  ///< kern[d + n - 1]: influence at offset d = i - j (periodic: of (i - j) mod n)
  std::vector<double> f, df;  ///< z at collocation points, z(t1) - z(t0)
  double coeff(int i, int j) const { return kern[static_cast<std::size_t>(i - j + n - 1)]; }
};

inline level_data make_level(const scene& sc, int n) {
  level_data L;
  L.n = n;
  L.periodic = sc.profile.periodic;
  L.x0 = sc.profile.lo();
  L.W = sc.profile.hi() - sc.profile.lo();
  L.h = L.W / n;
  const double th = bem::collocation_theta, g1 = boost::math::tgamma(1 - sc.alpha);
  if (L.periodic) {
    const periodic_kernel P(sc.alpha, sc.beta, L.W);
    std::vector<double> c(static_cast<std::size_t>(n));
    for (int d = 0; d < n; ++d) c[static_cast<std::size_t>(d)] = g1 * P(L.h, (d + th) * L.h);
    L.kern.resize(static_cast<std::size_t>(2 * n - 1));
    for (int d = -(n - 1); d <= n - 1; ++d) L.kern[static_cast<std::size_t>(d + n - 1)] = c[static_cast<std::size_t>((d + n) % n)];
  } else {
    const bem::kernel K(sc.alpha, sc.beta);
    L.kern.resize(static_cast<std::size_t>(2 * n - 1));
    for (int d = -(n - 1); d <= n - 1; ++d) L.kern[static_cast<std::size_t>(d + n - 1)] = g1 * K.panel(0, L.h, (d + th) * L.h);
  }
  L.f.resize(static_cast<std::size_t>(n));
  L.df.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    const double t0 = L.x0 + i * L.h, t1 = i + 1 == n ? L.x0 + L.W : L.x0 + (i + 1) * L.h;
    L.f[static_cast<std::size_t>(i)] = sc.profile.value(t0 + th * L.h);
    L.df[static_cast<std::size_t>(i)] = sc.profile.value(t1) - sc.profile.value(t0);
  }
  return L;
}

/// Runs of active panels as (first, length); periodic runs may wrap (first + length > n).
inline std::vector<std::pair<int, int>> runs(const std::vector<char>& act, bool periodic) {
  const int n = static_cast<int>(act.size());
  std::vector<std::pair<int, int>> r;
  int all = 0;
  for (char c : act) all += c;
  if (all == n) return {{0, n}};
  int start = 0;
  if (periodic) {  // begin at an inactive panel so that no run is cut
    while (act[static_cast<std::size_t>(start)]) ++start;
  }
  for (int k = 0; k < n;) {
    const int i = (start + k) % n;
    if (!act[static_cast<std::size_t>(i)]) { ++k; continue; }
    int len = 0;
    while (k + len < n && act[static_cast<std::size_t>((start + k + len) % n)]) ++len;
    r.emplace_back(i, len);
    k += len;
  }
  std::sort(r.begin(), r.end());
  return r;
}

/// The level's influence matrix times a density on all n panels, u_i = sum_j kern[i - j + n - 1]
/// g_j, by FFT with the kernel's transform computed once per level: a periodic level's matrix is
/// a circulant (c_d = kern[d + n - 1], d = 0 .. n - 1), a cyclic convolution of length n; a finite
/// level's is Toeplitz, a linear convolution padded to a power of 2 >= 3n. Eigen's FFT (any
/// length), exact up to rounding (~1e-16 x sum |kern g|). Used for the gaps above 4096 panels and,
/// with `options::fft_products`, for the periodic levels' GMRES products (O(n log n) instead of
/// the O(m^2) dense product over m active panels).
struct kernel_product {
  int n, N;
  mutable Eigen::FFT<double> fft;
  std::vector<std::complex<double>> k_hat;
  explicit kernel_product(const level_data& L) : n(L.n), N(L.n) {
    std::vector<double> k;
    if (L.periodic) {
      k.resize(static_cast<std::size_t>(n));
      for (int d = 0; d < n; ++d) k[static_cast<std::size_t>(d)] = L.kern[static_cast<std::size_t>(d + n - 1)];
    } else {
      N = 1;
      while (N < 3 * n) N *= 2;
      k.assign(static_cast<std::size_t>(N), 0.0);
      for (int d = -(n - 1); d <= n - 1; ++d) k[static_cast<std::size_t>((d + N) % N)] = L.kern[static_cast<std::size_t>(d + n - 1)];
    }
    fft.fwd(k_hat, k);
  }
  /// u for a density g on the n panels.
  std::vector<double> operator()(std::vector<double> g) const {
    g.resize(static_cast<std::size_t>(N), 0.0);
    std::vector<std::complex<double>> G;
    fft.fwd(G, g);
    for (std::size_t k = 0; k < G.size(); ++k) G[k] *= k_hat[k];
    std::vector<double> u;
    fft.inv(u, G);
    u.resize(static_cast<std::size_t>(n));
    return u;
  }
  /// (A x)_r = sum_c kern[idx_r - idx_c + n - 1] x_c over the active panels idx.
  Eigen::VectorXd apply(const std::vector<int>& idx, const Eigen::VectorXd& x) const {
    std::vector<double> g(static_cast<std::size_t>(n), 0.0);
    for (std::size_t r = 0; r < idx.size(); ++r) g[static_cast<std::size_t>(idx[r])] = x(static_cast<Eigen::Index>(r));
    const std::vector<double> u = (*this)(std::move(g));
    Eigen::VectorXd y(static_cast<Eigen::Index>(idx.size()));
    for (std::size_t r = 0; r < idx.size(); ++r) y(static_cast<Eigen::Index>(r)) = u[static_cast<std::size_t>(idx[r])];
    return y;
  }
};

/// Solve A x = b, A the active panels' influence matrix (idx), by GMRES (restarted every 60)
/// right-preconditioned with the exact inverse of each run's own block (block Jacobi: the runs
/// interact through smooth far fields). Relative residual 1e-13. Products by FFT when `C` is given
/// (kernel_product: periodic levels, `options::fft_products`), else dense.
struct block_solver {
  const level_data& L;
  const std::vector<int>& idx;
  const kernel_product* C = nullptr;
  std::vector<std::pair<int, int>> blocks;  // (offset in idx, size)
  std::vector<Eigen::PartialPivLU<Eigen::MatrixXd>> lu;
  block_solver(const level_data& L_, const std::vector<int>& idx_, const kernel_product* C_ = nullptr) : L(L_), idx(idx_), C(C_) {
    const int m = static_cast<int>(idx.size());
    for (int r = 0; r < m;) {
      int e = r + 1;
      while (e < m && (idx[static_cast<std::size_t>(e)] == idx[static_cast<std::size_t>(e - 1)] + 1)) ++e;
      blocks.emplace_back(r, e - r);
      r = e;
    }
    for (auto [o, len] : blocks) {
      Eigen::MatrixXd B(len, len);
      for (int i = 0; i < len; ++i)
        for (int j = 0; j < len; ++j) B(i, j) = L.coeff(idx[static_cast<std::size_t>(o + i)], idx[static_cast<std::size_t>(o + j)]);
      lu.emplace_back(B);
    }
  }
  Eigen::VectorXd apply(const Eigen::VectorXd& x) const {
    if (C) return C->apply(idx, x);
    const auto m = static_cast<Eigen::Index>(idx.size());
    Eigen::VectorXd y(m);
    for (Eigen::Index r = 0; r < m; ++r) {
      const double* k = L.kern.data() + (idx[static_cast<std::size_t>(r)] + L.n - 1);
      double acc = 0;
      for (Eigen::Index c = 0; c < m; ++c) acc += k[-idx[static_cast<std::size_t>(c)]] * x(c);
      y(r) = acc;
    }
    return y;
  }
  Eigen::VectorXd precondition(const Eigen::VectorXd& x) const {
    Eigen::VectorXd y(x.size());
    for (std::size_t b = 0; b < blocks.size(); ++b) {
      const auto [o, len] = blocks[b];
      y.segment(o, len) = lu[b].solve(x.segment(o, len));
    }
    return y;
  }
  Eigen::VectorXd solve(const Eigen::VectorXd& b, bool& ok) const {
    const Eigen::Index m = b.size();
    const int restart = 60, max_cycles = 40;
    Eigen::VectorXd x = Eigen::VectorXd::Zero(m);
    const double bn = b.norm();
    ok = true;
    if (bn == 0) return x;
    for (int cycle = 0; cycle < max_cycles; ++cycle) {
      Eigen::VectorXd r = b - apply(x);
      const double beta = r.norm();
      if (beta <= 1e-13 * bn) return x;
      Eigen::MatrixXd V(m, restart + 1), Hm = Eigen::MatrixXd::Zero(restart + 1, restart);
      V.col(0) = r / beta;
      Eigen::VectorXd gvec = Eigen::VectorXd::Zero(restart + 1);
      gvec(0) = beta;
      std::vector<double> cs(restart), sn(restart);
      int k = 0;
      for (; k < restart; ++k) {
        Eigen::VectorXd w = apply(precondition(V.col(k)));
        for (int i = 0; i <= k; ++i) {
          Hm(i, k) = V.col(i).dot(w);
          w -= Hm(i, k) * V.col(i);
        }
        Hm(k + 1, k) = w.norm();
        if (Hm(k + 1, k) > 0) V.col(k + 1) = w / Hm(k + 1, k);
        for (int i = 0; i < k; ++i) {
          const double t = cs[static_cast<std::size_t>(i)] * Hm(i, k) + sn[static_cast<std::size_t>(i)] * Hm(i + 1, k);
          Hm(i + 1, k) = -sn[static_cast<std::size_t>(i)] * Hm(i, k) + cs[static_cast<std::size_t>(i)] * Hm(i + 1, k);
          Hm(i, k) = t;
        }
        const double den = std::hypot(Hm(k, k), Hm(k + 1, k));
        cs[static_cast<std::size_t>(k)] = Hm(k, k) / den;
        sn[static_cast<std::size_t>(k)] = Hm(k + 1, k) / den;
        Hm(k, k) = den;
        Hm(k + 1, k) = 0;
        gvec(k + 1) = -sn[static_cast<std::size_t>(k)] * gvec(k);
        gvec(k) = cs[static_cast<std::size_t>(k)] * gvec(k);
        if (std::abs(gvec(k + 1)) <= 1e-13 * bn) { ++k; break; }
      }
      const Eigen::VectorXd yk = Hm.topLeftCorner(k, k).triangularView<Eigen::Upper>().solve(gvec.head(k));
      x += precondition(V.leftCols(k) * yk);
    }
    ok = (b - apply(x)).norm() <= 1e-10 * bn;
    return x;
  }
};

/// Panels above which the active system is solved by block-preconditioned GMRES instead of dense LU.
inline constexpr int dense_limit = 600;

}  // namespace detail

/// Active-set solve on n uniform panels, from `start` (per-panel activity; empty: the highest panel).
/// fft_products: periodic levels' GMRES products by FFT (`options::fft_products`).
inline level_result solve_level(const scene& sc, int n, std::vector<char> start = {}, int max_iterations = 400,
                                bool fft_products = false) {
  if (n < 8) bad("solve_level", "n = " + std::to_string(n) + " must be >= 8");
  const auto L = detail::make_level(sc, n);
  const bool per = L.periodic;
  // The FFT products (kernel_product), made when first needed.
  std::optional<detail::kernel_product> product;
  const auto fast = [&]() -> const detail::kernel_product& {
    if (!product) product.emplace(L);
    return *product;
  };
  double zmax = -std::numeric_limits<double>::infinity(), zmin = -zmax;
  for (double v : L.f) { zmax = std::max(zmax, v); zmin = std::min(zmin, v); }
  const double zscale = std::max(zmax - zmin, std::numeric_limits<double>::min());
  std::vector<char> act = std::move(start);
  if (act.size() != static_cast<std::size_t>(n)) {
    act.assign(static_cast<std::size_t>(n), 0);
    act[static_cast<std::size_t>(std::max_element(L.f.begin(), L.f.end()) - L.f.begin())] = 1;
  }
  level_result res;
  res.n = n;
  res.h = L.h;
  std::vector<double> g(static_cast<std::size_t>(n), 0.0), gap(static_cast<std::size_t>(n), 0.0);
  double delta = 0;
  auto nb = [&](int i, int d) -> int {  // neighbour index or -1
    const int k = i + d;
    if (per) return ((k % n) + n) % n;
    return k < 0 || k >= n ? -1 : k;
  };
  for (res.iterations = 1; res.iterations <= max_iterations; ++res.iterations) {
    std::vector<int> idx;
    for (int i = 0; i < n; ++i)
      if (act[static_cast<std::size_t>(i)]) idx.push_back(i);
    if (idx.empty()) bad("solve_level", "active set emptied");
    const auto m = static_cast<Eigen::Index>(idx.size());
    if (m > detail::dense_limit) {
      // g = x1 - delta x2 with A x1 = f, A x2 = 1; delta from the load.
      const detail::block_solver S(L, idx, fft_products && per ? &fast() : nullptr);
      Eigen::VectorXd f(m);
      for (Eigen::Index r = 0; r < m; ++r) f(r) = L.f[static_cast<std::size_t>(idx[static_cast<std::size_t>(r)])];
      bool ok1 = false, ok2 = false;
      const Eigen::VectorXd x1 = S.solve(f, ok1), x2 = S.solve(Eigen::VectorXd::Ones(m), ok2);
      if (!ok1 || !ok2) bad("solve_level", "GMRES did not converge on " + std::to_string(m) + " active panels");
      delta = (L.h * x1.sum() - sc.load) / (L.h * x2.sum());
      std::fill(g.begin(), g.end(), 0.0);
      for (Eigen::Index r = 0; r < m; ++r) g[static_cast<std::size_t>(idx[static_cast<std::size_t>(r)])] = x1(r) - delta * x2(r);
    } else {
    Eigen::MatrixXd A(m + 1, m + 1);
    Eigen::VectorXd rhs(m + 1);
    for (Eigen::Index r = 0; r < m; ++r) {
      for (Eigen::Index c = 0; c < m; ++c) A(r, c) = L.coeff(idx[static_cast<std::size_t>(r)], idx[static_cast<std::size_t>(c)]);
      A(r, m) = 1;
      A(m, r) = L.h;
      rhs(r) = L.f[static_cast<std::size_t>(idx[static_cast<std::size_t>(r)])];
    }
    A(m, m) = 0;
    rhs(m) = sc.load;
    const Eigen::VectorXd sol = A.partialPivLu().solve(rhs);
    std::fill(g.begin(), g.end(), 0.0);
    for (Eigen::Index r = 0; r < m; ++r) g[static_cast<std::size_t>(idx[static_cast<std::size_t>(r)])] = sol(r);
    delta = sol(m);
    }
    // Gaps at every inactive collocation point (the displacement by FFT convolution above 4096 panels).
    if (idx.size() > 1000 && n > 4096) {
      const std::vector<double> u = fast()(g);
      for (int i = 0; i < n; ++i)
        gap[static_cast<std::size_t>(i)] = act[static_cast<std::size_t>(i)] ? 0 : u[static_cast<std::size_t>(i)] + delta - L.f[static_cast<std::size_t>(i)];
    } else {
      for (int i = 0; i < n; ++i) {
        if (act[static_cast<std::size_t>(i)]) { gap[static_cast<std::size_t>(i)] = 0; continue; }
        double u = 0;
        for (int j : idx) u += L.coeff(i, j) * g[static_cast<std::size_t>(j)];
        gap[static_cast<std::size_t>(i)] = u + delta - L.f[static_cast<std::size_t>(i)];
      }
    }
    const double floor = -1e-12 * (zscale + std::abs(delta));
    auto pen = [&](int i) { return i >= 0 && !act[static_cast<std::size_t>(i)] && gap[static_cast<std::size_t>(i)] < floor; };
    std::vector<char> next = act;
    // Growth of every run into adjacent penetrating panels.
    for (auto [first, len] : detail::runs(act, per)) {
      const int step = std::max(1, len / 4);
      for (int k = 1, i = nb(first, -1); k <= step && pen(i); ++k, i = nb(i, -1)) next[static_cast<std::size_t>(i)] = 1;
      const int last = (first + len - 1) % n;
      for (int k = 1, i = nb(last, 1); k <= step && pen(i); ++k, i = nb(i, 1)) next[static_cast<std::size_t>(i)] = 1;
    }
    // Seeds: each penetrating component touching no run, at its deepest panel.
    {
      std::vector<char> seen(static_cast<std::size_t>(n), 0);
      for (int i0 = 0; i0 < n; ++i0) {
        if (seen[static_cast<std::size_t>(i0)] || !pen(i0)) continue;
        // component of penetrating panels containing i0
        int lo = i0, hi = i0, cnt = 1;
        while (cnt < n && pen(nb(lo, -1)) && nb(lo, -1) != hi) { lo = nb(lo, -1); ++cnt; }
        while (cnt < n && pen(nb(hi, 1)) && nb(hi, 1) != lo) { hi = nb(hi, 1); ++cnt; }
        bool touches = false;
        const int l1 = nb(lo, -1), h1 = nb(hi, 1);
        touches = (l1 >= 0 && act[static_cast<std::size_t>(l1)]) || (h1 >= 0 && act[static_cast<std::size_t>(h1)]);
        int worst = lo;
        for (int k = 0, i = lo; k < cnt; ++k, i = nb(i, 1)) {
          seen[static_cast<std::size_t>(i)] = 1;
          if (gap[static_cast<std::size_t>(i)] < gap[static_cast<std::size_t>(worst)]) worst = i;
        }
        if (!touches) next[static_cast<std::size_t>(worst)] = 1;
      }
    }
    if (next != act) { act = std::move(next); continue; }
    bool changed = false;
    for (int i : idx)
      if (g[static_cast<std::size_t>(i)] < 0) { act[static_cast<std::size_t>(i)] = 0; changed = true; }
    if (!changed) { res.converged = true; break; }
  }
  // Outputs.
  res.g = g;
  res.gap = gap;
  res.active = act;
  res.delta = delta;
  double gmin = std::numeric_limits<double>::infinity(), gsum = 0, moment = 0;
  int na = 0;
  res.min_gap = std::numeric_limits<double>::infinity();
  for (int i = 0; i < n; ++i) {
    const auto u = static_cast<std::size_t>(i);
    if (act[u]) {
      gmin = std::min(gmin, g[u]);
      gsum += g[u];
      moment += g[u] * L.df[u];
      ++na;
    } else {
      res.min_gap = std::min(res.min_gap, gap[u] / zscale);
    }
  }
  if (na == n) res.min_gap = 0;
  res.min_density = na ? gmin / (gsum / na) : 0;
  res.friction = moment / sc.load;
  res.fraction = static_cast<double>(na) / n;
  res.touches_end = !per && (act.front() || act.back());
  for (auto [first, len] : detail::runs(act, per)) {
    patch_values p;
    p.a = L.x0 + first * L.h;
    p.b = p.a + len * L.h;
    p.panels = len;
    for (int k = 0; k < len; ++k) {
      const auto u = static_cast<std::size_t>((first + k) % n);
      p.load += g[u] * L.h;
      p.moment += g[u] * L.df[u];
    }
    // Edges from the gap at the two nearest collocation points outside: gap ~ C d^(1 + e) at
    // distance d from a smooth edge with the bounded exponent e (docs/theory.md section 3).
    const double el = (3 - 2 * sc.alpha - sc.beta) / 2, et = (3 + sc.beta) / 2;
    auto edge = [&](int i1, int i2, double e, double fallback) {
      if (i1 < 0 || i2 < 0 || act[static_cast<std::size_t>(i1)] || act[static_cast<std::size_t>(i2)]) return fallback;
      const double g1 = gap[static_cast<std::size_t>(i1)], g2 = gap[static_cast<std::size_t>(i2)];
      if (!(g1 > 0 && g2 > g1)) return fallback;
      // collocation points relative to the fallback (the run's end), unwrapped
      const double dir = i2 == nb(i1, -1) ? -1 : 1;
      const double s1 = fallback + dir * (dir < 0 ? (1 - bem::collocation_theta) : bem::collocation_theta) * L.h;
      const double s2 = s1 + dir * L.h;
      const double r = std::pow(g2 / g1, 1 / e);  // (edge - s2) / (edge - s1)
      const double est = (s2 - r * s1) / (1 - r);
      return std::abs(est - fallback) <= L.h ? est : fallback;
    };
    const int last = (first + len - 1) % n;
    p.ea = edge(nb(first, -1), nb(nb(first, -1), -1), el, p.a);
    p.eb = edge(nb(last, 1), nb(nb(last, 1), 1), et, p.b);
    res.patches.push_back(p);
  }
  return res;
}

/// Edge of a patch from its estimates e0, e1, e2 on three levels (panel widths 4h, 2h, h): the
/// finest, bar h (measured |error| <= 0.6 h on the parabola, 24 cases; the run's end alone is off by
/// up to 0.9 h), or |e2 - e1| + h when the two finest disagree by more than their bars 3h.
inline bem::estimate edge_estimate(double e0, double e1, double e2, double h) {
  (void)e0;
  bem::estimate e;
  e.value = e.finest = e2;
  e.error = std::abs(e2 - e1) <= 3 * h ? h : std::abs(e2 - e1) + h;
  return e;
}

/// bem_oracle.hpp's Richardson step with a bar never below the larger of the last two differences
/// (on a fixed grid the values jitter with the grid's alignment: measured on the parabola, an
/// observed order's correction alone missed C_f's error by 15 %).
inline bem::estimate extrapolate(double q0, double q1, double q2, double scale) {
  auto e = bem::richardson(q0, q1, q2, scale);
  e.error = std::max(e.error, std::max(std::abs(q1 - q0), std::abs(q2 - q1)));
  return e;
}

// ---------------------------------------------------------------------------------------------
// Refinement and extrapolation.
struct options {
  int start_panels = 0;     ///< first level's panels over the window (0: the samples' intervals, doubled to >= 256)
  int min_levels = 3;       ///< at least this many levels (>= 3)
  int min_span = 16;        ///< every patch spans >= this many panels on the finest level
  int max_panels = 1 << 18; ///< refinement stops here (then converged = false unless already settled)
  double span_load = 1e-4;  ///< min_span applies to patches carrying at least this fraction of the load
  double friction_tol = 1e-4;  ///< refine until the body's C_f bar is below this x max |z'| of the samples
  /// Let patches narrower than min_span panels stand when their worst case, added to the body's C_f
  /// bar, keeps it below friction_tol (see `narrow_share`); off: every patch carrying >= span_load
  /// of the load must span min_span panels.
  bool bound_narrow = false;
  bool fft_products = false;  ///< periodic: GMRES products by FFT (`detail::kernel_product`), same values to rounding
};

/// Options for the sanitizer build: coarser (every check still runs, on fewer panels).
inline options test_options() {
  options o;
  if (bem::sanitizer_build) o.max_panels = 1 << 15;
  return o;
}

struct patch_estimate {
  bem::estimate a, b;          ///< edges (see `edge_estimate`)
  bem::estimate load, friction;
  std::vector<patch_values> levels;  ///< the matched patch on each of the last three levels
};

struct result {
  std::vector<patch_estimate> patches;  ///< of the finest level, in order of a
  bem::estimate friction;      ///< C_f of the body: int z' g / P (tangential over normal force per period)
  bem::estimate fraction;      ///< contact fraction (active length / window; finest level, bar from the edges' bars)
  double mean_load = 0;        ///< P / window (mean g; mean pressure = (pi/2) E_U mean_load), exact
  double min_density = 0;      ///< finest level: min g / mean g on the contacts (>= 0 by construction)
  double min_gap = 0;          ///< finest level: min gap / (max z - min z) off the contacts
  bool touches_end = false;    ///< finite: the finest level's contact reaches an end of the window
  bool converged = false;      ///< every level's active set converged, the last three have matching patches
  std::vector<int> panels;     ///< panels per level
  std::vector<int> patch_counts;  ///< patches per level
  std::vector<int> iterations;    ///< active-set iterations per level
  std::vector<double> level_friction;  ///< C_f of the body per level
  std::vector<double> level_seconds;   ///< wall time per level (reported, never asserted)
  double narrow_share = 0;     ///< bound_narrow: the narrow patches' share of friction.error (`narrow_share`)
  int narrow_patches = 0;      ///< bound_narrow: patches narrower than min_span panels on the finest level
  double seconds = 0;          ///< wall time (reported, never asserted)
  level_result finest;
};

namespace detail {

inline bool overlap(const patch_values& p, const patch_values& q, double W, bool periodic) {
  for (int s = periodic ? -1 : 0; s <= (periodic ? 1 : 0); ++s)
    if (p.a < q.b + s * W && q.a + s * W < p.b) return true;
  return false;
}

/// For each patch of `fine`, the index of the one patch of `coarse` overlapping it (-1: none or
/// not one-to-one).
inline std::vector<int> match(const level_result& coarse, const level_result& fine, double W, bool periodic) {
  std::vector<int> m(fine.patches.size(), -1);
  std::vector<int> used(coarse.patches.size(), 0);
  for (std::size_t i = 0; i < fine.patches.size(); ++i) {
    int hit = -1, cnt = 0;
    for (std::size_t j = 0; j < coarse.patches.size(); ++j)
      if (overlap(fine.patches[i], coarse.patches[j], W, periodic)) { hit = static_cast<int>(j); ++cnt; }
    if (cnt == 1) { m[i] = hit; ++used[static_cast<std::size_t>(hit)]; }
  }
  for (std::size_t i = 0; i < m.size(); ++i)
    if (m[i] >= 0 && used[static_cast<std::size_t>(m[i])] != 1) m[i] = -1;
  return m;
}

}  // namespace detail

/// The worst case that patches narrower than `min_span` panels on the finest level l2 add to the
/// body's C_f (`options::bound_narrow`), in C_f units, and how many there are:
///     sum over those patches i of (L_i r_i + dL_i R) / P.
/// WHY IT BOUNDS THEM. C_f = sum_j L_j C_j / P over the patches, and a patch's C_i = int z' g / int g
/// is a mean of z' with the weight g >= 0 (the exact solution's pressure, and every level's g by
/// the active set), so C_i, exact or on any level, lies in [min z', max z'] over the patch: r_i is
/// that range over the run widened to the edges' bars (`slope_range`, exact on the spline), so a
/// patch too narrow for its C_i to have converged still cannot be off by more than r_i (~ |z''| x
/// its width: small for the narrow ones). A wrong load dL_i moves to or from the other patches
/// (the total is P): at most dL_i R, R = the range of z' over the window. dL_i: the patch's load
/// bar plus |extrapolated - finest| (the finest level's error; `extrapolate`), its whole load when
/// it is not on all three levels. The loads' bars are estimates, so the sum is one too.
inline std::pair<double, int> narrow_share(const scene& sc, const level_result& l0, const level_result& l1,
                                           const level_result& l2, int min_span) {
  const bool per = sc.profile.periodic;
  const double W = sc.profile.hi() - sc.profile.lo();
  const auto [zmin, zmax] = sc.profile.slope_range(sc.profile.lo(), sc.profile.hi());
  const auto m1 = detail::match(l1, l2, W, per), m0 = detail::match(l0, l2, W, per);
  double share = 0;
  int count = 0;
  for (std::size_t i = 0; i < l2.patches.size(); ++i) {
    const auto& p = l2.patches[i];
    if (p.panels >= min_span) continue;
    ++count;
    double dL = p.load, bar_a = p.b - p.a + l2.h, bar_b = bar_a;
    if (m0[i] >= 0 && m1[i] >= 0) {
      const auto &p0 = l0.patches[static_cast<std::size_t>(m0[i])], &p1 = l1.patches[static_cast<std::size_t>(m1[i])];
      const auto e = extrapolate(p0.load, p1.load, p.load, sc.load);
      dL = e.error + std::abs(e.value - p.load);
      // the edges' bars (`edge_estimate`), periodic images brought next to p
      auto near = [&](double v) { return per ? v + W * std::round((p.a - v) / W) : v; };
      bar_a = edge_estimate(near(p0.ea), near(p1.ea), p.ea, l2.h).error;
      bar_b = edge_estimate(near(p0.eb), near(p1.eb), p.eb, l2.h).error;
    }
    const auto [smin, smax] = sc.profile.slope_range(std::min(p.a, p.ea) - bar_a, std::max(p.b, p.eb) + bar_b);
    share += (p.load * (smax - smin) + dL * (zmax - zmin)) / sc.load;
  }
  return {share, count};
}

/// The whole oracle: levels n = start * 2^k until the contact set is stable, Richardson on the last three.
inline result solve(const scene& sc, const options& opt = {}) {
  const auto t_start = std::chrono::steady_clock::now();
  if (opt.min_levels < 3) bad("solve", "min_levels must be >= 3");
  const bool per = sc.profile.periodic;
  const double W = sc.profile.hi() - sc.profile.lo();
  int n = opt.start_panels;
  if (n <= 0) {  // panel ends on the knots (uniform samples): the spline is one cubic per panel
    n = static_cast<int>(sc.profile.x.size()) - 1;
    while (n < 256) n *= 2;
  }
  result res;
  res.mean_load = sc.load / W;
  std::vector<level_result> lv;
  std::vector<char> start;
  double slope = 0;  // natural scale of C_f: the steepest slope at the samples
  for (std::size_t i = 0; i + 1 < sc.profile.x.size(); ++i)
    slope = std::max(slope, std::abs(sc.profile.slope(sc.profile.x[i])));
  bool settled = false;
  for (;; n *= 2) {
    const auto t_level = std::chrono::steady_clock::now();
    lv.push_back(solve_level(sc, n, start, 400, opt.fft_products));
    res.level_seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t_level).count());
    const auto& cur = lv.back();
    res.panels.push_back(n);
    res.patch_counts.push_back(static_cast<int>(cur.patches.size()));
    res.iterations.push_back(cur.iterations);
    res.level_friction.push_back(cur.friction);
    start.assign(static_cast<std::size_t>(2 * n), 0);
    for (int i = 0; i < n; ++i) start[static_cast<std::size_t>(2 * i)] = start[static_cast<std::size_t>(2 * i + 1)] = cur.active[static_cast<std::size_t>(i)];
    const std::size_t L = lv.size();
    if (L >= static_cast<std::size_t>(opt.min_levels)) {
      const auto &l0 = lv[L - 3], &l1 = lv[L - 2], &l2 = lv[L - 1];
      bool ok = l0.converged && l1.converged && l2.converged && l0.patches.size() == l2.patches.size() &&
                l1.patches.size() == l2.patches.size();
      if (ok) {
        const auto m1 = detail::match(l1, l2, W, per), m0 = detail::match(l0, l2, W, per);
        for (std::size_t i = 0; i < m1.size(); ++i) ok = ok && m1[i] >= 0 && m0[i] >= 0;
        double narrow = 0;
        if (opt.bound_narrow) narrow = narrow_share(sc, l0, l1, l2, opt.min_span).first;
        else
          for (const auto& p : l2.patches) ok = ok && (p.panels >= opt.min_span || p.load < opt.span_load * sc.load);
        ok = ok && extrapolate(l0.friction, l1.friction, l2.friction, slope).error + narrow <= opt.friction_tol * slope;
      }
      if (ok) { settled = true; break; }
    }
    if (2 * n > opt.max_panels) break;
  }
  const std::size_t L = lv.size();
  res.finest = lv.back();
  res.converged = settled;
  res.min_density = res.finest.min_density;
  res.min_gap = res.finest.min_gap;
  res.touches_end = res.finest.touches_end;
  if (L < 3) {
    bad("solve", "fewer than three levels below max_panels");
  }
  const auto &l0 = lv[L - 3], &l1 = lv[L - 2], &l2 = lv[L - 1];
  res.friction = extrapolate(l0.friction, l1.friction, l2.friction, slope);
  if (opt.bound_narrow) {
    std::tie(res.narrow_share, res.narrow_patches) = narrow_share(sc, l0, l1, l2, opt.min_span);
    res.friction.error += res.narrow_share;
  }
  const auto m1 = detail::match(l1, l2, W, per), m0 = detail::match(l0, l2, W, per);
  for (std::size_t i = 0; i < l2.patches.size(); ++i) {
    patch_estimate pe;
    const auto& p2 = l2.patches[i];
    if (m0[i] < 0 || m1[i] < 0) {  // not on every level: its existence is uncertain, bars to match
      pe.load = bem::estimate{p2.load, p2.load, 0, p2.load};
      pe.friction = bem::estimate{p2.friction(), slope, 0, p2.friction()};
      pe.a = bem::estimate{p2.ea, p2.b - p2.a + l2.h, 0, p2.ea};
      pe.b = bem::estimate{p2.eb, p2.b - p2.a + l2.h, 0, p2.eb};
      pe.levels = {p2};
      res.patches.push_back(pe);
      continue;
    }
    auto p0 = l0.patches[static_cast<std::size_t>(m0[i])], p1 = l1.patches[static_cast<std::size_t>(m1[i])];
    // periodic: bring the coarser patches to the same period image as p2
    for (auto* p : {&p0, &p1}) {
      const double shift = W * std::round(((p2.a + p2.b) - (p->a + p->b)) / (2 * W));
      p->a += shift;
      p->b += shift;
      p->ea += shift;
      p->eb += shift;
    }
    pe.levels = {p0, p1, p2};
    pe.load = extrapolate(p0.load, p1.load, p2.load, sc.load);
    pe.friction = extrapolate(p0.friction(), p1.friction(), p2.friction(), slope);
    pe.a = edge_estimate(p0.ea, p1.ea, p2.ea, l2.h);
    pe.b = edge_estimate(p0.eb, p1.eb, p2.eb, l2.h);
    res.patches.push_back(pe);
  }
  // Contact fraction: the finest level's, with the patches' edge bars (a run's length jumps with the
  // grid's alignment: not extrapolated).
  res.fraction = bem::estimate{l2.fraction, 0, 0, l2.fraction};
  for (const auto& pe : res.patches) res.fraction.error += (pe.a.error + pe.b.error) / W;
  res.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
  return res;
}

}  // namespace punch_test::bem_profile
