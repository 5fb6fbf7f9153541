// punch/src/coarse_contact.cpp: the coarse non-negative solve of a sampled profile on one rigid body
// (coarse_contact.hpp), on panel_grid.hpp's discretisation and active set.
#include "coarse_contact.hpp"

#include "active_solve.hpp"
#include "panel_grid.hpp"

#include <algorithm>

namespace rhabel::punch::detail {
namespace {

// The first grid: every panel active (its LU: 256^3 flops).
constexpr std::size_t first_panels = 256;
// Panels at most. Products and the penetration check go through the FFT (toeplitz_product.hpp),
// O(n log n) each: at 2^17 panels ~9 ms a product and ~16 MB of FFT buffers (measured, one core,
// -O3). It binds only above 65536 samples (32 panels a sample). WHY 2^21: the coupled solve starts
// from these edges, and a contact narrower than a sample is known to a panel. At 2^17 a
// 16000-sample self-affine profile had 8 panels a sample, and the seeded search of its 35 contacts
// at load 1e-3 lost its way (not ok after 45-60 s; ok in 7 s at 2^19). At 2^19 (5 a sample on 1e5
// samples) the periodic 1e5-sample profiles' first rounds starved or merged real contacts: seed 1
// at load 1.4e-2 lost or merged one of its ~980 in each of eight rounds and ended with 977 (one
// real contact missing) in 16-18 min; seeds 2 and 3 at 6e-3 took 4.5-6.1 min. At 2^21 (21 a sample)
// every first round keeps its coarse contacts: 980 contacts ok in 12.3-14.3 min, seeds 2 and 3 in
// 90 s and 129 s, 233 contacts (load 3e-3) in 22 s instead of 43 s; the coarse solve takes 6-18 s
// of it and the solve 240-330 MB (one core, another solve on the other). At 2^20 seed 3's first
// round lost a contact again. The nine periodic 32000-sample profiles (seeds 1-3, loads 2e-3, 3e-3,
// 6e-3: 68-240 contacts) refine to 32 a sample at most (2^19 then bound) and are ok with the same
// contacts and C_f either way, in 155 s in all against 162 s.
constexpr std::size_t max_panels = std::size_t{1} << 21;
// A contact of fewer panels than this refines the grid on towards fine_panels. WHY 4: the contacts
// narrower than a sample on a rough profile have 1-3 panels at 8 a sample and need the finer grid
// (contact_set.cpp, seed_panels); at 16, the 50 cosine bumps' smallest contacts refined too (0.4 s
// became 2.0 s) and gained nothing.
constexpr std::size_t resolved_patch = 4;

}  // namespace

std::vector<coarse_patch> coarse_contacts(const profile_curve& curve, double load, const context& cx,
                                          std::size_t panels, std::size_t fine_panels, point_sources* sources) {
  const auto [lo, hi] = std::minmax_element(curve.z().begin(), curve.z().end());
  const double top = *hi, span = *hi - *lo;
  panels = std::clamp(panels, first_panels, max_panels);
  fine_panels = std::clamp(fine_panels, panels, max_panels);
  std::size_t n = first_panels;
  std::vector<char> active(n, 1);
  Eigen::VectorXd g;
  std::vector<std::size_t> idx;
  panel_grid gr;
  std::size_t steps = 0;
  warm_start ws;  // each solve starts from the last one
  for (;;) {
    gr = make_panel_grid(curve, n, cx, top);
    double D = 0;
    if (!settle(gr, load, span, active, g, idx, D, cx, steps, n == first_panels ? first_grid_steps : refined_grid_steps, ws)) return {};
    if (n >= panels) {
      std::size_t narrowest = n;
      for (const auto& [s, e] : runs_of(idx)) narrowest = std::min(narrowest, static_cast<std::size_t>(e - s));
      if (n >= fine_panels || narrowest >= resolved_patch) break;
    }
    const std::size_t next = std::min(4 * n, n < panels ? panels : fine_panels);
    active = refine_active(active, next);
    n = next;
  }
  if (sources) {
    *sources = {};
    for (std::size_t c = 0; c < idx.size(); ++c) {
      sources->t.push_back(gr.lo + gr.length * (static_cast<double>(idx[c]) + 0.5) * gr.h);
      sources->w.push_back(gr.h * g[static_cast<Eigen::Index>(c)]);
    }
  }
  std::vector<coarse_patch> out;
  for (const auto& [s, e] : runs_of(idx)) {
    coarse_patch p;
    p.a = gr.edge(idx[static_cast<std::size_t>(s)]);
    p.b = gr.edge(idx[static_cast<std::size_t>(e - 1)] + 1);
    p.load = gr.h * g.segment(s, e - s).sum();
    out.push_back(p);
  }
  return out;
}

}  // namespace rhabel::punch::detail
