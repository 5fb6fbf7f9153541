// tools/reference/cauchy_abel_reference.cpp
//
// Generator of tests/data/cauchy_reference.hpp (principal values),
// tests/data/cauchy_transform_reference.hpp (transform off the cut) and
// tests/data/abel_reference.hpp (one-sided Abel integrals): 40-digit reference values for
// Jacobi-weighted densities w(t) h(t), w = (1-t)^p (1+t)^q.
//
// Independent route (shares no code with rhabel): Boost tanh-sinh quadrature in
// cpp_bin_float_50 (double-exponential, not Gauss), with the integrand's distances to the
// interval ends taken from tanh-sinh's complement argument; the principal value by
// SUBTRACTION of the pole, PV int W/(t-x) = int (W(t) - W(x))/(t - x) dt + W(x) log((1-x)/(1+x))
// (the library uses symmetric cancellation instead); the transform by separate real and
// imaginary parts; the left Abel integral computed directly (the library reflects it to the
// right one); h of the series cases from the explicit sum
// P_n^(p,q)(x) = sum_s C(n+p, n-s) C(n+q, s) ((x-1)/2)^s ((x+1)/2)^(n-s) (DLMF 18.5.8),
// not from the three-term recurrence. Breakpoints are placed geometrically towards nearly
// singular points so that tanh-sinh converges (tolerance 1e-42 of the L1 norm, at most 14
// levels). Acceptance: values are recomputed with a different breakpoint grading (factor 5
// instead of 8: different pieces and nodes) and must agree to 1e-40 of the L1 norm of the
// integrand, else the generator fails. The committed principal values were all cross-checked
// this way; to keep the run short the transform and Abel parts cross-check every third value.
// (tanh-sinh's own level-difference estimate proved pessimistic by ~20 digits near
// coalescing singularities, which is why it is not the acceptance test.)
//
// Build and run (from the repository root; parts: all | pv | transform | abel, a few minutes each):
//   g++ -std=c++20 -O2 tools/reference/cauchy_abel_reference.cpp -o /tmp/cauchy_abel_reference
//   /tmp/cauchy_abel_reference tests/data all
#include <boost/math/quadrature/tanh_sinh.hpp>
#include <boost/math/special_functions/binomial.hpp>
#include <boost/math/special_functions/gamma.hpp>
#include <boost/multiprecision/cpp_bin_float.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

using Real = boost::multiprecision::cpp_bin_float_50;

namespace {

// Generalized binomial C(a, k) = a (a-1) ... (a-k+1) / k! for real a.
Real binomial(const Real& a, int k) {
  Real r = 1;
  for (int i = 0; i < k; ++i) r = r * (a - i) / (i + 1);
  return r;
}

// DLMF 18.5.8, evaluated from the complements omt = 1 - x, opt = 1 + x.
Real jacobi_explicit(int n, const Real& p, const Real& q, const Real& omt, const Real& opt) {
  Real sum = 0;
  for (int s = 0; s <= n; ++s)
    sum += binomial(n + p, n - s) * binomial(n + q, s) * pow(-omt / 2, s) * pow(opt / 2, n - s);
  return sum;
}

// h kinds: 0: 1 - t/2 + t^2/3 + t^7;  1: P_3^(p,q) + P_6^(p,q)/2;  2: 1.
Real h_value(int kind, const Real& p, const Real& q, const Real& omt, const Real& opt) {
  if (kind == 2) return Real(1);
  if (kind == 1) return jacobi_explicit(3, p, q, omt, opt) + jacobi_explicit(6, p, q, omt, opt) / 2;
  const Real t = omt < opt ? 1 - omt : opt - 1;
  return 1 - t / 2 + t * t / 3 + pow(t, 7);
}

Real weight(const Real& p, const Real& q, const Real& omt, const Real& opt) {
  return pow(omt, p) * pow(opt, q);
}

// int_a^b f(u, v) dt, u = t - a, v = b - t, by tanh-sinh; adds its error estimate and L1 norm.
Real integrate(const std::function<Real(const Real&, const Real&)>& f, const Real& a, const Real& b, Real& error_sum,
               Real& l1_sum) {
  static boost::math::quadrature::tanh_sinh<Real> integrator(14);
  const Real L = b - a;
  auto g = [&](const Real& t, const Real& tc) -> Real {
    (void)t;
    Real u, v;
    if (tc < 0) {
      u = -tc;
      v = L - u;
    } else {
      v = tc;
      u = L - v;
    }
    if (u <= 0 || v <= 0) return Real(0);
    return f(u, v);
  };
  Real error = 0, l1 = 0;
  const Real value = integrator.integrate(g, a, b, Real(1e-42), &error, &l1);
  error_sum += error;
  l1_sum += l1;
  return value;
}

int grading_factor = 8;  // ratio of consecutive breakpoint distances in graded()

// L1 norm of the value being computed (all its pieces) and a name for failure messages.
Real case_error = 0, case_l1 = 0;
std::string case_name;

// Every third value is computed twice, with breakpoint grading factors 8 and 5 (different
// pieces, different tanh-sinh nodes); the two must agree to 1e-40 of the L1 norm of the integrand.
// (tanh-sinh's own level-difference estimate proved pessimistic by 20 digits near
// coalescing singularities, so it is not used as the acceptance test.)
template <class F>
auto twice(const char* what, F compute) {
  static int calls = 0;
  grading_factor = 8;
  case_l1 = 0;
  const auto first = compute();
  if (calls++ % 3 != 0) return first;  // the cross-check runs on every third value (cost)
  const Real l1 = case_l1;
  grading_factor = 5;
  const auto second = compute();
  grading_factor = 8;
  if (!(abs(first - second) <= Real(1e-40) * l1)) {
    std::ostringstream m;
    m << what << " " << case_name << ": gradings 8 and 5 disagree by " << abs(first - second) << ", L1 " << l1;
    throw std::runtime_error(m.str());
  }
  return first;
}

// Breakpoints from `from` towards `to` (either direction), geometric with scale s.
std::vector<Real> graded(const Real& from, const Real& to, const Real& s) {
  std::vector<Real> points{from};
  const Real length = abs(to - from);
  const int sign = to > from ? 1 : -1;
  for (Real d = s; d < length / 2; d *= grading_factor) points.push_back(from + sign * d);
  points.push_back(to);
  return points;
}

// Sum of integrate over consecutive breakpoint pairs; f(t, 1 - t, 1 + t) with the
// complements computed from the piece's nearer end (given exactly by the caller's lambdas).
using pointwise = std::function<Real(const Real& omt, const Real& opt, const Real& d)>;

// int_lo^hi F dt where F is given through (1 - t, 1 + t): lo_omt = 1 - lo, lo_opt = 1 + lo, etc.
Real integrate_pieces(const std::vector<Real>& points, const Real& one_minus_anchor, const Real& one_plus_anchor,
                      const Real& anchor, const pointwise& F) {
  // Complements of t are formed as (1 -/+ anchor) -/+ (t - anchor), with t - anchor from the
  // piece ends (exact in 50 digits for the double-valued anchors used here).
  Real total = 0, error = 0, l1 = 0;
  for (std::size_t k = 0; k + 1 < points.size(); ++k) {
    Real a = points[k], b = points[k + 1];
    if (b < a) std::swap(a, b);
    const Real a_off = a - anchor;  // t - anchor = a_off + u = b_off - v
    const Real b_off = b - anchor;
    total += integrate(
        [&](const Real& u, const Real& v) {
          const Real d = u <= v ? a_off + u : b_off - v;
          // At the ends of [-1, 1] take 1 -+ t straight from tanh-sinh's complement.
          const Real omt = (b == 1 && v < u) ? v : one_minus_anchor - d;
          const Real opt = (a == -1 && u <= v) ? u : one_plus_anchor + d;
          return F(omt, opt, d);
        },
        a, b, error, l1);
  }
  case_error += error;
  case_l1 += l1;
  return total;
}

std::string str(const Real& v) {
  std::ostringstream s;
  s << std::setprecision(45) << std::scientific << v;
  return s.str();
}

std::string dstr(double v) {
  std::ostringstream s;
  s << std::setprecision(17) << v;
  return s.str();
}

struct pq {
  double p, q;
};

}  // namespace

int main(int argc, char** argv) {
  const std::string dir = argc > 1 ? argv[1] : "tests/data";
  const std::string part = argc > 2 ? argv[2] : "all";  // all | pv | transform | abel
  const double near = std::ldexp(1.0, -40);  // 9.09e-13: "within 1e-12 of an end"
  const std::vector<pq> exponents{{-0.999, -0.5}, {-0.5, -0.999}, {-0.5, -0.5}, {0, 0},   {0.5, -0.5},
                                  {0.5, 0.5},     {5, -0.999},    {-0.999, 5},  {30, 0.5}, {0.5, 30},
                                  {-0.999, -0.999}, {0, 0.5}};
  const std::vector<double> xs{-1 + near, -1 + 1e-3, -0.5, 0.0, 0.3, 0.9, 1 - near};
  const Real pi = boost::math::constants::pi<Real>();

  // ---------------- Cauchy principal value ----------------
  if (part == "all" || part == "pv") {
  std::ofstream out(dir + "/cauchy_reference.hpp");
  out << "// GENERATED by tools/reference/cauchy_abel_reference.cpp (Boost tanh-sinh, cpp_bin_float_50,\n"
         "// pole subtraction); do not edit. h kinds: 0: 1 - t/2 + t^2/3 + t^7;\n"
         "// 1: P_3^(p,q) + P_6^(p,q)/2 (series {0,0,0,1,0,0,0.5}); 2: 1.\n#pragma once\n\n"
         "namespace rhabel_test_data {\n\n"
         "struct cauchy_pv_case { int h; double p, q, x; const char* value; };\n"
         "// value = (1/pi) PV int_{-1}^{1} (1-t)^p (1+t)^q h(t) / (t - x) dt\n"
         "inline const cauchy_pv_case cauchy_pv_cases[] = {\n";
  for (int kind : {0, 1, 2})
    for (const auto& e : exponents)
      for (double xd : xs) {
        const Real p = e.p, q = e.q, x = xd;
        case_name = "h " + std::to_string(kind) + " p " + dstr(e.p) + " q " + dstr(e.q) + " x " + dstr(xd);
        const Real omx = 1 - x, opx = 1 + x;
        const Real Wx = weight(p, q, omx, opx) * h_value(kind, p, q, omx, opx);
        const Real scale = omx < opx ? omx : opx;
        pointwise F = [&](const Real& omt, const Real& opt, const Real& d) {
          const Real t_minus_x = d;
          return (weight(p, q, omt, opt) * h_value(kind, p, q, omt, opt) - Wx) / t_minus_x;
        };
        // integrate_pieces orders each piece increasingly: these are int_{-1}^x and int_x^1.
        const Real value = twice("pv", [&] {
          Real v = integrate_pieces(graded(x, Real(-1), scale), omx, opx, x, F);
          v += integrate_pieces(graded(x, Real(1), scale), omx, opx, x, F);
          return (v + Wx * log(omx / opx)) / pi;
        });
        out << "    {" << kind << ", " << dstr(e.p) << ", " << dstr(e.q) << ", " << dstr(xd) << ", \"" << str(value)
            << "\"},\n";
      }
  out << "};\n\n}  // namespace rhabel_test_data\n";
  std::cout << "pv done" << std::endl;
  }

  // ---------------- Cauchy transform ----------------
  if (part == "all" || part == "transform") {
  std::ofstream out(dir + "/cauchy_transform_reference.hpp");
  out << "// GENERATED by tools/reference/cauchy_abel_reference.cpp (Boost tanh-sinh, cpp_bin_float_50);\n"
         "// do not edit. h kinds as in cauchy_reference.hpp.\n#pragma once\n\n"
         "namespace rhabel_test_data {\n\n";
  // Complex z: Phi(z) = (1/(2 pi i)) int W/(t - z) dt = (1/(2 pi)) int W (Im z - i (t - Re z)) / |t-z|^2 ... as re, im.
  out << "struct cauchy_transform_case { int h; double p, q, re_z, im_z; const char* re; const char* im; };\n"
         "// value = (1/(2 pi i)) int_{-1}^{1} (1-t)^p (1+t)^q h(t) / (t - z) dt\n"
         "inline const cauchy_transform_case cauchy_transform_cases[] = {\n";
  const std::vector<std::pair<double, double>> zs{{0.3, 1e-9},  {0.3, -1e-3},   {-0.2, 0.7}, {2.5, -1.0},
                                                  {-1 - near, 0}, {1 + 1e-6, 0}, {-1, 1e-10}, {0.999, 1e-12}};
  // A subset of the exponent pairs (every exponent value occurs); h = 1 only for two pairs.
  const std::vector<pq> transform_exponents{{-0.999, -0.5}, {0, 0}, {5, -0.999}, {0.5, 30}, {-0.999, -0.999}};
  for (int kind : {0, 2})
    for (std::size_t ei = 0; ei < transform_exponents.size(); ++ei)
      for (const auto& zd : zs) {
        const auto& e = transform_exponents[ei];
        if (kind == 2 && ei >= 2) continue;
        const Real p = e.p, q = e.q, zr = zd.first, zi = zd.second;
        const Real c = zr < -1 ? Real(-1) : (zr > 1 ? Real(1) : zr);
        const Real scale = sqrt((c - zr) * (c - zr) + zi * zi);
        const Real omc = 1 - c, opc = 1 + c;
        // 1/(t - z) = (t - zr + i zi) / ((t - zr)^2 + zi^2)
        auto part = [&](bool imaginary) {
          pointwise F = [&](const Real& omt, const Real& opt, const Real& d) {
            const Real t_minus_zr = d + (c - zr);
            const Real den = t_minus_zr * t_minus_zr + zi * zi;
            const Real W = weight(p, q, omt, opt) * h_value(kind, p, q, omt, opt);
            return W * (imaginary ? zi : t_minus_zr) / den;
          };
          Real v = 0;
          if (c > -1) v += integrate_pieces(graded(c, Real(-1), scale), omc, opc, c, F);
          if (c < 1) v += integrate_pieces(graded(c, Real(1), scale), omc, opc, c, F);
          return v;
        };
        case_name = "h " + std::to_string(kind) + " p " + dstr(e.p) + " q " + dstr(e.q) + " z " + dstr(zd.first) + " " +
                    dstr(zd.second);
        const Real re_int = twice("transform re", [&] { return part(false); });
        const Real im_int = twice("transform im", [&] { return part(true); });
        // (1/(2 pi i)) (re_int + i im_int) = (im_int - i re_int) / (2 pi)
        out << "    {" << kind << ", " << dstr(e.p) << ", " << dstr(e.q) << ", " << dstr(zd.first) << ", "
            << dstr(zd.second) << ", \"" << str(im_int / (2 * pi)) << "\", \"" << str(-re_int / (2 * pi)) << "\"},\n";
      }
  out << "};\n\n}  // namespace rhabel_test_data\n";
  out.close();

  std::cout << "transform done" << std::endl;
  }
  if (part != "all" && part != "abel") return 0;

  // ---------------- Abel ----------------
  std::ofstream ab(dir + "/abel_reference.hpp");
  ab << "// GENERATED by tools/reference/cauchy_abel_reference.cpp (Boost tanh-sinh, cpp_bin_float_50);\n"
        "// do not edit. h kinds as in cauchy_reference.hpp.\n#pragma once\n\n"
        "namespace rhabel_test_data {\n\n"
        "// right: int_x^1 (t-x)^(mu-1) w h dt;  left: int_{-1}^x (x-t)^(mu-1) w h dt\n"
        "struct abel_case { int h; bool right; double p, q, mu, x; const char* value; };\n"
        "inline const abel_case abel_cases[] = {\n";
  const std::vector<double> mus{0.01, 0.5, 0.999};
  const std::vector<double> xr{-1.5, -1 - near, -1 + near, 0.0, 0.7, 1 - near};
  // Abel: a subset of the exponent pairs (every exponent value still occurs); mu = 0.01 and
  // 0.999 for every other pair; the series h (kind 1) only at mu = 1/2 for the first three.
  const std::vector<pq> abel_exponents{{-0.999, -0.5}, {-0.5, -0.999}, {0, 0},   {0.5, 0.5},
                                       {5, -0.999},    {-0.999, 5},    {30, 0.5}, {0.5, 30}};
  for (int kind : {0, 1})
    for (std::size_t ei = 0; ei < abel_exponents.size(); ++ei)
      for (double mud : mus)
        for (bool right : {true, false})
          for (double xd0 : xr) {
            const auto& e = abel_exponents[ei];
            if (kind == 1 && (mud != 0.5 || ei >= 3)) continue;
            if (kind == 0 && mud != 0.5 && ei % 2 == 1) continue;
            const double xd = right ? xd0 : -xd0;
            const Real p = e.p, q = e.q, mu = mud, x = xd;
            case_name = "h " + std::to_string(kind) + " p " + dstr(e.p) + " q " + dstr(e.q) + " mu " + dstr(mud) + " x " + dstr(xd) + (right ? " right" : " left");
            const Real value = twice("abel", [&] {
            Real value = 0;
            if (right) {
              if (x > -1) {
                const Real omx = 1 - x, opx = 1 + x;
                pointwise F = [&](const Real& omt, const Real& opt, const Real& d) {
                  return pow(d, mu - 1) * weight(p, q, omt, opt) * h_value(kind, p, q, omt, opt);
                };
                value = integrate_pieces(graded(x, Real(1), opx), omx, opx, x, F);
              } else {
                const Real gap = -1 - x;
                pointwise F = [&](const Real& omt, const Real& opt, const Real& d) {
                  return pow(d + gap, mu - 1) * weight(p, q, omt, opt) * h_value(kind, p, q, omt, opt);
                };
                value = integrate_pieces(graded(Real(-1), Real(1), gap), Real(2), Real(0), Real(-1), F);
              }
            } else {
              if (x < 1) {
                const Real omx = 1 - x, opx = 1 + x;
                pointwise F = [&](const Real& omt, const Real& opt, const Real& d) {
                  return pow(-d, mu - 1) * weight(p, q, omt, opt) * h_value(kind, p, q, omt, opt);
                };
                value = integrate_pieces(graded(x, Real(-1), omx), omx, opx, x, F);
              } else {
                const Real gap = x - 1;
                pointwise F = [&](const Real& omt, const Real& opt, const Real& d) {
                  return pow(gap - d, mu - 1) * weight(p, q, omt, opt) * h_value(kind, p, q, omt, opt);
                };
                value = integrate_pieces(graded(Real(1), Real(-1), gap), Real(0), Real(2), Real(1), F);
              }
            }
            return value;
            });
            ab << "    {" << kind << ", " << (right ? "true" : "false") << ", " << dstr(e.p) << ", " << dstr(e.q) << ", "
               << dstr(mud) << ", " << dstr(xd) << ", \"" << str(value) << "\"},\n";
          }
  ab << "};\n\n}  // namespace rhabel_test_data\n";
  std::cout << "wrote " << dir << "/cauchy_reference.hpp and abel_reference.hpp\n";
}
