// Self-affine rough profiles for the punch tests and studies: the samples a profilometer gives of
// a randomly rough surface (issue: rough surfaces as users measure them).
//
// WHAT IT MAKES. n samples z_i at x_i = i/n (one unit of length, i = 0 .. n-1) of the periodic
// profile
//     z(x) = sum_{k=1}^{n/2} k^-(1/2 + H) cos(2 pi k x + phi_k),
// i.e. the power spectrum C(q) ~ q^-(1 + 2H) of a self-affine profile with Hurst exponent H, the
// phases phi_k uniform in [0, 2 pi) from std::mt19937_64(seed) (the top 53 bits of each draw, so
// the samples are the same on every platform), scaled to the rms height `rms` and shifted so that
// the highest sample is z = 0. The same construction as studies/scenes/self_affine_profile.py
// (which draws its phases with NumPy instead, so the two give other profiles for the same seed).
// Summed directly (O(n^2): 8e6 terms for n = 4000), no FFT: the test's oracle side shares nothing
// with the FFT of the product's coarse search.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

namespace punch_test {

struct sampled {
  std::vector<double> x, z;
};

inline constexpr double two_pi = 6.283185307179586476925286766559005768;

/// The modes k = 1 .. n/2 of self_affine: amplitude[k] = k^-(1/2 + H), phase[k] uniform in
/// [0, 2 pi) from std::mt19937_64(seed) (the top 53 bits of each draw); index 0 unused.
struct modes {
  std::vector<double> amplitude, phase;
};

inline modes self_affine_modes(std::size_t n, std::uint64_t seed, double hurst) {
  std::mt19937_64 rng(seed);
  modes m;
  m.amplitude.resize(n / 2 + 1);
  m.phase.resize(n / 2 + 1);
  for (std::size_t k = 1; k <= n / 2; ++k) {
    m.amplitude[k] = std::pow(static_cast<double>(k), -(0.5 + hurst));
    m.phase[k] = two_pi * static_cast<double>(rng() >> 11) * 0x1p-53;
  }
  return m;
}

/// The samples at x_i = i/n of z (summed however), scaled to the rms height `rms` and shifted so
/// that the highest sample is z = 0.
inline sampled on_unit_length(std::vector<double> z, double rms) {
  const std::size_t n = z.size();
  double sum = 0;
  for (const double v : z) sum += v * v;
  const double scale = rms / std::sqrt(sum / static_cast<double>(n));
  const double top = *std::max_element(z.begin(), z.end());
  sampled out;
  out.x.resize(n);
  for (std::size_t i = 0; i < n; ++i) out.x[i] = static_cast<double>(i) / static_cast<double>(n);
  for (double& v : z) v = (v - top) * scale;
  out.z = std::move(z);
  return out;
}

inline sampled self_affine(std::size_t n, std::uint64_t seed, double hurst = 0.8, double rms = 1e-3) {
  const modes m = self_affine_modes(n, seed, hurst);
  std::vector<double> z(n);
  for (std::size_t i = 0; i < n; ++i) {
    double sum = 0;
    for (std::size_t k = 1; k <= n / 2; ++k) {
      // The angle reduced exactly: (k i mod n)/n, so large k i costs no digits.
      const double turn = static_cast<double>((k * i) % n) / static_cast<double>(n);
      sum += m.amplitude[k] * std::cos(two_pi * turn + m.phase[k]);
    }
    z[i] = sum;
  }
  return on_unit_length(std::move(z), rms);
}

}  // namespace punch_test
