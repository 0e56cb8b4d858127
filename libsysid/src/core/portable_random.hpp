// The library's one random generator, for the virtual stage's noise and the networks'
// initialisations. Determinism across standard libraries: std::normal_distribution (and every
// other std::*_distribution) is implementation-defined, so the same seed would give different
// files with libstdc++ and libc++. std::mt19937_64's output sequence is fixed by the standard,
// and every transform below is written out here.
#ifndef SYSID_SRC_CORE_PORTABLE_RANDOM_HPP_
#define SYSID_SRC_CORE_PORTABLE_RANDOM_HPP_

#include <cmath>
#include <cstdint>
#include <random>

namespace sysid::internal {

class PortableRandom {
 public:
  explicit PortableRandom(std::uint64_t seed) : engine_(seed) {}

  /// Uniform on [0, 1) with 53 random bits.
  double Uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }

  /// Uniform on [-1, 1).
  double Symmetric() { return 2.0 * Uniform() - 1.0; }

  /// Approximately standard normal: Irwin-Hall sum of 12 uniforms minus 6. Mean 0, variance 1,
  /// excess kurtosis -0.1, bounded by +-6 (a sensor's noise has no infinite tails either).
  /// Only exact operations (a 53-bit integer scaled by 2^-53, and additions): bit-identical on
  /// every IEEE-754 machine, which the bundled datasets' byte-identical test relies on.
  double IrwinHallGaussian() {
    double s = 0;
    for (int i = 0; i < 12; ++i) s += Uniform();
    return s - 6.0;
  }

  /// Standard normal by Box-Muller (exact tails; log and cos round per libm, so the last bit
  /// may differ between C libraries).
  double Normal() {
    double u1 = 0;
    while (u1 <= 0) u1 = Uniform();
    const double u2 = Uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
  }

  /// Unbiased-enough index in [0, n) for shuffling (modulo bias < n / 2^64).
  std::uint64_t Index(std::uint64_t n) { return engine_() % n; }

 private:
  std::mt19937_64 engine_;
};

}  // namespace sysid::internal

#endif  // SYSID_SRC_CORE_PORTABLE_RANDOM_HPP_
