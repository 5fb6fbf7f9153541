// punch/src/periodic_profile.cpp: a periodic sampled profile by the spectral contact search
// (solve_profile with profile.period; docs/theory.md section 10).
//
// THE ITERATION. On a window of one period whose ends lie in a gap of the contacts, the periodic
// problem is the finite one with the profile z replaced by z - w_img, w_img the displacement
// that the other periods add (periodic_images.hpp), which depends on the solution. So:
//   0. a coarse periodic boundary-element solve (coarse_contact.hpp) gives the contacts, their
//      loads and a first w_img (its panels as point sources); the window starts at the sample
//      nearest the middle of the largest gap between its contacts;
//   1. the finite window with z - w_img is searched (contact_set.cpp, search_window), its first
//      round seeded by the last contacts;
//   2. w_img of the solved densities; when its slope moved by more than the target on a contact
//      (relative to that contact's data), 1 again from the new w_img.
// Each pass is a fixed-point step z - w_img(g) -> g: the images are far from the contacts (the
// window's ends in the widest gap), so their response to a change of g is small and the passes
// converge geometrically.
// The reported residual of (8) is the window's plus the last pass's change of w_img's slope:
// that is the residual of the periodic equation for the reported densities.
#include "coupled_problem.hpp"
#include "periodic_images.hpp"
#include "profile_search.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <sstream>

namespace rhabel::punch::detail {
namespace {

constexpr const char* periodic_who = "rhabel::punch::solve_profile";
// Fixed-point passes at most.
constexpr std::size_t max_passes = 40;
// The passes stop when w_img's slope changed by at most this fraction of the acceptance (relative
// to each contact's data): the residual of the periodic equation then exceeds the window's by at
// most that.
constexpr double pass_fraction = 0.1;
// The table of w_img to this fraction of max |z'| (slope) and of max z - min z (value).
constexpr double table_accuracy = 1e-13;

/// The sample nearest the middle of the widest gap between the contacts (periodic, in the order
/// of x); `widest` the gap's width (the period when there is no contact).
std::size_t cut_sample(const std::vector<double>& x, double period, const std::vector<coarse_patch>& patches,
                       double& widest) {
  const double x0 = x.front();
  double middle = x0;
  widest = period;
  if (!patches.empty()) {
    widest = -1;
    for (std::size_t k = 0; k < patches.size(); ++k) {
      const double next_a = k + 1 < patches.size() ? patches[k + 1].a : patches.front().a + period;
      const double gap = next_a - patches[k].b;
      if (gap > widest) widest = gap, middle = patches[k].b + gap / 2;
    }
  }
  middle = x0 + std::fmod(std::fmod(middle - x0, period) + period, period);
  std::size_t best = 0;
  double distance = period;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double d = std::min(std::abs(x[i] - middle), period - std::abs(x[i] - middle));
    if (d < distance) distance = d, best = i;
  }
  return best;
}

/// Abscissae moved into the window [lo, lo + period).
double into_window(double t, double lo, double period) { return t < lo ? t + period : t; }

/// The contacts moved into the window, in the order of x, those that meet across the window's
/// original start joined.
std::vector<coarse_patch> window_patches(std::vector<coarse_patch> patches, double lo, double period) {
  for (auto& p : patches) {
    if (p.a < lo) p.a += period, p.b += period;
  }
  std::sort(patches.begin(), patches.end(), [](const coarse_patch& p, const coarse_patch& q) { return p.a < q.a; });
  std::vector<coarse_patch> out;
  for (const auto& p : patches) {
    if (!out.empty() && p.a <= out.back().b + 1e-12 * period) {
      out.back().b = std::max(out.back().b, p.b);
      out.back().load += p.load;
    } else {
      out.push_back(p);
    }
  }
  return out;
}

/// The window's result made the periodic one's: the fields the window computes from its profile
/// z - w_img and its own displacement get the images' part back (`used`: the w_img the window was
/// solved with). C_f = int z' p / int p with z' = (z - w_img)' + w_img' on the contact; the
/// approach w - (z - z(tip)) and the displacements gain w_img. With `next` (the w_img of the
/// solved densities), each contact's residual of (8) gains the change of w_img's slope on it
/// relative to its data (then it is the periodic equation's residual), and the level mismatch
/// gains the largest change of w_img between neighbouring contacts (relative to the span);
/// returns the largest change of either.
double add_images(profile_result& r, const image_field& used, const image_field* next, const profile_curve& window,
                  const profile_curve& periodic, const std::vector<point_sources>& sources) {
  double worst = 0;
  for (std::size_t k = 0; k < r.contacts.size(); ++k) {
    indentor_result& c = r.contacts[k];
    const point_sources& src = sources[k];  // its density's (window_solution: in the contacts' order)
    double moment = 0, load = 0;
    for (std::size_t q = 0; q < src.t.size(); ++q) moment += src.w[q] * used.slope(src.t[q]), load += src.w[q];
    const double coulomb = c.total_friction - c.hysteretic_friction;
    if (load > 0) c.hysteretic_friction += moment / load;
    c.total_friction = c.hysteretic_friction + coulomb;
    if (k < r.tips.size() && std::isfinite(c.approach)) c.approach += used.value(r.tips[k]);
    for (std::size_t i = 0; i < c.displacement_x.size(); ++i)
      c.displacement[i] += used.value(c.displacement_x[i]) - used.value(c.a);
    if (next && c.contact_length > 0) {
      double change = 0, data = 0;
      for (int j = 0; j <= 16; ++j) {
        const double x = c.a + c.contact_length * (0.5 - 0.5 * std::cos(pi * j / 16.0));
        change = std::max(change, std::abs(next->slope(x) - used.slope(x)));
        data = std::max(data, std::abs(window.slope(x)));
      }
      const double relative = data > 0 ? change / data : change;
      c.residual += relative;
      worst = std::max(worst, relative);
    }
  }
  if (next) {
    // The levels move with w_img too: its change between neighbouring contacts' leading edges,
    // relative to the profile's span, joins the window's level mismatch.
    const auto [zlo, zhi] = std::minmax_element(periodic.z().begin(), periodic.z().end());
    const auto moved = [&](double at) { return next->value(at) - used.value(at); };
    for (std::size_t k = 1; k < r.contacts.size(); ++k) {
      const double relative = std::abs(moved(r.contacts[k].a) - moved(r.contacts[k - 1].a)) / (*zhi - *zlo);
      r.level_mismatch += relative;
      worst = std::max(worst, relative);
    }
  }
  for (std::size_t i = 0; i < r.surface_x.size(); ++i) r.surface[i] += used.value(r.surface_x[i]);
  if (!r.contacts.empty() && !r.tips.empty() && std::isfinite(r.contacts.front().approach)) {
    double top = -std::numeric_limits<double>::infinity();
    for (const double z : periodic.z()) top = std::max(top, z);
    r.body_approach = r.contacts.front().approach + top - periodic.value(r.tips.front());
  }
  r.diagnostics.residual = 0;
  for (const auto& c : r.contacts) r.diagnostics.residual = std::max(r.diagnostics.residual, c.residual);
  return worst;
}

}  // namespace

profile_result solve_periodic_profile(const profile_scene& s, const context& cx) {
  const profile_curve curve(s.profile);
  const double period = s.profile.period, load = s.load / cx.pressure_scale;
  const auto& x = s.profile.x;
  const auto [zlo, zhi] = std::minmax_element(s.profile.z.begin(), s.profile.z.end());
  const double span = *zhi - *zlo;
  double steepest = 0;
  for (const double xi : x) steepest = std::max(steepest, std::abs(curve.slope(xi)));
  const double value_accuracy = table_accuracy * span, slope_accuracy = table_accuracy * steepest;
  // The coarse start (without it, when the time runs out there: the window from x_0, no images,
  // the window's own coarse start; the result then says the time ran out).
  point_sources sources;
  std::vector<coarse_patch> patches;
  std::shared_ptr<const image_field> field = std::make_shared<image_field>();
  std::size_t first = 0;
  try {
    patches = coarse_contacts(curve, load, cx, seed_panels * x.size(), seed_panels_fine * x.size(), &sources);
    double widest = 0;
    first = cut_sample(x, period, patches, widest);
    if (widest < period / static_cast<double>(x.size())) {
      std::ostringstream os;
      os.precision(6);
      os << periodic_who << ": at body.load = " << s.load << " the profile touches over the whole period (a coarse "
         << "boundary-element solve leaves no gap of a sample spacing between its contacts): the spectral search needs "
         << "a gap to start its window of one period in; lower body.load, or use profile.solver = \"boundary_element\"";
      throw std::domain_error(os.str());
    }
    for (auto& t : sources.t) t = into_window(t, x[first], period);
    field = std::make_shared<image_field>(sources, x[first], period, cx, value_accuracy, slope_accuracy);
  } catch (const time_limit_reached&) {
    patches.clear();
  }
  const double lo = x[first];
  std::vector<coarse_patch> seeds = window_patches(patches, lo, period);
  profile_scene window;
  window.material = s.material;
  window.speed = s.speed;
  window.load = s.load;
  profile_result out;
  std::size_t rounds = 0, iterations = 0, pass = 0;
  double change = 0;
  std::string stopped;  // why the passes ended before the change met the target ("" if it did)
  // The next pass's search: at the top series degree the last one reached, each of its contacts
  // within capped_below of the acceptance holding its degree. WHY: the images move the contacts
  // little between passes, and from degree 128 each pass climbed the degrees again (1e5-sample
  // periodic profile, 443 contacts: the second pass's searches at 128, 512 and 1024 took 70 s).
  context pass_cx = cx;
  // The passes solve one window with nearly the same contacts: each starts from the Jacobian the
  // last one kept (coupled::jacobian_memo).
  const auto memo = std::make_shared<coupled::jacobian_memo>();
  // The contacts the last pass lost once and did not restore, given back by the next pass where
  // the profile penetrates there (contact_set.cpp, restore_lost). WHY: each pass is a new search,
  // which would otherwise not know them as lost, as the searches at higher degrees already do.
  // (No measured scene needs it yet: the ~980-patch profile converges in one pass.)
  std::vector<coarse_patch> lost;
  bool spare = false;  // the last pass kept light contacts far from the solution: so does the next
  for (;;) {
    ++pass;
    const profile_curve wc(curve, first, [field](double at) { return field->value(at); },
                           [field](double at) { return field->slope(at); });
    window.profile.x = wc.x();
    window.profile.z = wc.z();
    window_solution sol = search_window(window, wc, pass_cx, seeds, memo, lost, spare);
    // (before the result moves out: its contacts' residuals of (8) are the window's own)
    std::vector<coarse_patch> next_seeds = sol.contacts_capped(capped_below * cx.options.acceptance);
    lost = sol.lost_seeds();
    spare = sol.spare;
    rounds += sol.result.diagnostics.rounds;
    iterations += sol.result.diagnostics.iterations;
    out = std::move(sol.result);
    // Each contact's density as point sources, once: its C_f correction and the next w_img.
    std::vector<point_sources> sources_of;
    for (const auto& d : sol.densities) sources_of.push_back(density_sources(d, sol.origin));
    std::shared_ptr<const image_field> next;
    if (out.diagnostics.code == status_code::ok) {
      try {
        next = std::make_shared<image_field>(joined(sources_of), lo, period, cx, value_accuracy, slope_accuracy);
      } catch (const time_limit_reached&) {
        stopped = cx.time_limit_message() + " before the other periods' displacement of the solution was evaluated";
      }
    }
    change = add_images(out, *field, next.get(), wc, curve, sources_of);
    if (!next) break;
    if (change <= pass_fraction * cx.options.acceptance) break;
    if (pass == max_passes) {
      stopped = "after " + std::to_string(pass) + " passes";
      break;
    }
    if (cx.out_of_time()) {
      stopped = cx.time_limit_message() + " after " + std::to_string(pass) + " passes";
      break;
    }
    seeds = std::move(next_seeds);
    pass_cx.options.max_degree = std::max(pass_cx.options.max_degree, sol.max_degree);
    field = std::move(next);
  }
  out.window_start = lo;
  out.diagnostics.rounds = rounds;
  out.diagnostics.iterations = iterations;
  // ok when the last change is within the acceptance (each contact's residual includes it), even
  // if the passes stopped before pass_fraction; not when the change could not be evaluated.
  const bool unchecked = out.diagnostics.code == status_code::ok && !stopped.empty() && change == 0;
  if (out.diagnostics.code == status_code::ok && (unchecked || change > cx.options.acceptance)) {
    std::ostringstream os;
    os.precision(3);
    os << "the other periods' displacement was not converged: " << (stopped.empty() ? "" : stopped + "; ")
       << "its slope or level changed by " << change << " of the data in the last pass";
    out.diagnostics.code = status_code::not_converged;
    out.diagnostics.status = os.str();
  }
  if (out.diagnostics.code == status_code::ok && out.level_mismatch > cx.options.acceptance) {
    std::ostringstream os;
    os.precision(3);
    os << "the contacts' levels differ from the body's by up to " << out.level_mismatch
       << " of max z - min z with the other periods' displacement (at x = " << out.level_mismatch_at << ")";
    out.diagnostics.code = status_code::not_converged;
    out.diagnostics.status = os.str();
  }
  return out;
}

}  // namespace rhabel::punch::detail
