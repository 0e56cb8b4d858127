// Deterministic noise for the virtual stage. std::normal_distribution (and every other
// std::*_distribution) is implementation-defined, so the same seed would give different files
// with libstdc++ and libc++. std::mt19937_64's output sequence is fixed by the standard; the
// Gaussian transform below uses only exact operations (a 53-bit integer scaled by 2^-53, and
// additions), so a seed gives bit-identical noise on every IEEE-754 machine.
#ifndef SYSID_SRC_STAGE_STAGE_NOISE_HPP_
#define SYSID_SRC_STAGE_STAGE_NOISE_HPP_

#include <cstdint>
#include <random>

namespace sysid::detail {

class StageNoise {
 public:
  explicit StageNoise(std::uint64_t seed) : engine_(seed) {}

  /// Uniform on [0, 1) with 53 random bits.
  double Uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }

  /// Approximately standard normal: Irwin-Hall sum of 12 uniforms minus 6. Mean 0, variance 1,
  /// excess kurtosis -0.1, bounded by +-6 (a sensor's noise has no infinite tails either).
  double Gaussian() {
    double s = 0;
    for (int i = 0; i < 12; ++i) s += Uniform();
    return s - 6.0;
  }

  /// Unbiased-enough index in [0, n) for shuffling (modulo bias < n / 2^64).
  std::uint64_t Index(std::uint64_t n) { return engine_() % n; }

 private:
  std::mt19937_64 engine_;
};

}  // namespace sysid::detail

#endif  // SYSID_SRC_STAGE_STAGE_NOISE_HPP_
