// A recording of a known classical Prandtl-Ishlinskii model: the fixture of the tests that fit,
// invert or score a PI model and must recover the model they were given.
#ifndef SYSID_TESTS_SUPPORT_KNOWN_PI_HPP_
#define SYSID_TESTS_SUPPORT_KNOWN_PI_HPP_

#include <cstdint>
#include <string>

#include "sysid/hysteresis.hpp"
#include "sysid/io.hpp"

namespace sysid::test {

/// Three operators (0.5, 1, 1.5 V), a cubic term and an offset, on 0-3.6 V: x of order 10 um.
sysid::PiParameters KnownPiParameters();

/// The drive: decaying loops u = 1.8 + 1.7 sin(2 pi k / period) (1 - depth + depth cos(k / envelope))
/// [V], so that every operator reverses at several amplitudes; noise on x is uniform with the
/// given peak-to-peak width [m] from a seeded LCG (0: none).
struct KnownPiDrive {
  double period_samples = 400;
  double envelope_samples = 900;
  double depth = 0.4;
  double sample_time_s = 5e-3;  ///< [s] 200 Hz, as the bundled piezo recording
  double noise_width_m = 0;
  std::uint64_t noise_seed = 12345;
  std::string source;  ///< Recording::source
};

/// t [s], u [V], x [m] of `model` driven by `drive` for n samples.
sysid::Recording KnownPiRecording(const sysid::PiParameters& model, int n,
                                  const KnownPiDrive& drive = {});

}  // namespace sysid::test

#endif  // SYSID_TESTS_SUPPORT_KNOWN_PI_HPP_
