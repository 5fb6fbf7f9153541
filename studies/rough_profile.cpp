// study_rough_profile: self-affine rough profiles, the workload most users bring: work-precision of
// rhabel's boundary-element solver (rhabel/punch/profile_bem.hpp), its spectral contact search
// (rhabel/punch/profile.hpp, finite windows and periodic), and the usual boundary-element method a user would
// write (the punch tests' oracle, tests/punch/bem_profile_oracle.hpp: dense blocks, its own
// splines and Richardson bars), side by side.
//
// PROFILES. n samples on [0, 1) of a self-affine profile (Hurst 0.8, rms 1e-3, highest sample at
// 0; tests/punch/rough_profiles.hpp's construction: amplitudes k^-(1/2 + H), phases from
// std::mt19937_64(seed); summed directly up to 16000 samples, by Eigen's FFT above), alpha 0.3,
// nu 0, E1 = U = 1, loads per unit length 5e-4, 3e-3, 2e-2 (about 5, 20 and 100 patches at 1000
// samples), seeds 1, 2, 3; periodic (period 1) and finite windows.
//
// ROWS (CSV on stdout): samples,seed,load,mode,method,setting,status,patches,Cf,Cf_error,
//   err_Cf,seconds,panels
//   method rhabel_bem      setting = acceptance 1e-3 .. 1e-6 (time limit 60 s)
//   method rhabel_spectral up to 16000 samples, finite and periodic, acceptance 1e-6, tolerance
//                          1e-10 (Cf_error empty: its evidence is the residual of (8), not a C_f bar)
//   method bem_oracle      up to 4000 samples (its default options: C_f bar < 1e-4 max |z'|)
//   err_Cf = |Cf - reference|, the reference being the value with the smallest error estimate
//   among the ok rows of the scene (empty when there is none). A refused finite window (contacts
//   at the end of the samples) is a row with status "refused".
// OPTIONS: --quick (1000 samples, seed 1), --samples N[,N...] (default 1000,4000,16000,100000),
// --seeds S[,S...] (default 1,2,3), --no-oracle.
#include "rhabel/punch.hpp"

#include "bem_profile_oracle.hpp"
#include "rough_profiles.hpp"

#include <unsupported/Eigen/FFT>

#include <chrono>
#include <cmath>
#include <complex>
#include <cstdint>
#include <cstdio>
#include <iostream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace {
namespace pu = rhabel::punch;
namespace bp = punch_test::bem_profile;

/// rough_profiles.hpp's profile by FFT (its modes; rounding aside the same samples).
punch_test::sampled self_affine_fft(std::size_t n, std::uint64_t seed, double hurst = 0.8, double rms = 1e-3) {
  const punch_test::modes m = punch_test::self_affine_modes(n, seed, hurst);
  // z_i = sum_k a_k cos(2 pi k i/n + phi_k) = Re sum_k a_k e^{i phi_k} e^{2 pi i k i/n}
  std::vector<std::complex<double>> spectrum(n, 0.0);
  for (std::size_t k = 1; k <= n / 2; ++k) spectrum[k] += m.amplitude[k] * std::polar(1.0, m.phase[k]);
  Eigen::FFT<double> fft;
  std::vector<std::complex<double>> z;
  fft.inv(z, spectrum);  // (1/n) sum_k spectrum_k e^{2 pi i k i/n}
  std::vector<double> real(n);
  for (std::size_t i = 0; i < n; ++i) real[i] = z[i].real() * static_cast<double>(n);
  return punch_test::on_unit_length(std::move(real), rms);
}

struct row {
  std::string method, setting, status;
  std::size_t patches = 0, panels = 0;
  double cf = std::numeric_limits<double>::quiet_NaN(), cf_error = std::numeric_limits<double>::quiet_NaN();
  double seconds = 0;
  bool ok = false;
};

std::string cell(double v) {
  if (!std::isfinite(v)) return "";
  std::ostringstream os;
  os.precision(10);
  os << v;
  return os.str();
}

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::size_t> sizes{1000, 4000, 16000, 100000};
  std::vector<std::uint64_t> seeds{1, 2, 3};
  bool oracle = true;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--quick") sizes = {1000}, seeds = {1};
    else if (a == "--no-oracle") oracle = false;
    else if (a == "--samples" && i + 1 < argc) {
      sizes.clear();
      std::stringstream ss(argv[++i]);
      for (std::string t; std::getline(ss, t, ',');) sizes.push_back(std::stoul(t));
    } else if (a == "--seeds" && i + 1 < argc) {
      seeds.clear();
      std::stringstream ss(argv[++i]);
      for (std::string t; std::getline(ss, t, ',');) seeds.push_back(std::stoull(t));
    } else {
      std::cerr << "usage: study_rough_profile [--quick] [--samples N,N...] [--seeds S,S...] [--no-oracle]\n";
      return 2;
    }
  }
  std::cout << "samples,seed,load,mode,method,setting,status,patches,Cf,Cf_error,err_Cf,seconds,panels\n";
  for (const std::size_t n : sizes)
    for (const std::uint64_t seed : seeds)
      for (const double load : {5e-4, 3e-3, 2e-2})
        for (const bool periodic : {true, false}) {
          const auto samples = n <= 16000 ? punch_test::self_affine(n, seed) : self_affine_fft(n, seed);
          pu::profile_scene s;
          s.material.alpha = 0.3;
          s.profile.x = samples.x;
          s.profile.z = samples.z;
          s.profile.period = periodic ? 1.0 : 0.0;
          s.load = load;
          std::vector<row> rows;
          for (const double acceptance : {1e-3, 1e-4, 1e-5, 1e-6}) {
            row r;
            r.method = "rhabel_bem";
            r.setting = cell(acceptance);
            pu::solve_options o;
            o.acceptance = acceptance;
            o.time_limit = 60;
            const auto t0 = std::chrono::steady_clock::now();
            try {
              const auto res = pu::solve_profile_bem(s, o);
              r.seconds = seconds_since(t0);
              r.status = pu::to_string(res.diagnostics.code);
              r.ok = res.diagnostics.code == pu::status_code::ok;
              r.patches = res.patches.size();
              r.cf = res.hysteretic_friction.value;
              r.cf_error = res.hysteretic_friction.error;
              r.panels = res.diagnostics.panels;
            } catch (const std::domain_error&) {
              r.seconds = seconds_since(t0);
              r.status = "refused";
            }
            rows.push_back(r);
            std::cerr << n << " seed " << seed << " P " << load << (periodic ? " periodic" : " finite") << " bem "
                      << acceptance << ": " << r.status << " " << r.patches << " patches C_f " << r.cf << " +- "
                      << r.cf_error << " " << r.seconds << " s, " << r.panels << " panels\n";
            if (r.status == "refused" || r.seconds > 30) break;
          }
          if (n <= 16000) {
            row r;
            r.method = "rhabel_spectral";
            r.setting = "1e-06";
            pu::solve_options o;
            o.acceptance = 1e-6;
            o.tolerance = 1e-10;
            o.time_limit = 60;
            const auto t0 = std::chrono::steady_clock::now();
            try {
              const auto res = pu::solve_profile(s, o);
              r.status = pu::to_string(res.diagnostics.code);
              r.ok = res.diagnostics.code == pu::status_code::ok;
              r.patches = res.contacts.size();
              r.cf = res.hysteretic_friction;
            } catch (const std::domain_error&) {
              r.status = "refused";
            }
            r.seconds = seconds_since(t0);
            rows.push_back(r);
          }
          if (oracle && n <= 4000) {
            row r;
            r.method = "bem_oracle";
            const auto t0 = std::chrono::steady_clock::now();
            const auto res = bp::solve(bp::make_scene_physical(samples.x, samples.z, 1, 0.3, 0, 0, 1, load, s.profile.period),
                                       bp::options{});
            r.seconds = seconds_since(t0);
            r.ok = res.converged && !res.touches_end;
            r.status = res.touches_end ? "touches_end" : res.converged ? "ok" : "not_converged";
            r.patches = res.patches.size();
            r.cf = res.friction.value;
            r.cf_error = res.friction.error;
            r.panels = res.panels.empty() ? 0 : static_cast<std::size_t>(res.panels.back());
            rows.push_back(r);
          }
          // The reference: the ok row with the smallest error estimate.
          double reference = std::numeric_limits<double>::quiet_NaN(), best = std::numeric_limits<double>::infinity();
          for (const row& r : rows)
            if (r.ok && std::isfinite(r.cf_error) && r.cf_error < best) best = r.cf_error, reference = r.cf;
          for (const row& r : rows)
            std::cout << n << ',' << seed << ',' << cell(load) << ',' << (periodic ? "periodic" : "finite") << ','
                      << r.method << ',' << r.setting << ',' << r.status << ',' << r.patches << ',' << cell(r.cf) << ','
                      << cell(r.cf_error) << ',' << cell(std::abs(r.cf - reference)) << ',' << cell(r.seconds) << ','
                      << (r.panels ? std::to_string(r.panels) : "") << '\n'
                      << std::flush;
        }
  return 0;
}
