// What the drive's hysteresis and creep tests share: the command sequence, the ceramic they
// drive and the effective voltage written out from the hysteresis module's play operator.
#ifndef SYSID_TESTS_STAGE_DRIVE_REFERENCE_HPP_
#define SYSID_TESTS_STAGE_DRIVE_REFERENCE_HPP_

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <vector>

#include "sysid/hysteresis.hpp"
#include "sysid/stage.hpp"

namespace sysid::test {

// Pulses, a slow and a fast triangle, a sinusoid with reversals and a hold: rises, falls and
// minor loops at several rates [V], one value per sample.
inline std::vector<double> Commands(int n) {
  std::vector<double> u(static_cast<size_t>(n), 0.0);
  for (int k = 0; k < n; ++k) {
    const double t = k / static_cast<double>(n);
    double v = 0;
    if (t < 0.15) v = t < 0.05 ? 0 : (t < 0.1 ? 2.0 : -2.3);
    else if (t < 0.4) v = 1.8 * std::sin(2 * M_PI * (t - 0.15) / 0.25);             // slow
    else if (t < 0.55) v = 1.6 * std::sin(2 * M_PI * (t - 0.4) / 0.05) - 0.3;        // fast
    else if (t < 0.8) v = 0.4 * std::sin(2 * M_PI * (t - 0.55) / 0.03) + 1.45;       // minor
    else v = t < 0.9 ? -2.0 : 1.5;
    u[static_cast<size_t>(k)] = v;
  }
  return u;
}

// [m/s] The true velocity after the held-pulse run the drive tests compare plateaus with:
// 0.3 s at 2 V against u's direction, 0.3 s at 0 V, then u [V] held 1.2 s (1800 samples of a
// 1 kHz control loop), from 4 cm on the side u moves away from; `noisy` false zeroes the
// position noise.
inline double HeldPulseVelocity(sysid::StageParameters p, double u, bool noisy) {
  std::vector<double> cmd(300, u > 0 ? -2.0 : 2.0);
  cmd.resize(600, 0.0);
  cmd.resize(1800, u);
  const Eigen::Map<const Eigen::VectorXd> command(cmd.data(), 1800);
  p.rig.initial_position_m = u > 0 ? -0.04 : 0.04;
  if (!noisy) p.rig.position_noise_m = 0;
  return sysid::RunOpenLoop(p, command, 1).v_true_mps[1799];
}

inline sysid::DriveHysteresis Ceramic(double alpha, double rate_weight, double tau) {
  sysid::DriveHysteresis h;
  h.thresholds_v = {0.05, 0.12, 0.25};
  h.weights = {0.15, 0.1, 0.2};
  h.rate_weights_s_per_v = {rate_weight, 0.0, 2 * rate_weight};
  h.rate_time_constant_s = tau;
  h.asymmetry = alpha;
  return h;
}

// The effective voltage written out from the module's play operator (whole sequence at once)
// and the documented rate filter.
inline std::vector<double> Reference(const sysid::DriveHysteresis& h, const std::vector<double>& u,
                                     double ts) {
  const Eigen::VectorXd in = Eigen::Map<const Eigen::VectorXd>(u.data(), static_cast<long>(u.size()));
  std::vector<Eigen::VectorXd> f;
  for (double r : h.thresholds_v)
    f.push_back(sysid::PlayOperator(in.array() - h.asymmetry * r, r, 0.0));
  double wsum = 0, ssum = 0;
  for (double w : h.weights) wsum += w;
  for (double s : h.rate_weights_s_per_v) ssum += s;
  const double rho_sat = ssum > 0 ? (1 - wsum) / ssum : 1e300;
  const double b = h.rate_time_constant_s > 0 ? 1 - std::exp(-ts / h.rate_time_constant_s) : 1;
  std::vector<double> out(u.size());
  double q = 0, prev = 0;
  for (size_t k = 0; k < u.size(); ++k) {
    q += b * ((u[k] - prev) / ts - q);
    prev = u[k];
    const double rho = std::min(std::abs(q), rho_sat);
    double y = u[k];
    for (size_t i = 0; i < f.size(); ++i)
      y -= (h.weights[i] + h.rate_weights_s_per_v[i] * rho) * (u[k] - f[i][static_cast<long>(k)]);
    out[k] = y;
  }
  return out;
}

}  // namespace sysid::test

#endif  // SYSID_TESTS_STAGE_DRIVE_REFERENCE_HPP_
