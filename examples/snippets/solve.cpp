// README example (C++): the scene of examples/snippets/scene.json built with rhabel::punch.
// Build: as the CTest test snippets.cpp does (target snippet_solve), or in your project after
// `cmake --install build --prefix PREFIX`:
//     find_package(rhabel 0.1 REQUIRED)
//     target_link_libraries(app PRIVATE rhabel::punch)
#include "rhabel/punch.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

int main() {
  using namespace rhabel::punch;
  scene s;
  s.material.alpha = 0.3;      // E(t) = E1 t^-alpha
  s.material.E1 = 1.0e6;       // Pa s^alpha
  s.material.poisson = 0.4;
  s.material.coulomb = 0.5;    // Coulomb coefficient k
  s.speed = 0.01;              // m/s, towards -x
  s.indentors.push_back({parabolic{0.02}, 100.0, 0.0});           // radius [m], load [N/m], apex [m]
  s.indentors.push_back({wedge{0.05, 0.08}, 50.0, 0.02});         // slopes ahead / behind the apex
  solve_options options;
  options.grid_points = 401;                                      // pressure and displacement samples

  const scene_result r = solve(s, options);
  std::printf("beta = %.6g, kappa = %.6g, regime %s, status %s\n", r.beta, r.kappa, to_string(r.regime),
              to_string(r.diagnostics.code));
  for (const indentor_result& ind : r.indentors) {
    char peak[64];
    if (std::isinf(ind.peak_pressure)) std::snprintf(peak, sizeof peak, "singular");
    else std::snprintf(peak, sizeof peak, "%.6g Pa", ind.peak_pressure);
    std::printf("%-9s contact [%.6g, %.6g] m, C_f = %.6g, C_f + k = %.6g, peak %s at %.6g m\n", to_string(ind.shape),
                ind.a, ind.b, ind.hysteretic_friction, ind.total_friction, peak, ind.peak_pressure_at);
    for (const edge_report& e : ind.edges)
      std::printf("    %-8s edge: p ~ K d^%.6g\n", e.side == edge_side::leading ? "leading" : "trailing", e.exponent);
  }
  const auto& p = r.indentors[0].pressure;  // p at r.indentors[0].grid_x, inside the contact
  std::printf("parabola pressure samples: %zu, max %.6g Pa\n", p.size(), *std::max_element(p.begin(), p.end()));
  const indentor_result& parabola = r.indentors[0];  // the solved pressure at points of one's own
  std::printf("parabola pressure at the contact's centre: %.6g Pa\n", parabola.pressure_at({(parabola.a + parabola.b) / 2})[0]);
}
