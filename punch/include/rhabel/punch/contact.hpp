// rhabel/punch/contact.hpp: rigid indentors sliding over a power-law viscoelastic half-space.
//
// WHAT IS COMPUTED
//   Plane strain, steady sliding at speed U > 0 of one or several rigid 2-D indentors towards -x over
//   a half-space with relaxation modulus E(t) = E1 t^-alpha (alpha in [0, 1); alpha = 0 is the
//   elastic half-plane), Poisson ratio nu and Coulomb friction coefficient k. For every indentor the
//   solver returns its contact interval [a, b] (a = LEADING edge, b = trailing edge), the contact
//   pressure p, the hysteretic friction coefficient C_f, edge singularities and, on request, the
//   pressure and the surface displacement on a grid.
//
// THEORY (docs/theory.md, sections 1, 2, 4, 5)
//   tan(beta pi/2) = k (1 - 2 nu) / (2 (1 - nu)),   kappa = cos((alpha + beta/2) pi) / cos(beta pi/2).
//   With F(s) = f'(s)/Gamma(1 - alpha) (f: the indentor profile) the density g solves eq. (8)
//       F(s) = int_s^b g(t)(t - s)^(alpha-1) dt - kappa int_a^s g(t)(s - t)^(alpha-1) dt,  a < s < b,
//   (on the union of the contact intervals when there are several indentors: paper system 41), and
//       p(s) = (pi/2) E_U g(s),   E_U = E1 Gamma(1 - alpha) U^alpha / (1 - nu^2),
//       load per unit length  lambda = int p,   C_f = (1/lambda) int f'(s) p(s) ds   (paper 23),
//       total friction coefficient = C_f + k.
//   g is expanded in Jacobi polynomials times the exact edge weights (t-a)^gam (b-t)^del, which
//   diagonalises (8) (docs/theory.md section 4). The operator, its spectral relation, the density type and
//   the independent quadrature of (8) are rhabel::abel's (abel_parameters, abel_operator,
//   jacobi_density, solve_image_series, apply / apply_by_quadrature, and solve_step with its singular
//   enrichment for the wedge's apex); this layer adds the shapes, the projection of the forcing (steps
//   in closed form), the edge root finding, loads, friction, displacement and the coupling of
//   indentors. The edge exponents are
//       gam = (1 - 2 alpha - beta)/2 (smooth leading edge) or -(1 + 2 alpha + beta)/2 (corner),
//       del = (1 + beta)/2 (smooth trailing edge)          or (beta - 1)/2 (corner).
//   A smooth edge carries zero intensity factor; its position is fixed by the orthogonality
//   condition of docs/theory.md section 4 together with the load.
//
// REGIMES (scene_result::regime) with respect to alpha + beta/2 = 1/2:
//   "below"    alpha + beta/2 < 1/2 (kappa > 0): wedge contact wraps around the apex (a < 0 < b),
//              flat punch in full contact with singular edges.
//   "boundary" alpha + beta/2 = 1/2 within 1e-12 (kappa = 0): one-sided (elementary) Abel equation;
//              an indentor is acted on only by indentors at larger x (behind it: t > s in (8)); wedge
//              and flat punch behave as "above".
//   "above"    alpha + beta/2 > 1/2 (kappa < 0): wedge contact ends at the apex, flat punch contact
//              collapses to a moving line load at its leading corner (paper 24-25).
//
// METHOD AND ACCURACY (measured; commands: build/tests/punch_test_contact,
//   build/tests/punch_test_wedge, build/bin/study_scene_timing, build/bin/study_wedge_near_edge,
//   build/bin/study_wedge_table, build/bin/study_wedge_stationarity)
//   * Parabola, general smooth profile: the forcing is smooth, the Jacobi degree is chosen adaptively
//     by abel::solve (Chebyshev tail below options.tolerance; with corners: projection with the
//     jumps in closed form); the edges come from a TOMS 748 root of the orthogonality coefficient
//     d_0 nested in a secant iteration on log L. Against the
//     closed forms (alpha in {0, 0.2, 0.45, 0.7}, k in {0, 0.5, 2}): L, b, C_f, load and pressure to
//     a few 1e-15 relative; independent residual of (8) <= 6e-14.
//   * Wedge, alpha + beta/2 >= 1/2: closed-form structure (nu = 0, b = apex), L and pressure to 1e-14.
//   * Wedge below the boundary: eps = (apex - a)/L by Boost's ibeta_inv (and 1 - eps from the
//     complementary inversion, so both are accurate at slope ratios 1e-6 .. 1e6); L from the load in
//     closed form, load = E_U cos(beta pi/2) (S1 + S2) eps^del (1 - eps)^gam L^(1-alpha) / (2 Gamma(2 - alpha))
//     (the moment formula of the Riemann-Hilbert route with the eps condition substituted: no
//     cancellation; 1e-15 relative at slope ratios 1e-6 .. 1e6 against a 50-digit evaluation).
//     The density has a |s - apex|^-alpha (log at alpha = 0) singularity at the apex: it is built in
//     by abel::solve_step (g = C phi + w sum c_n P_n, C from the jump in closed form, the remainder by
//     adaptive Chebyshev interpolation on 65, 195, 585 points, at most max(2 max_degree + 1, 585)),
//     then c_0 is set to the exact load. An isolated wedge with the apex within L/4 of an edge (eps
//     outside [1/4, 3/4]: slope ratios beyond ~2.4, or alpha + beta/2 near 1/2; eps = 0.907 for
//     alpha = 0.3, S1 = S2) is split (punch/src/contact.cpp, build_wedge_near_edge): the long
//     side's constant of F in closed form (class nu = 0, singular at the near edge) plus the rest,
//     which vanishes on the long side, by solve_step with the apex mapped to the centre
//     (abel::apex_placement::centred); the singular parts cancel (the orthogonality condition) and
//     the load is matched by scaling the whole density. 66 points from L/4 down to 1e-14 L. C_f =
//     (S1 int_a^apex g - S2 int_apex^b g)/int g with the smaller share integrated directly.
//     error_estimate = max(Chebyshev tail, relative load defect of the density before the load is
//     corrected): an estimate. Measured against the Riemann-Hilbert route (riemann::solve_abel_rh at
//     order 24: C_f and the pointwise density; tests/punch/test_wedge.cpp,
//     build/bin/study_wedge_near_edge, build/bin/study_scene_timing; tolerance 1e-10): eps 0.84 ..
//     0.99999 and 0.01, alpha 0.1 .. 0.3: C_f <= 1.6e-14, the 1000 pressure samples <= 2.4e-14 of
//     the peak; elastic frictionless wedge at eps 0.972 .. 0.99999 against its closed form: pressure
//     <= 1.1e-14, C_f <= 8.4e-16, and to 1 - eps = 2.5e-12 (tests): pressure <= 3.4e-11; the 50
//     cases of study_scene_timing with 1 - eps >= 1e-14: C_f <= 8.0e-13 and pressure <= 4.1e-12 at
//     slope ratios 0.1 .. 10 (the split ones: 1.3e-13, 9.9e-13), within 1.8e-9 of an order-16
//     reference that is itself good to ~1e-10
//     at 1e-6 and 1e6 (README.md). Within 1e-14 L of the trailing edge the contact is solved as
//     ending at the apex (C_f from the Riemann-Hilbert route while 1 - eps > 1e-30, else S1). With
//     solve_options::wedge_apex_split off the isolated wedge takes C_f and the pressure samples
//     from the Riemann-Hilbert route (order 16 on the unit interval, samples from a piecewise
//     Chebyshev interpolant; the status says so) and the plain Jacobi series the rest.
//     A coupled wedge (other indentors present): see "Several indentors".
//   * Flat punch below the boundary: nu = +1, spectral, 1e-15; above/on the boundary a line load.
//   * Several indentors (paper system 41; punch/src/coupled_solve.cpp, docs/theory.md section 7):
//     for given edges ONE linear solve on the union of the contact intervals: a particular solution
//     of every contact alone with its own data (the single-contact builders above: spectral, the
//     wedge's apex enrichment or, apex within L/4 of an edge, its split form; a flat face carries
//     its load as the homogeneous solution), plus the coupling correction with the smooth data
//     -sum_{i != j} A p_i by abel::solve_union (collocation in the contacts' Jacobi bases, cross
//     blocks by graded quadrature, a pair at least a half-length apart by one Gauss-Jacobi panel
//     of n/2 + ~20 nodes; from 6 contacts on the collocation system by GMRES with the
//     block-diagonal preconditioner instead of LU, separated contacts through the far field;
//     degree raised until its independent residual is
//     within the tolerance relative to the original data). The edges: Newton's method on ALL edge conditions
//     at once (d_j = 0, or a vanishing near-edge intensity for a split wedge, and int g_j = P_j),
//     forward-difference Jacobian at the base point's degree (banded by Curtis-Powell-Reid colouring
//     above 5 contacts) then Broyden updates, steps limited to keep every contact at least half and
//     every gap at least a fifth of its size. Above 5 contacts, parabolas and general profiles
//     without corners below the boundary are iterated with their loads imposed (the class singular at both edges,
//     conditions: both intensity factors vanish; then re-solved in the bounded class), which
//     keeps the banded Jacobian of many contacts accurate. Started from the isolated contacts, or, when those
//     overlap (or Newton from them fails), by continuation in the load (all loads times t, contacts shrinking
//     about their apexes, t raised to 1); up to 16 independent parabolas, when both fail, from a coarse boundary-element solve of all of them at once (each indentor its own
//     level and load, no path in the load: docs/theory.md section 7), and independent indentors of
//     unequal loads, when that fails too, by continuation in the loads' ratio (every load equal to
//     the largest, then each brought to its own: a light contact on the surface a heavy one shaped).
//     The contacts' order along x is found, not assumed (above
//     alpha = 1/2 a blunt indentor's contact can lie ahead of a sharper one's). A gap below
//     1e-6 of the smaller contact that a step keeps closing ends the iteration: contacts_merge
//     when the step closes it, not_converged otherwise (gaps below 3e-3 L are solved with poles
//     beyond the facing ends, solve_options::layered_below; the reported densities are their
//     projections onto Jacobi series, whose measured error is in error_estimate, and the residual
//     of (8) is that of the densities as solved). Measured: the alpha = 1/2 semi-closed
//     two-parabola solution (trailing contact independent; tests/punch/test_coupled.cpp) to 1e-9 L
//     at gaps 1, 0.1, 0.01 L; the boundary-element oracle of tests/punch/bem_oracle.hpp (its own
//     error ~1e-5 L) within twice its error bar for two parabolas at alpha 0, 0.25, 0.7, beta 0,
//     0.3, two of loads 100 : 1 at alpha 0.4, three at alpha 0.6 whose contacts lie in another
//     order than their apexes, and for parabola-wedge-parabola and flat-flat-parabola rows (test_coupled_bem.cpp);
//     mirror symmetry of identical elastic frictionless indentors to 1e-9, and to 1e-10 L at gaps
//     of ~8e-6 and ~3e-6 L; the coupling decaying
//     like distance^(alpha - 1); the rigid approaches (indentor_result::approach) against the
//     oracle's. Cost: see "Cost" below.
//   * Rigid body (scene::body): the loads are unknowns; each contact's load condition is replaced
//     by the total load (one contact) or equal levels approach + height (the others), solved by
//     the same Newton iteration (up to five contacts the full Jacobian; from six, coloured with
//     the far entries from each load's monopole, the full one if that fails), from an equal
//     split of the load, with a continuation in the height differences when that fails. The
//     differenced columns run on solve_options::threads threads. Against the boundary-element
//     oracle (one_body mode): the loads' split, edges, C_f and the approach within twice its
//     error bar (test_coupled_bem.cpp). An indentor lifted off by the others is reported as
//     status_code::contact_lost (it is not removed from the scene); flat punches on a body are
//     refused (their load would be an unknown without an edge).
//   * residual (computed unless solve_options::residual is false; NaN then): max over check points
//     of |A g - F| relative to the data's scale (max |F| there, and mean(g) (L/2)^alpha, the size of
//     the density's own action, which is all a flat face has), with the two one-sided integrals
//     computed by abel_operator::apply_by_quadrature (Gauss-Jacobi with the kernel singularity as
//     weight, independent of the spectral relation; uniform down to alpha = 0), the apex enrichment
//     by abel's direct quadrature of A[phi] (the one solve_step used to build the data: for that part
//     only the smooth remainder is checked), the other indentors by abel_operator::apply / abel::apply
//     (graded quadrature, not the coupled solve's cross nodes). Check points: 7 interior points and,
//     facing a neighbour at distance gap, points 0.37 gap 3^k from that end (the boundary layer).
//     Measured: <= 7e-13 for single indentors at alpha in {0, 1e-8, 5e-4} (tests/punch/
//     test_contact.cpp); ~3e-14 for examples/default_scene.json (coupled wedge + parabola).
//   * STATUS (status_code; the command line exits 3 on anything but ok): a contact is ok only when
//     its residual and error estimate are within solve_options::acceptance (1e-9), its density is
//     >= -acceptance x its mean at 64 interior points and the check points (else tension), its
//     load matches (else load_mismatch) and, with several indentors, the surface clears its profile
//     at 14 points L/64 .. L from its edges (a general profile's inside its search window; else
//     penetration: the slope equations are solved but
//     the contact set is not the physical one); the scene's code is the coupled solve's or the
//     first non-ok contact's. Flat punches close behind one another at alpha > 0 typically come back
//     `tension`: the full-contact class of a flat face gives the trailing corner of the leading
//     punch a negative intensity (partial contact of a flat face is not modelled).
//   * Displacement: outside the contact from the slope integral (paper 27, 28) integrated in closed
//     form in s, then Gauss-Jacobi in t (series part), abel's composite quadrature of the apex enrichment;
//     the datum (log-singular at t = a) by one Gauss-Jacobi sum from alpha = 1e-2 on, by closed-form
//     moments of the logarithm at alpha = 0, else (and with a wedge's apex) by tanh-sinh in offsets
//     from a, the apex and b; inside the own
//     contact f(x) - f(a) exactly. Elastic flat punch against -(2P/(pi E*)) arccosh(x/c): < 1e-8 for
//     |x| >= 1.4 c; accuracy degrades next to the edges (log kernel nearly singular there).
//   * Cost (Release, warm caches; build/bin/study_scene_timing and study_wedge_near_edge: wall time
//     of solve_single, grid_points = 1000, displacement off, minimum per call, then over 2 and 2
//     runs; the cheapest solve_options::tolerance at which C_f and the pressure reach 1e-10, with /
//     without the residual): single parabola ~0.2 ms. Single wedge below the boundary: apex >= L/4
//     from both edges (65 points, no map) 0.43-0.69 / 0.30-0.52 ms; nearer an edge, the split form
//     (the long side's constant in closed form plus the short side's step with the apex mapped to
//     the centre, 66 points; punch/src/contact.cpp, build_wedge_near_edge) 0.52-0.97 / 0.34-0.60 ms
//     down to 1e-3 L, 0.82-1.49 / 0.36-0.42 ms within 1e-3 L, 1.46-2.94 / 0.44-0.78 ms at slope
//     ratios 1e-6 and 1e6 (apex within ~1e-7 L; C_f within 2.2e-12 .. 1.8e-9 of an order-16
//     reference that is itself good to ~1e-10 there: README.md). So the target of issue #4 (1e-10
//     for eps, L, C_f and 1000 samples in < 1 ms) is met without the residual for every measured
//     isolated wedge.
//     Where the time goes (alpha = 0.3, S2/S1 = 0.1): abel::solve_step's quadrature of A[phi]
//     ~0.3 ms (65 points), the 1000 samples ~0.11 ms (their series summed four points at a time,
//     quadrature::jacobi_series::evaluate), the independent
//     residual 0.1-0.3 ms. Several indentors (build/bin/study_multi_contact, studies/README.md; two
//     parabolas, all `ok`, edges and C_f to ~1e-12): gap ~ L 1.6-2.7 ms, 0.1 L 12-81 ms, 0.01 L
//     81-225 ms, 1e-3 L 0.83-3.6 s (the correction's degree grows like sqrt(L/gap) and each Newton
//     evaluation is a dense solve; far from the solution it is solved inexactly); parabola + wedge
//     30-400 ms; rows of N parabolas 1.5 L apart (alpha 0.3, tolerance 1e-10; loads imposed above 5
//     contacts; build/bin/study_multi_contact --rows-only, studies/README.md): N = 5 15 ms (10
//     Newton iterations), 10 28 ms (13), 40 0.16 s (10), 100 0.51 s (12), 300 2.7 s (24), 1000 16 s
//     (22; peak RSS 194 MB). From 6 contacts on,
//     separated contacts act through abel's far field (abel/far_field.hpp: the coupling
//     data, the union's GMRES products without an assembled matrix, the residuals, the surface
//     displacement), so an evaluation costs O(N) and memory O(N). Against the
//     usual boundary-element
//     method (the tests' oracle at 3200 uniform panels): edges to 3e-4 .. 1.2e-3 L and C_f to
//     1e-7 .. 4e-6 in 2-8 s.
//
// UNITS: any consistent set; the comments use SI: lengths in m, E1 in Pa s^alpha, speed in m/s,
//   load per unit length in N/m, pressure in Pa. Slopes and friction coefficients are dimensionless.
//
// REFERENCES: the source paper (eqs. 8, 23-41; docs/theory.md); K. L. Johnson, Contact
//   Mechanics (1985), ch. 5 and 7 for the elastic limits.
#pragma once

#include <cstddef>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <variant>
#include <utility>
#include <vector>

namespace rhabel::punch {

/// Power-law viscoelastic half-space E(t) = E1 t^-alpha with Coulomb friction at the contact.
struct material {
  double alpha = 0;    ///< material exponent, [0, 1); 0 = elastic
  double E1 = 1;       ///< modulus coefficient E1 > 0 [Pa s^alpha]
  double poisson = 0;  ///< Poisson ratio nu in [0, 1/2]
  double coulomb = 0;  ///< Coulomb friction coefficient k >= 0

  /// Friction parameter beta in [0, 1): tan(beta pi/2) = k (1 - 2 nu) / (2 (1 - nu)).
  double beta() const;
  /// kappa = cos((alpha + beta/2) pi) / cos(beta pi/2), in (-1, 1].
  double kappa() const;
  /// E_U = E1 Gamma(1 - alpha) U^alpha / (1 - nu^2) [Pa], U = sliding speed [m/s] > 0.
  double effective_modulus(double speed) const;
};

/// Parabolic indentor f(x) = -(x - apex)^2 / (2 radius).
struct parabolic {
  double radius = 1;  ///< tip radius R > 0 [m]
};
/// Wedge: f' = slope_leading left of the apex (the leading face, x < apex), -slope_trailing right.
struct wedge {
  double slope_leading = 0.1;   ///< S1 > 0 (dimensionless)
  double slope_trailing = 0.1;  ///< S2 > 0 (dimensionless)
};
/// Flat punch with a face of the given width centred at the apex, corners at apex -+ width/2.
struct flat {
  double width = 1;  ///< face width > 0 [m]
};
/// General profile given by its slope f'(x) (x measured from the indentor's apex), smooth on the
/// contact. The contact interval is assumed to have smooth edges (zero intensity factors) and must
/// lie inside (search_lo, search_hi). Slope discontinuities inside the contact (corners) are
/// allowed and must be listed so that the quadratures split there.
struct general_profile {
  std::function<double(double)> slope;  ///< f'(x), x relative to the apex; must decrease overall
  std::vector<double> corners;          ///< abscissae (relative to the apex) of slope jumps
  /// Optional f(x) up to a constant (x relative to the apex), consistent with `slope`. When set,
  /// the rise of the profile between two points (the levels of indentors on a rigid body, the
  /// penetration check) is its difference, exact; else the integral of `slope` by Gauss-Legendre
  /// between the corners, which converges slowly where `slope` has kinks it does not list (a
  /// spline's knots: up to ~4e-5 of a self-affine profile's span over ~3 knots).
  std::function<double(double)> value;
  /// Optional knots (x relative to the apex, f'''(x+) - f'''(x-)): points where f is C^2 but its
  /// third derivative jumps, as at a cubic spline's knots (a sampled profile's are filled in).
  /// With solve_options::profile_knots the coupled solve (several indentors, a rigid body, a
  /// sampled profile) builds each knot inside a contact into the density as its own singular term
  /// (|t - x|^(2 - alpha)), from alpha = 0.01 on, instead of resolving it by the series' degree
  /// (docs/theory.md section 4). Ignored elsewhere and where a corner lies in the same contact.
  std::vector<std::pair<double, double>> knots;
  double search_lo = -1;                ///< the leading edge is sought in (search_lo, search_hi) [m]
  double search_hi = 1;                 ///< idem for the trailing edge [m]
};

/// Which of the shapes above an indentor has (indentor_result::shape; a sampled profile's contacts
/// are `general`).
enum class shape_kind { parabolic, wedge, flat, general };
/// "parabolic", "wedge", "flat" or "general" (the scene file's names).
const char* to_string(shape_kind shape);

struct indentor {
  std::variant<parabolic, wedge, flat, general_profile> shape;
  double load = 1;  ///< load per unit length lambda > 0 [N/m] (not used with scene::body)
  double apex = 0;  ///< position of the apex (face centre for the flat punch) [m]
  /// scene::body only: height of the apex above the body's reference level [m] (upward positive:
  /// a higher indentor reaches the surface later). The profile on the body is f(x) + height.
  double height = 0;
};

/// Several indentors mounted on one rigid body pressed with a total load (paper, end of section
/// 3; docs/theory.md section 7): the indentors' loads are unknowns, split so that all share one
/// rigid approach. Parabolic, wedge and general profiles; every indentor must touch (an indentor
/// that would carry no load is reported, not dropped: see status_code::contact_lost).
struct rigid_body {
  double load = 1;  ///< total load per unit length > 0 [N/m]
};

struct scene {
  punch::material material;
  double speed = 1;  ///< sliding speed U > 0 towards -x [m/s]
  std::vector<indentor> indentors;
  std::optional<rigid_body> body{};  ///< all indentors on one rigid body (their `load` fields unused)
};

/// Where the pressure samples of solve_options::grid_points lie in a contact [a, b] of length L.
enum class sample_spacing {
  /// Midpoints of n equal cells, a + L (k + 1/2)/n: a table of equal steps.
  uniform,
  /// Chebyshev points of the first kind, a + L (1 - cos(pi (k + 1/2)/n))/2: spaced like
  /// (pi/n)^2 L/16 next to the edges, where the pressure vanishes or blows up like a power of the
  /// distance, so that plots show the edge behaviour (the first sample of 400 lies 4e-6 L from
  /// the edge, against 1.25e-3 L on the uniform grid).
  graded
};

struct solve_options {
  std::size_t grid_points = 0;  ///< pressure and displacement samples per indentor (0 = none)
  bool displacement = true;     ///< with grid_points > 0: also the displacement grid (the costlier one)
  sample_spacing spacing = sample_spacing::uniform;  ///< where the pressure samples lie (the displacement's are uniform)
  double tolerance = 1e-12;     ///< relative tolerance of the root finders and of the expansions
                                ///< (a sampled profile's edges: max(tolerance, 1e-3 acceptance), profile.hpp)
  std::size_t max_degree = 128; ///< largest Jacobi degree of a density expansion (cost ~ degree^2);
                                ///< the wedge's enriched solve may use up to max(2 max_degree + 1, 585) points
  /// Wedge below the boundary: build the apex singularity into the density (abel::solve_step's
  /// singular enrichment; spectral convergence, no Gibbs oscillation at the apex; an isolated wedge
  /// with the apex nearer an edge than L/4 in the split form, a coupled one down to 1e-4 L from an
  /// edge). L and eps are exact either way. false: plain Jacobi series of degree max_degree
  /// (C_f and the pressure samples of an isolated wedge then from the Riemann-Hilbert route; a
  /// coupled one: pressure poor next to the apex, C_f by Richardson extrapolation, ~1e-6; residual
  /// and displacement from the series). The name is kept from the former apex split.
  bool wedge_apex_split = true;
  /// A general profile's knots (general_profile::knots; a sampled profile's spline knots) inside a
  /// coupled contact: build each into the density as its own singular term (abel::solve_kinks,
  /// from alpha = 0.01 on) instead of resolving it by the series' degree. The series then
  /// converges spectrally: on self-affine profiles of 4000 and 16000 samples (21-85 patches) the
  /// residual of (8) is 4e-10 .. 1e-8 where the plain series ends at 2e-7 .. 4e-7 (docs/theory.md
  /// section 9). Off by default: each knotted contact costs ~3 us a knot and interpolation point
  /// at every evaluation of the coupled solve, and on a periodic 86-patch profile whose plain
  /// series climbs to degree 2048 the search took 55 s, against 10 s without.
  bool profile_knots = false;
  /// Threshold of the evidence for status_code::ok (relative residual of (8), relative negative
  /// pressure, relative load defect, error estimate). A result beyond it is returned with another
  /// code, never silently.
  double acceptance = 1e-9;
  /// Compute the independent residual of (8) at 7 interior points (indentor_result::residual,
  /// diagnostics::residual): the evidence that the solution solves the equation. false skips it
  /// (roughly a quarter to a third of a wedge solve; study_scene_timing) and reports NaN there.
  bool residual = true;
  /// Threads for the finite-difference columns of a coupled solve's Jacobian (several contacts;
  /// the sampled profile's contact search): 1 runs them in turn, 0 on every core. The columns are
  /// independent, so the result is the same for any count, bit for bit. At most 1024. The other
  /// work of a solve stays on the calling thread; callers that solve many scenes at once (rhabel
  /// sweep) keep 1 and run scenes in parallel instead.
  std::size_t threads = 1;
  /// Seconds after which a coupled solve (several contacts; the sampled profile's contact search)
  /// stops and reports what it reached with status_code::not_converged and a message naming the
  /// limit; 0 = no limit. Checked at every evaluation of the coupled edge conditions (each
  /// Jacobian column, each point of a line search) and every product of the boundary-element
  /// active set (a profile's coarse search, solve_profile_bem), so a solve stops within one evaluation of it (milliseconds to a few tenths of a
  /// second) and then reports the last accepted state, with its report's own cost on top (the
  /// residuals and clearances of the contacts reached). A one-contact solve, which takes
  /// milliseconds, does not check it. The work done by a given time depends on
  /// the machine: a result stopped by the limit is not reproducible, one that finished is.
  double time_limit = 0;
  /// Polled where time_limit is checked (so never by a one-contact solve, which takes
  /// milliseconds); when it returns true the solve stops at that check, skips its report and
  /// throws punch::interrupted (no result). For front ends that turn a user's Ctrl-C into a stop
  /// (the Python package raises KeyboardInterrupt then). It may be called from the threads of
  /// `threads`; it must be cheap or throttle itself. Empty: never polled.
  std::function<bool()> interrupt{};
  /// Several contacts, fewer than six: when two neighbouring contacts are closer than this
  /// fraction of the shorter one, the coupling correction of each Newton evaluation is solved in
  /// abel's boundary-layer basis (abel::solve_union_layered: a Jacobi series of degree 24 to 48
  /// plus poles clustered beyond the facing ends, ~log(L/gap) unknowns) instead of the Jacobi
  /// series alone (degree ~ 10 sqrt(L/gap), up to 600). The default is where the two cost about
  /// the same on two parabolas (alpha 0.3, one core): the series alone is faster above it (gap
  /// 1e-2 L: 0.12 s against 0.19 s), the layers below (1.1e-3 L: 0.46 s against 1.08 s, and a
  /// residual of 1.2e-14 against 1.4e-11; 4e-4 L: 0.64 s against 2.2 s). 0 never uses the layers,
  /// a value >= 1 uses them for every pair of neighbours closer than a contact length.
  /// The reported density is one Jacobi series either way (the layers are projected onto it). From
  /// six contacts on (the far-field route) the series alone is used.
  double layered_below = 3e-3;
};

/// Thrown by solve, solve_profile and solve_profile_bem when solve_options::interrupt returned true.
struct interrupted : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// What a result's evidence says (indentor_result::code, scene_result::diagnostics_t::code). A
/// result is `ok` only when, on its contact, the independent residual of (8) is within
/// solve_options::acceptance (relative to the data's scale), the pressure is non-negative to that
/// tolerance (relative to the largest sampled pressure), the load is matched to it (relative) and
/// the error estimate is within it; anything else carries one of the other codes, and the status
/// message gives the numbers.
enum class status_code {
  ok,              ///< every check above passed
  not_converged,   ///< residual or error estimate above the acceptance, or an iteration that did not converge
  tension,         ///< the pressure is negative somewhere (beyond the acceptance)
  load_mismatch,   ///< the load of the solution differs from the requested one
  contacts_merge,  ///< two contacts meet (their gap closed during the coupled solve)
  penetration,     ///< several indentors: the surface crosses an indentor's profile next to its
                   ///< contact (checked at 14 points L/64 .. L from its edges)
  contact_lost,    ///< rigid body: an indentor's contact shrinks to nothing (it would carry no
                   ///< load at this total load and these heights)
};

/// "ok", "not_converged", "tension", "load_mismatch", "contacts_merge", "penetration", "contact_lost".
const char* to_string(status_code code);

/// Where a material lies with respect to alpha + beta/2 = 1/2 (REGIMES at the top).
enum class regime_kind {
  below,     ///< alpha + beta/2 < 1/2 (kappa > 0)
  boundary,  ///< alpha + beta/2 = 1/2 within 1e-12 (kappa = 0)
  above,     ///< alpha + beta/2 > 1/2 (kappa < 0)
};

/// "below", "boundary", "above".
const char* to_string(regime_kind regime);

enum class edge_side { leading, trailing };

/// Behaviour of the pressure at one edge of a contact interval: p ~ K (distance)^exponent.
struct edge_report {
  edge_side side = edge_side::leading;
  double position = 0;          ///< abscissa of the edge [m]
  bool singular = false;        ///< exponent < 0 (infinite pressure at the edge)
  double exponent = 0;          ///< gam (leading) or del (trailing) of the notes
  /// K = lim p / distance^exponent [Pa m^-exponent], of the whole density (series and apex part).
  /// At the edge next to the apex of a wedge in the split form (apex nearer an edge than L/4): an
  /// estimate (Richardson extrapolation, punch/src/fields.cpp edge_intensity), measured within
  /// 2.8e-11 of the elastic closed form.
  double intensity_factor = 0;
};

/// The solved pressure of a contact as a function: p(x) [Pa] at any abscissae, evaluated from the
/// density itself (its Jacobi series, apex enrichment and boundary-layer part; an isolated wedge
/// with its apex near an edge from its Riemann-Hilbert solution, interpolated as the samples are).
/// At the abscissae of indentor_result::grid_x it gives indentor_result::pressure to rounding (the
/// shift of a scene far from the origin). 0 outside the open contact (a, b) and for a line load;
/// +inf at a singular point inside (a wedge's apex below the boundary). Accuracy: the density's,
/// indentor_result::error_estimate relative to the peak (an estimate, not a bound). Cost: O(degree)
/// a point, plus a Riemann-Hilbert interpolant (~3 ms) per call for such a wedge. Thread-safe;
/// copies share the density.
class pressure_field {
 public:
  struct source;  ///< the density and its scale (defined in punch/src)
  pressure_field() = default;
  pressure_field(std::shared_ptr<const source> s, double origin) : source_(std::move(s)), origin_(origin) {}
  /// p(x) at every x. Throws std::invalid_argument for a non-finite x, std::logic_error when
  /// empty (a default-constructed field).
  std::vector<double> operator()(const std::vector<double>& x) const;
  /// False for a default-constructed field (not from a solve).
  explicit operator bool() const noexcept { return source_ != nullptr; }

 private:
  std::shared_ptr<const source> source_;
  double origin_ = 0;  // the solve's coordinates are x - origin (scenes far from 0)
};

struct indentor_result {
  shape_kind shape = shape_kind::parabolic;  ///< the indentor's shape (a profile's contact: general)
  double a = 0;                     ///< leading edge [m]
  double b = 0;                     ///< trailing edge [m]
  double contact_length = 0;        ///< L = b - a [m] (0 for a line load)
  std::optional<double> epsilon;    ///< wedge only: eps = (apex - a)/L
  double load = 0;                  ///< int p over the contact, recomputed from the solution [N/m]
  double hysteretic_friction = 0;   ///< C_f = (1/lambda) int f' p (0 when the solve failed before the contact carried load)
  double total_friction = 0;        ///< C_f + k
  double peak_pressure = 0;         ///< max p [Pa]; +inf if some point is singular
  double peak_pressure_at = 0;      ///< where the max is attained (the singular point if infinite) [m]
  std::vector<edge_report> edges;   ///< leading then trailing
  std::vector<double> grid_x;       ///< pressure abscissae, inside [a, b] (empty unless asked; solve_options::spacing)
  std::vector<double> pressure;     ///< p(grid_x) [Pa]
  pressure_field pressure_at;       ///< p(x) at any x: `r.pressure_at(xs)` (pressure_field)
  std::vector<double> displacement_x;  ///< displacement abscissae, [a - L, b + L] (empty unless asked)
  std::vector<double> displacement;    ///< downward surface displacement relative to its value at
                                       ///< the leading edge a: equals f(x) - f(a) in contact [m]
  /// Several indentors: the rigid approach of the indentor, approach = w(x) - f(x) on its contact
  /// [m], w the downward surface displacement of docs/theory.md section 8 (the kernel Psi fixes its
  /// constant: a plane-strain half-space has no displacement datum at infinity, so approaches are
  /// meaningful as differences between indentors and as responses to loads; paper, end of section
  /// 3). f is the profile with f(apex) = 0. NaN for a single indentor (not computed).
  double approach = std::numeric_limits<double>::quiet_NaN();
  double residual = 0;              ///< max |LHS - RHS of (8)| / max |F| at check points
                                    ///< (NaN if solve_options::residual is false)
  double error_estimate = 0;        ///< estimated relative error of the density (an estimate)
  std::size_t degree = 0;           ///< Jacobi degree used (wedge with an apex near an edge: in the mapped variable)
  status_code code = status_code::ok;  ///< what the evidence says (see status_code)
  std::string status;               ///< "ok", or what went wrong / was approximated, with the numbers
};

struct scene_result {
  /// scene::body: the body's approach, approach_i + height_i (equal for all indentors to the
  /// acceptance, relative to the largest f' L; the evidence is in diagnostics.status otherwise).
  std::optional<double> body_approach;
  double beta = 0;
  double kappa = 0;
  regime_kind regime = regime_kind::below;  ///< the sign of alpha + beta/2 - 1/2 (see the top)
  std::vector<indentor_result> indentors;
  /// Several indentors, with grid_points > 0 and displacement: the downward surface displacement
  /// w(x) [m] of the whole scene on one grid (grid_points points a contact, uniform over the
  /// contacts' span widened by the longest contact on either side), in the datum of
  /// indentor_result::approach: w = f_i(x) + approach_i on contact i (f_i(apex_i) = 0), so that
  /// the indentors' displacements join into one curve. Empty otherwise.
  std::vector<double> surface_x, surface;
  struct diagnostics_t {
    double residual = 0;  ///< max over indentors of indentor_result::residual (NaN if not computed)
    double seconds = 0;   ///< wall-clock solve time [s]
    status_code code = status_code::ok;  ///< the worst of the indentors' codes and the coupled solve's
    /// "ok", the coupled solve's failure, or, when it converged and some indentors are not ok,
    /// the first one's status and how many are not ok with their indices (e.g. "see
    /// indentors[0].status: residual of (8) 2.6e-14 > acceptance 1e-15; 2 of 2 indentors are not
    /// ok: 0, 1"; at most 8 listed).
    std::string status;
    std::size_t iterations = 0;  ///< Newton iterations of the coupled solve (0 for one indentor)
  } diagnostics;
};

/// Solves the scene. Validates every field first and throws std::invalid_argument naming it, e.g.
/// "rhabel::punch::solve: indentors[1].radius = -2 must be > 0". Throws std::domain_error when a
/// single indentor has no contact interval. Several indentors are always returned with their
/// evidence: contacts that meet, an iteration that does not converge, tension or penetration are a
/// status_code other than ok with the numbers in the status messages (see STATUS at the top).
scene_result solve(const scene& s, const solve_options& options = {});

/// Single-indentor building block (no other indentor present); the apex of `ind` is honoured.
indentor_result solve_single(const material& m, double speed, const indentor& ind,
                             const solve_options& options = {});

/// Trial solution of paper section 4: on a PRESCRIBED interval [a, b] (absolute abscissae, a < b),
/// the unique solution of (8) for the indentor's own profile that is bounded at a and unbounded at b
/// (index nu = 0, exponents gam = (1-2alpha-beta)/2, del = (beta-1)/2), scaled by nothing (the load
/// is whatever (8) gives). Returns the load int p [N/m] and C_f = int f' p / int p of that field.
/// Used to test the conjecture that C_f, at fixed load, is stationary at the true contact interval.
/// Parabolic, wedge (apex enrichment as in solve) and general profiles; throws std::invalid_argument for
/// a flat punch or a < b violated.
struct trial_result {
  double load = 0;
  double hysteretic_friction = 0;
  double error_estimate = 0;  ///< estimate of the relative error of the density
};
trial_result trial_interval(const material& m, double speed, const indentor& ind, double a, double b,
                            const solve_options& options = {});

/// The regime of a material (see the top of this header).
regime_kind regime(const material& m);

/// Library version "major.minor.patch".
const char* version();

}  // namespace rhabel::punch
