#include "support/known_pi.hpp"

#include <cmath>

namespace sysid::test {

sysid::PiParameters KnownPiParameters() {
  sysid::PiParameters p;
  p.thresholds = {0.5, 1.0, 1.5};
  p.weights = {2e-6, 1e-6, 0.5e-6};
  p.polynomial = {4e-6};
  p.offset_m = -1e-4;
  p.input_min_v = 0;
  p.input_max_v = 3.6;
  return p;
}

sysid::Recording KnownPiRecording(const sysid::PiParameters& model, int n,
                                  const KnownPiDrive& drive) {
  const sysid::PrandtlIshlinskiiModel pi(model);
  Eigen::VectorXd u(n);
  for (int k = 0; k < n; ++k)
    u[k] = 1.8 + 1.7 * std::sin(2 * M_PI * k / drive.period_samples) *
                     (1 - drive.depth + drive.depth * std::cos(k / drive.envelope_samples));
  Eigen::VectorXd x = pi.Simulate(u, drive.sample_time_s);
  if (drive.noise_width_m > 0) {
    std::uint64_t state = drive.noise_seed;
    for (int k = 0; k < n; ++k) {  // Knuth's MMIX LCG: the same noise on every platform
      state = state * 6364136223846793005ULL + 1442695040888963407ULL;
      x[k] += drive.noise_width_m * (static_cast<double>(state >> 11) / 9007199254740992.0 - 0.5);
    }
  }
  sysid::Recording rec;
  rec.source = drive.source;
  rec.names = {"t", "u", "x"};
  rec.data.resize(n, 3);
  for (int k = 0; k < n; ++k) rec.data.row(k) << k * drive.sample_time_s, u[k], x[k];
  return rec;
}

}  // namespace sysid::test
