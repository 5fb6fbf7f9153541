// rhabel/punch/profile.hpp: a measured (sampled) rigid profile pressed with a total load onto a
// power-law viscoelastic half-space, with the set of contacts unknown (issue: rough surfaces,
// asperity arrays given as data).
//
// WHAT IS COMPUTED
//   One rigid body whose lower surface is given by samples (x_i, z_i), z in the sign convention of
//   the profile f of contact.hpp (z grows towards the half-space: samples of a parabola with its
//   vertex at c are z = -(x - c)^2 / (2R)), slides at speed U towards -x over the half-space of
//   contact.hpp's material and is pressed with the load P per unit length. The contacts are not
//   given: the solver finds them, and for each reports what contact.hpp reports for an indentor
//   (edges, load, pressure, C_f, edge exponents, evidence), plus the body's approach and the
//   clearance of the surface outside the contacts.
//
// THE INTERPOLANT (docs/theory.md section 9)
//   The profile between samples is the natural cubic spline of the samples (GSL's cspline),
//   separately on each piece between declared corners:
//     * C2 between corners, so the forcing F = z'/Gamma(1 - alpha) of (8) is C1 and the density,
//       expanded in Jacobi polynomials on each contact, converges algebraically (like degree^-3)
//       where a polynomial forcing would converge spectrally: the residual of (8) against the
//       spline stops near the spline's own slope error (MEASURED below). The status reports it;
//       set solve_options::acceptance to what the data is worth (a measured profile is rarely
//       known better than 1e-4; the examples and tests use 1e-6).
//     * a declared corner (sampled_profile::corners, a sample abscissa) is kept exactly: the slope
//       jumps there, the two sides are separate splines with natural ends (zero curvature at the
//       corner, exact for the flanks of a wedge). Corners are for the valleys between asperities
//       (the envelope of overlapping caps, a machined groove): inside a contact the density's
//       singularity at a corner is not built in (the wedge of contact.hpp is), and such a contact
//       comes back not_converged or tension (measured: a sampled symmetric wedge, residual 0.15 at
//       alpha 0.3). Corners are not detected: in measured data a detector turns noise into corners.
//     * the natural end conditions make the spline of a parabola exact only away from the ends
//       and the corners: the end's error decays by 2 - sqrt(3) = 0.27 per sample, below 1e-14 of
//       the curvature 25 samples in. Keep the data 25 samples wider than the contacts.
//   Outside [x_0, x_n] the profile is not defined; a contact must lie inside the samples (else
//   status not_converged naming it).
//
// THE CONTACT SET (an active set on the profile's bumps; punch/src/contact_set.cpp)
//   The bumps are the local maxima of the samples (tips), each with its basin between the lowest
//   samples towards its neighbours. A contact covers one basin, or a run of adjacent basins when
//   contacts merged.
//   The first set comes from a coarse boundary-element solve of the whole profile at the full
//   load (punch/src/coarse_contact.hpp: piecewise-constant pressure on 8 panels per sample, and
//   on up to 32 while a contact has fewer than 4 panels, at most 2^21, non-negative, one rigid
//   body, an active set on panels refined from 256 panels up; 0.01-0.21 s for 800-4000 samples at
//   8 a sample): each coarse contact becomes a contact of its own (the run of basins whose tips
//   it covers; two coarse contacts may share a basin), with its coarse load as the start of the
//   coupled solve's split and its coarse edges as the start of the first round's Newton
//   iteration (a seed: the isolated contacts of a rough profile's bumps are often not found
//   inside their basins, or overlap). When Newton fails from the seeds (a contact narrower than
//   a sample, known to a panel, starts with its level far off), the first round follows the
//   homotopy from the seeds' own edge conditions to zero (F(x) - (1 - s) F(x0), s from 0 to 1).
//   The levels of the contacts use the spline's values, not an integral of its slope. From
//   there, rounds at the full load P:
//     1. solve the current contacts on one rigid body (contact.hpp's coupled solve: every contact a
//        general profile with smooth edges, loads unknown, total load P, equal rigid levels),
//        each contact's Newton iteration started from its edges in the last converged round (the
//        coarse ones in the first);
//     2. a contact that vanishes in that solve (status contact_lost; also one below 1 % of the mean
//        load that a Newton step would shrink past zero) is dropped; two contacts that meet
//        (contacts_merge; also two closing to a gap below 1e-4 of a contact length) become one
//        contact over both basins; a contact that reaches beyond its basins takes the next basin
//        in (shared with the contact there while the two stay apart);
//     3. otherwise the surface displacement is evaluated at every sample outside the contacts (not
//        within 1/64 of a contact's length of its edges, where the surface's quadrature is not
//        resolved and the edge conditions hold anyway): where the profile penetrates the surface
//        by more than acceptance x (max z - min z), the basins of the deepest penetrations (within
//        a factor 4 of the deepest) are added as new contacts, each started from a quarter of a
//        sample spacing about its deepest sample; so is a penetration on a basin that has a
//        contact, more than a sample spacing from it (a flank's contact of its own);
//     4. a contact whose pressure is negative inside (below -acceptance x its mean) starts the
//        next round without the part where it is negative: its edge moved there when that part
//        reaches the edge, else as two contacts either side of it (the edge conditions also have
//        such a root where the physical solution has a gap; at most twice a tip).
//   The coarse set is first-order accurate: a contact carrying a few percent of its neighbours'
//   load may be missing or extra, and costs one more round. A contact spanning spline knots that
//   misses the acceptance at the series' degree is solved again at degree 512, 1024, then 2048 (see
//   below), from the last round's contacts when it reached the full load (its rounds then add
//   the contacts missing where the surface penetrates). When the seeded rounds at these degrees do not end ok (or the coarse solve's active
//   set does not settle), the search starts again by load continuation: from the highest tip
//   alone at 1/256 of P, the load raised by 4 after each round that settles (the set grown at t
//   is the start at 4 t), a step that fails halved towards the last settled load (at most three
//   times), then rounds at P (and the degrees again).
//   The seeded rounds solve the edges to 1e-3 x acceptance (when that is above
//   solve_options::tolerance; 1e-2 x acceptance in the searches at higher degrees from the
//   contacts already found, which polish a settled set): the evidence is judged at the
//   acceptance, and the steps beyond that cost time without changing what the checks see (of the
//   54 self-affine scenes of rough_matrix.py ok with the edges to the tolerance 1e-12 and ok now,
//   one C_f moved in its 10 printed digits, by 3.5e-8 relative).
//   A bump dropped twice at the same load is not added again (the iteration could cycle between
//   a contact too small to keep and a penetration too deep to ignore): its penetration is then
//   reported as status penetration with the numbers.
//   A scene whose coarse solve puts 1e-3 of the load or more on a panel at an end of the samples
//   is refused (std::domain_error naming body.load and the samples): the surface displacement of a
//   load grows with the distance (Psi ~ -d^alpha/alpha, -log d at alpha = 0), so far from the
//   loads the surface rises above any profile of bounded height, and a long profile under a heavy
//   load (or at alpha near 1) touches at the end of its data, beyond which nothing is known.
//   A result that is not ok says what is missing: diagnostics.load_fraction is the fraction of the
//   load its contacts carry (below 1 when the search stopped inside its load continuation, and
//   then the status leads with "the search reached only t of body.load"), and `penetrations`
//   lists where the profile penetrates the surface outside the contacts found (the contacts the
//   search is missing). A result whose contacts are not all ok leads with the first one's status
//   and lists how many are not ok (e.g. "see contacts[44].status: residual of (8) 1.27e-06 >
//   acceptance 1e-06; 8 of 435 contacts are not ok: 44, 47, ..."). solve_options::time_limit is
//   checked at every evaluation of a round's coupled solve and every step of the coarse solve: the
//   search then reports its last round, and a result that is not ok once the time ran out says so
//   (whichever stage the limit cut: a round, the series degrees, a periodic pass).
//   The contacts' series go to solve_options::max_degree (128 by default). When the result
//   misses the acceptance only because a contact's series stopped there with its residual of
//   (8) above the acceptance (a contact spanning several samples of a rough profile: the
//   spline's C2 joints make its series converge algebraically, measured residual 5e-6 at degree
//   127 and 2e-8 at 511; a contact over ~3 samples, 1.8e-6 at 511 and 4.2e-7 at 1023; over 4-8
//   samples, 1.1e-6 .. 1.6e-6 at 1023 and 3.5e-8 .. 2.7e-7 at 2047), the
//   search runs again with the series to degree 512, then 1024 and 2048 while one still misses it
//   there, on the same clock. A seeded round whose contact series stops at the degree with its
//   tail above the acceptance ends at its first failed iteration (no retries: none can be ok at
//   that degree), and the next degree starts at once.
//   So `ok` means: every contact passes contact.hpp's checks (residual of (8) against the
//   spline, non-negative pressure, loads adding up to P), the levels of neighbouring contacts
//   evaluated afresh from the reported pressures agree with the profile's rise between them
//   (profile_result::level_mismatch), and the surface clears the profile at every checked sample
//   and between neighbouring ones (where the spline rises above both), both to acceptance x
//   (max z - min z).
//
// PERIODIC PROFILES (sampled_profile::period > 0; docs/theory.md section 10)
//   The samples are one period of a profile that repeats (the periodic cubic spline), the load is
//   per period and every period loads the half-space. The search runs on a window of one period
//   that starts at the sample nearest the middle of the widest gap between the contacts of a
//   coarse periodic boundary-element solve; there the other periods add a displacement w_img that
//   is smooth on the window (their contacts are beyond its ends), so the window is the finite
//   problem above with the profile z - w_img. w_img depends on the solution: it is computed from
//   the coarse solve first, then from each solve's densities, and the window is solved again
//   (seeded by the last contacts) until w_img's slope changes by at most a tenth of the acceptance
//   on every contact (measured: one or two passes; the first pass's change is 1e-10 .. 5e-8 of the
//   data on self-affine profiles). The reported residual of (8) of a contact is the window's plus
//   that last change: the periodic equation's. C_f = int z' p / int p with the profile's own
//   slope. The contacts, tips and penetrations are abscissae of the window [window_start,
//   window_start + period], which may extend beyond the samples' period. A load that leaves no gap
//   (full contact over the period) is refused (std::domain_error naming body.load).
//
// MEASURED (alpha 0.3 unless said; tolerance 1e-8 .. 1e-10, acceptance 1e-6)
//   * A parabola sampled 100 times per unit on [-3, 3]: edges, load and C_f of the parabolic
//     indentor's closed-form path to 1e-9 (tests/punch/test_profile.cpp, alpha 0, 0.3, 0.7).
//   * The envelope of four parabolic caps, one 0.3 lower (tests/punch/test_profile.cpp): the same
//     three contacts as the boundary-element oracle's one-body active set, edges and loads within
//     twice its error bar.
//   * 25 cosine bumps (tests/punch/test_profile.cpp): the surface made by the reported pressure
//     samples alone, integrated by the test's own panels, clears the profile and has one level on
//     the 14 contacts, both to 1.6e-4 of the span (the quadrature's error).
//   * Residual of (8) against the spline for ten cosine bumps sampled 200 times per period:
//     4e-9 .. 3.5e-8 (the residual of the contacts of examples/rough_profile.json: 8e-10 .. 5e-8).
//   * Cost (`rhabel solve --acceptance 1e-6 --threads 1`, diagnostics.seconds, two runs, one core;
//     another single-threaded run on the machine's second core):
//       scene (samples, contacts)                                      rounds   time
//       examples/rough_profile.json (2000, 6)                               1     0.09-0.11 s
//       studies/scenes/cosine_profile.py 10 (800, 6)                        1     0.08-0.09 s
//       cosine_profile.py 25 (2000, 14)                                     1     0.19 s
//       cosine_profile.py 50 (4000, 29)                                     1     0.34 s
//       cosine_profile.py 100 20 0.25 (2000, 45)                            1     0.40 s
//       self_affine_profile.py 1000 SEED 5e-4, seeds 1-3 (3-6)            1-2     0.08-0.23 s
//       self_affine_profile.py 4000 SEED 5e-4, seeds 1-3 (6-11)             2     0.35-0.38 s
//       self_affine_profile.py 4000 1 2e-3 (35)                              2     1.0 s
//       self_affine_profile.py 16000 1 1e-3 (35)                             2     1.45-1.48 s
//     The coarse solve takes 0.01-0.21 s of that (0.21 s of the 50 bumps' 0.34 s); the self-affine contacts spanning several samples
//     are solved twice (degree 128, then 512: see above), or more (then 1024, 2048).
//     Each round is one coupled solve of its contacts (contact.hpp, "Cost"); from six contacts on,
//     a rigid body's Jacobian is coloured (10 evaluations) with its far entries from the loads'
//     monopoles. The same 50 bumps at material.alpha = 0: 49 contacts, 1 round, 1.3 s (a
//     contact's own datum by closed-form moments of the logarithm; between alpha = 0 and 1e-2 it is
//     tanh-sinh, several times slower).
//
// LIMITS
//   Any alpha in [0, 1) and beta; contacts with smooth edges and no declared corner inside (see
//   THE INTERPOLANT; either shows as tension or not_converged). The data must extend beyond
//   the contacts. A contact that must cover many samples (a long contact on a rough profile)
//   needs a degree beyond max(2048, max_degree): not_converged with its residual. Rough (self-affine) profiles:
//   of self_affine_profile.py's 36 finite windows at 1000, 4000 and 16000 samples, seeds 1-3,
//   loads 5e-4, 1e-3, 2e-3, 3e-3 (acceptance 1e-6, --time-limit 60; studies/scenes/
//   rough_matrix.py), 15 are refused (contacts at an end of the samples) and the other 21 are ok
//   (3 to 64 contacts, 0.10-10 s; those of tests/punch/test_rough_profile.cpp agree with the
//   boundary-element oracle); one of them (16000 samples, seed 2, load 1e-3) needs one contact
//   across spline knots at degree 2048 (residual of (8) 1.15e-6 at 1023, 3.5e-8 at 2047).
//   A search that ends short of the load says which load was reached and where the
//   profile penetrates. The same 36 as periodic profiles (rough_matrix.py --periodic): all 36 ok
//   (3 to 85 contacts, 0.10-4.6 s), each with the boundary-element solver's patches and C_f within
//   its estimate (those of tests/punch/test_rough_profile.cpp against the boundary-element
//   oracle). 1e5 samples a period with 233 contacts (self_affine_profile.py 100000 1 3e-3
//   --periodic): ok in 15-18 s (one core), at 6e-3 443 contacts ok in 51-58 s; the same samples
//   at 6e-3 with seed 2 in 49-51 s (437 contacts), with seed 3 in 50-51 s (428); at 1.4e-2
//   (~980 patches) ok after 4.0-4.4 min (another job on the other core) with 979 contacts, two of
//   the boundary-element solver's patches one panel apart solved as one (its pressure
//   non-negative to the acceptance, its residual of (8) 9.95e-7 at degree 2047). Each agrees with the boundary-element solver's patches and its C_f within its estimate
//   (tests/long/rough_1e5_periodic*.sh). A search whose last round fails reports its last converged
//   round at that load, not_converged unless its own evidence names another status, with why the
//   search stopped. An ok result bounds the residual of (8), the loads, the pressure's sign, the
//   levels and the clearance by the acceptance. The clearance is checked at the samples and,
//   between two samples, where the spline rises above both (its crests stand up to h^2 |z''|/8
//   above the samples, ~1e-4 of the span on 16000 samples). A contact narrower than a spacing that
//   carries under a hundredth of the mean load can starve in the first rounds' coupled solve; the
//   search gives it back from its coarse edges once the others settle and the profile penetrates there (on the
//   tests' profile of 16000 samples, seed 4, load 2e-3, periodic: two contacts 2e-6 and 2.9e-6
//   wide, 3e-5 and 1.2e-4 of the load, lost and restored; ok with the test oracle's 60 patches in
//   ~70 s, C_f 0.0322901). A lost contact that penetrates by less than the acceptance times the
//   span is not given back (the result is ok without it, and giving it back can cost the search
//   its path). So what an ok cannot exclude is a missing contact whose penetration stays under the
//   acceptance times the span (one the coarse solve does not seed, or such a lost one): the
//   clearance is bounded, not the load such a contact would carry.
//   Scenes the search does not solve, and many hundreds of patches, are what
//   rhabel/punch/profile_bem.hpp's boundary-element solver is for (first order, with error
//   estimates).
#pragma once

#include "rhabel/punch/contact.hpp"

#include <cstddef>
#include <string>
#include <vector>

namespace rhabel::punch {

/// A rigid profile given by samples: x strictly increasing, z(x) in the sign convention of f
/// (towards the half-space), at least 4 samples per piece between corners.
struct sampled_profile {
  std::vector<double> x;        ///< abscissae [m], finite, strictly increasing
  std::vector<double> z;        ///< heights [m], finite, z.size() == x.size()
  std::vector<double> corners;  ///< abscissae of slope jumps: each one of x[1] .. x[n-2]
  /// > 0: the profile repeats with this period [m]; the samples lie in [x_0, x_0 + period) and
  /// the interpolant is the periodic cubic spline closed by (x_0 + period, z_0) (no corners).
  /// Solved by solve_profile (the spectral search on one period: see "PERIODIC PROFILES" above)
  /// or by solve_profile_bem (rhabel/punch/profile_bem.hpp).
  double period = 0;
};

/// The scene of a sampled profile: one rigid body with a total load, the contacts unknown.
struct profile_scene {
  punch::material material;
  double speed = 1;  ///< sliding speed U > 0 towards -x [m/s]
  sampled_profile profile;
  double load = 1;   ///< total load per unit length > 0 [N/m]
};

struct profile_result {
  double beta = 0;
  double kappa = 0;
  regime_kind regime = regime_kind::below;
  /// The contacts found, in the order of x. Each reports contact.hpp's fields; its `approach` is
  /// the rigid approach of the profile's point at its tip.
  std::vector<indentor_result> contacts;
  std::vector<double> tips;  ///< abscissa of the highest tip inside each contact [m]
  /// Several contacts, with grid_points > 0 and displacement: the surface displacement on one
  /// grid, as scene_result::surface (its datum that of the contacts' `approach`).
  std::vector<double> surface_x, surface;
  /// The body's approach: the rigid approach of the profile's highest sample (approach of a
  /// contact + max z - z(tip)); in the Psi datum of contact.hpp (differences are meaningful).
  double body_approach = 0;
  /// Where the contacts' abscissae are reported: a finite window's x_0; a periodic profile's
  /// window of one period [window_start, window_start + period], which starts at the sample
  /// nearest the middle of the widest gap between contacts (the contacts, tips, clearance_at and
  /// penetrations are abscissae in it; subtract the period from those beyond x_0 + period for
  /// the samples' period) [m].
  double window_start = 0;
  /// The body's C_f: int z' p / int p over all contacts (of one period when periodic), from the
  /// contacts' loads and C_f; total_friction = that + material.coulomb.
  double hysteretic_friction = 0;
  double total_friction = 0;
  /// body.load / the window's length (x_n - x_0; periodic: the period) [Pa], and the contacts'
  /// total length over it.
  double mean_pressure = 0;
  double contact_fraction = 0;
  /// Smallest clearance w - z + const found at the checked samples outside the contacts and between
  /// them (where the spline rises above two neighbours), relative to max z - min z (negative: the
  /// profile penetrates the surface there).
  double clearance = 0;
  double clearance_at = 0;  ///< where that clearance is [m]
  /// The contacts lie on one rigid body: the largest |w(a_i) - w(a_(i-1)) - (z(a_i) - z(a_(i-1)))|
  /// over neighbouring contacts' leading edges a_i, w the surface displacement of the reported
  /// pressures (evaluated afresh from them), z the profile, relative to max z - min z; ok needs it
  /// within the acceptance. NaN when the last round had no solved state to check.
  double level_mismatch = 0;
  double level_mismatch_at = 0;  ///< the leading edge of the contact where it is [m]
  /// Where the profile penetrates the surface outside the contacts found by more than the
  /// acceptance (x (max z - min z)): the deepest sample of each such bump, deepest first, at most
  /// 16 [m]. Contacts the search is missing; empty when the surface clears the profile (or the
  /// last round had no solved state to check).
  std::vector<double> penetrations;
  struct diagnostics_t {
    double residual = 0;     ///< max over contacts of indentor_result::residual
    double seconds = 0;      ///< wall-clock time [s]
    status_code code = status_code::ok;
    std::string status;      ///< "ok" or what failed, with the numbers
    std::size_t rounds = 0;  ///< coupled solves of the active set
    std::size_t iterations = 0;  ///< Newton iterations, summed over the rounds
    /// The fraction of body.load that the reported contacts carry: 1, or less when the search
    /// stopped in its load continuation (then the status is not ok and says so: the result is
    /// not the answer to the full load).
    double load_fraction = 1;
  } diagnostics;
};

/// Solves a sampled profile on one rigid body with the contact set unknown (see the top of this
/// header). Validates every field first and throws std::invalid_argument naming it (e.g.
/// "rhabel::punch::solve_profile: profile.x[3] = 0.2 must be > profile.x[2] = 0.2"). Throws
/// std::domain_error when not even the highest tip alone, at 16^-12 of the load, has a contact
/// inside its basin. Otherwise the result is returned with its evidence (the last solved round's
/// contacts); anything not verified is a status other than ok.
profile_result solve_profile(const profile_scene& s, const solve_options& options = {});

}  // namespace rhabel::punch
