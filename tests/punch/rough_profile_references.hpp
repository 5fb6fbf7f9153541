// Reference values for test_rough_profile.cpp's periodic scenes of 4000 and 16000 samples,
// computed by the test suite's boundary-element oracle alone (bem_profile_oracle.hpp, which shares
// no code with rhabel) and committed here because the oracle takes minutes a scene: too long for
// the default test run. Regenerated and checked by test_rough_profile_reference.cpp (CTest label
// `long`):
//     ctest --test-dir build -R punch.test_rough_profile_reference -V
// The scene: punch_test::self_affine(samples, seed) as one period (period 1), alpha 0.3, nu 0, k 0,
// E1 = U = 1, load per period `load`; the oracle's options `reference_options` there.
#pragma once

#include <cstddef>
#include <cstdint>

namespace punch_test {

struct rough_reference {
  std::uint64_t seed;
  double load;          ///< per period (physical)
  std::size_t patches;  ///< the oracle's patches, the same on its last three levels
  double friction;      ///< the oracle's C_f of the body (extrapolated)
  double bar;           ///< its error bar (an estimate: Richardson's, plus the narrow patches' share)
  std::size_t samples = 4000;  ///< punch_test::self_affine(samples, seed)
};

// Measured (Release, one core of a shared 2-core machine): levels 4000 .. 1024000 panels, settled.
inline constexpr rough_reference rough_reference_seed4{4, 6e-3, 74, 0.0244682934, 1.24e-6};
inline constexpr rough_reference rough_reference_seed15{15, 6e-3, 86, 0.0215062673, 1.16e-6};
// Levels 16000 .. 4096000 panels (2^22), settled at friction_tol 5e-5; 9 min, the last level 6-7.
inline constexpr rough_reference rough_reference_16000_seed4{4, 2e-3, 60, 0.0322900805, 5.81e-6, 16000};

}  // namespace punch_test
