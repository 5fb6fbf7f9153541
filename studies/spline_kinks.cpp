// studies/spline_kinks.cpp: the density of one contact on a sampled profile, with and without the
// spline's knots built in (abel::solve_kinks against abel::solve, as the punch layer solves a
// contact's particular solution today).
//
// A sampled profile is a cubic spline: its slope F = z' is piecewise quadratic and F'' jumps at
// every sample (knot). The density of A g = F on a contact containing knots then converges only
// algebraically in its degree (docs/theory.md section 9), and a rough profile's contacts sit on
// tips, next to or around samples. abel::solve_kinks builds each knot in from its jump of z'''
// (docs/theory.md section 4). This study measures both on the contacts a rough profile has:
//   profile  self-affine, Hurst 0.8, rms 1e-3, n samples on [0, 1) (tests/punch/rough_profiles.hpp,
//            seeds 1-3), periodic natural cubic spline (GSL, as the punch layer's profile_curve);
//   contacts at every tip (a sample above both neighbours): [c - L/2, c + L/2] with the centre c
//            0.3 L past the tip (a contact is rarely centred on its tip), L = 0.1, 0.3, 1, 3, 10
//            sample spacings;
//   solve    alpha = 0.3, beta = 0, class nu = -1 (bounded at both edges: a profile's contact);
//            the data z'(s); residual switched off; tolerance (relative Chebyshev tail) 1e-10,
//            the accuracy a contact's particular solution needs for the edges' conditions at the
//            profile's acceptance 1e-6 (coupled_solve.cpp: 1e-3 of it);
//   plain    abel::solve up to 128, 512 and 2048 coefficients;
//   kinks    abel::solve_kinks with every knot inside the contact (order 2, the jump of z''').
// CSV (stdout): method, cap, length_spacings, contacts, mean_knots, reached (share with the tail
// <= tolerance), median_degree, max_degree, median_tail, max_tail, seconds_per_contact (the mean
// wall time of one solve). Usage: study_spline_kinks [samples = 4000].
#include "rhabel/abel.hpp"
#include "punch/rough_profiles.hpp"

#include <gsl/gsl_spline.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace {

using namespace rhabel::abel;

// The periodic natural cubic spline of the samples closed by (x_0 + 1, z_0): slope and the jump of
// z''' at each sample.
class periodic_spline {
 public:
  explicit periodic_spline(const punch_test::sampled& p) : x_(p.x), z_(p.z) {
    x_.push_back(x_.front() + 1);
    z_.push_back(z_.front());
    spline_ = gsl_spline_alloc(gsl_interp_cspline_periodic, x_.size());
    gsl_spline_init(spline_, x_.data(), z_.data(), x_.size());
    accel_ = gsl_interp_accel_alloc();
  }
  ~periodic_spline() {
    gsl_interp_accel_free(accel_);
    gsl_spline_free(spline_);
  }
  periodic_spline(const periodic_spline&) = delete;
  periodic_spline& operator=(const periodic_spline&) = delete;
  std::size_t samples() const { return x_.size() - 1; }
  double spacing() const { return x_[1] - x_[0]; }
  double x(long i) const {  // sample i, any integer (periodic)
    const long n = static_cast<long>(samples());
    const long k = ((i % n) + n) % n;
    return x_[static_cast<std::size_t>(k)] + static_cast<double>((i - k) / n);
  }
  double slope(double t) const { return gsl_spline_eval_deriv(spline_, reduce(t), accel_); }
  // z''' right of sample i minus left of it (z'' is linear between samples).
  double third_jump(long i) const { return third(i) - third(i - 1); }
  bool tip(long i) const { return value(i) > value(i - 1) && value(i) > value(i + 1); }

 private:
  double reduce(double t) const {
    double r = std::fmod(t - x_.front(), 1.0);
    if (r < 0) r += 1;
    return x_.front() + r;
  }
  double value(long i) const { return gsl_spline_eval(spline_, reduce(x(i)), accel_); }
  double second(long i) const { return gsl_spline_eval_deriv2(spline_, reduce(x(i)), accel_); }
  double third(long i) const { return (second(i + 1) - second(i)) / spacing(); }
  std::vector<double> x_, z_;
  gsl_spline* spline_ = nullptr;
  gsl_interp_accel* accel_ = nullptr;
};

struct tally {
  std::vector<double> degrees, tails;
  double seconds = 0, knots = 0;
  std::size_t reached = 0;
};

double median(std::vector<double> v) {
  if (v.empty()) return std::nan("");
  std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  const std::size_t n = argc > 1 ? std::stoul(argv[1]) : 4000;
  const double alpha = 0.3, beta = 0.0, tolerance = 1e-10;
  const std::vector<double> lengths{0.1, 0.3, 1, 3, 10};
  const std::vector<std::size_t> caps{128, 512, 2048};
  // tallies[length][method]: methods 0..2 plain at caps, 3 kinks
  std::vector<std::vector<tally>> tallies(lengths.size(), std::vector<tally>(caps.size() + 1));
  for (std::uint64_t seed : {1, 2, 3}) {
    const periodic_spline spline(punch_test::self_affine(n, seed));
    const double h = spline.spacing();
    auto F = [&](double s) { return spline.slope(s); };
    for (long i = 0; i < static_cast<long>(spline.samples()); ++i) {
      if (!spline.tip(i)) continue;
      for (std::size_t l = 0; l < lengths.size(); ++l) {
        const double L = lengths[l] * h, c = spline.x(i) + 0.3 * L;
        const double a = c - L / 2, b = c + L / 2;
        const abel_operator<double> op(alpha, beta, a, b);
        std::vector<kink<double>> kinks;
        for (long k = i - 20; k <= i + 20; ++k)
          if (spline.x(k) > a && spline.x(k) < b) kinks.push_back({spline.x(k), 2, spline.third_jump(k)});
        solve_options<double> o;
        o.residual_points = 0;
        o.tolerance = tolerance;
        for (std::size_t m = 0; m <= caps.size(); ++m) {
          tally& t = tallies[l][m];
          o.max_degree = (m < caps.size() ? caps[m] : caps.back()) + 1;
          const auto start = std::chrono::steady_clock::now();
          const auto sol = m < caps.size() ? solve(op, edge::bounded, edge::bounded, F, o)
                                           : solve_kinks(op, edge::bounded, edge::bounded, F, kinks, o).smooth;
          t.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
          t.degrees.push_back(static_cast<double>(sol.degree));
          t.tails.push_back(sol.coefficient_tail);
          t.reached += sol.coefficient_tail <= tolerance;
          t.knots += static_cast<double>(kinks.size());
        }
      }
    }
  }
  std::printf("method,cap,length_spacings,contacts,mean_knots,reached,median_degree,max_degree,median_tail,max_tail,"
              "seconds_per_contact\n");
  for (std::size_t l = 0; l < lengths.size(); ++l) {
    for (std::size_t m = 0; m <= caps.size(); ++m) {
      const tally& t = tallies[l][m];
      const double count = static_cast<double>(t.degrees.size());
      std::printf("%s,%zu,%g,%zu,%.2f,%.3f,%g,%g,%.2e,%.2e,%.2e\n", m < caps.size() ? "plain" : "kinks",
                  m < caps.size() ? caps[m] : caps.back(), lengths[l], t.degrees.size(), t.knots / count,
                  static_cast<double>(t.reached) / count, median(t.degrees),
                  *std::max_element(t.degrees.begin(), t.degrees.end()), median(t.tails),
                  *std::max_element(t.tails.begin(), t.tails.end()), t.seconds / count);
    }
  }
  return 0;
}
