// Regression test of the committed tables of docs/tables.md (docs/tables/exponents.csv, wedge.csv,
// parabola.csv): every value is recomputed with rhabel::punch::solve (studies/support/tables.hpp, the
// code the study study_tables writes them with) and compared with the committed one. A change of the
// solver that moves a tabulated value beyond the tolerances below fails here; if the change is
// deliberate, regenerate the tables (build/bin/study_tables docs, from the source directory) and
// commit them with it. The measured exponents are also compared with the theoretical ones
// (docs/theory.md section 3), the parabola with its closed forms (section 5).
#include <doctest/doctest.h>

#include "../../studies/support/tables.hpp"

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace {

// A refit of the same grid moves a fitted exponent by ~1e-13 under rounding-level changes of the
// density; 1e-6 catches any change of the solution near a singular point that matters.
constexpr double exponent_moved_tol = 1e-6;
// Bias of the local fit over d in [1e-5 L, 1e-3 L] (the terms of the local expansion beyond those in
// the fit): measured <= 2.9e-5 at the wedge's apex (alpha = 0.1, beta = 0.3), <= 2.6e-6 at every edge.
constexpr double exponent_theory_tol = 1e-4;
// eps and L come from the incomplete-beta condition and the load in closed form (1e-15 measured);
// the parabola's b/L, L and C_f from a root finder polished to 1e-12 (solve_options::tolerance).
constexpr double closed_form_moved_tol = 1e-12;
// The wedge's C_f below the boundary: a quadrature of the enriched density, accurate to <= 1e-12
// (docs/accuracy.md); 1e-10 leaves room for rounding-level changes and catches real ones.
constexpr double wedge_cf_moved_tol = 1e-10;

using table = std::vector<std::map<std::string, std::string>>;

table read_csv(const std::string& name) {
  const std::string path = std::string(RHABEL_SOURCE_DIR) + "/docs/tables/" + name;
  std::ifstream in(path);
  REQUIRE_MESSAGE(in.good(), "cannot read " << path);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> header;
  {
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) header.push_back(cell);
  }
  table rows;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    std::stringstream ss(line);
    std::string cell;
    std::map<std::string, std::string> row;
    for (const auto& h : header) {
      if (!std::getline(ss, cell, ',')) cell.clear();
      row[h] = cell;
    }
    rows.push_back(row);
  }
  return rows;
}

double value(const std::map<std::string, std::string>& row, const std::string& key) {
  const auto it = row.find(key);
  if (it == row.end() || it->second.empty()) return rhabel_tables::nan;
  return std::stod(it->second);
}

double rel(double a, double b) { return std::abs(a - b) / std::max(std::abs(b), 1e-300); }

}  // namespace

TEST_CASE("exponent table: measured edge and apex exponents have not moved and match the theory") {
  const auto committed = read_csv("exponents.csv");
  const auto now = rhabel_tables::exponent_table();
  REQUIRE(committed.size() == now.size());
  for (std::size_t i = 0; i < now.size(); ++i) {
    const auto& r = now[i];
    const auto& c = committed[i];
    INFO(r.shape << " alpha = " << r.alpha << " beta = " << r.beta << " " << r.point);
    CHECK(c.at("shape") == r.shape);
    CHECK(c.at("point") == r.point);
    CHECK(c.at("regime") == r.regime);
    CHECK(value(c, "alpha") == r.alpha);
    CHECK(value(c, "beta") == r.beta);
    const double was = value(c, "measured");
    if (std::isnan(r.measured)) {
      CHECK(std::isnan(was));  // line load both times
      continue;
    }
    CHECK(r.status == "ok");
    CHECK(std::abs(r.measured - was) <= exponent_moved_tol);
    CHECK(std::abs(r.measured - r.theory) <= exponent_theory_tol);
  }
}

TEST_CASE("wedge table: eps, L and C_f against alpha have not moved") {
  const auto committed = read_csv("wedge.csv");
  std::size_t i = 0;
  for (double beta : rhabel_tables::table_betas())
    for (double alpha : rhabel_tables::table_alphas()) {
      REQUIRE(i < committed.size());
      const auto& c = committed[i++];
      const auto w = rhabel_tables::wedge_values(alpha, beta);
      INFO("wedge alpha = " << alpha << " beta = " << beta);
      CHECK(value(c, "alpha") == alpha);
      CHECK(value(c, "beta") == beta);
      CHECK(c.at("regime") == w.regime);
      CHECK(w.status == "ok");
      CHECK(rel(w.eps, value(c, "eps")) <= closed_form_moved_tol);
      CHECK(rel(w.L, value(c, "L")) <= closed_form_moved_tol);
      CHECK(std::abs(w.Cf - value(c, "Cf_over_S1")) <= wedge_cf_moved_tol);  // C_f / S1 in [0, 1]: absolute
      if (w.regime != "below") {  // contact ends at the apex: eps = 1, C_f = S1 (docs/theory.md section 5)
        CHECK(w.eps == 1.0);
        CHECK(std::abs(w.Cf - 1.0) <= closed_form_moved_tol);
      }
    }
  CHECK(i == committed.size());
}

TEST_CASE("parabola table: b/L, L and C_f against alpha have not moved and match the closed forms") {
  const auto committed = read_csv("parabola.csv");
  std::size_t i = 0;
  for (double beta : rhabel_tables::table_betas())
    for (double alpha : rhabel_tables::table_alphas()) {
      REQUIRE(i < committed.size());
      const auto& c = committed[i++];
      const auto p = rhabel_tables::parabola_values(alpha, beta);
      INFO("parabola alpha = " << alpha << " beta = " << beta);
      CHECK(value(c, "alpha") == alpha);
      CHECK(value(c, "beta") == beta);
      CHECK(p.status == "ok");
      // b/L may vanish (alpha + beta/2 = 1/2): compared absolutely.
      CHECK(std::abs(p.b_over_L - value(c, "b_over_L")) <= closed_form_moved_tol);
      CHECK(std::abs(p.b_over_L - p.b_over_L_closed) <= closed_form_moved_tol);
      CHECK(rel(p.L, value(c, "L")) <= closed_form_moved_tol);
      CHECK(rel(p.L, p.L_closed) <= closed_form_moved_tol);
      if (alpha + beta > 0) {
        CHECK(rel(p.CfR_over_L, value(c, "CfR_over_L")) <= closed_form_moved_tol);
        CHECK(rel(p.CfR_over_L, p.CfR_over_L_closed) <= closed_form_moved_tol);
      } else {
        CHECK(std::abs(p.CfR_over_L) <= closed_form_moved_tol);  // elastic, frictionless: C_f = 0
      }
    }
  CHECK(i == committed.size());
}
