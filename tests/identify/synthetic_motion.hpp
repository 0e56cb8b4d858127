// Test helper: recordings of the friction model built in closed form. Any smooth x(t) is a
// trajectory of  x'' = -a1 v(t - tau) - a2 sgn v + a3 u  when u is computed from the inverse
// model, so the truth is known exactly without a simulator.
#ifndef SYSID_TESTS_IDENTIFY_SYNTHETIC_MOTION_HPP_
#define SYSID_TESTS_IDENTIFY_SYNTHETIC_MOTION_HPP_

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "sysid/io.hpp"
#include "sysid/model.hpp"

namespace sysid::test {

struct Sine {
  double amplitude_m, frequency_hz, phase_rad;
};

/// x(t) = sum A sin(2 pi f t + phi), sampled at rate_hz for duration_s, x quantised to
/// quantum_m; u from the model's inverse plus N(0, u_noise_v^2) (seeded).
inline Recording ClosedFormRecording(const FrictionModel& m, const std::vector<Sine>& sines,
                                     double duration_s, double rate_hz, double quantum_m,
                                     double u_noise_v, unsigned seed) {
  const auto n = static_cast<Eigen::Index>(std::round(duration_s * rate_hz)) + 1;
  Eigen::MatrixXd data(n, 3);
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, u_noise_v);
  auto eval = [&](double t, int deriv) {
    double s = 0;
    for (const auto& c : sines) {
      const double w = 2 * M_PI * c.frequency_hz, ph = w * t + c.phase_rad;
      s += deriv == 0   ? c.amplitude_m * std::sin(ph)
           : deriv == 1 ? c.amplitude_m * w * std::cos(ph)
                        : -c.amplitude_m * w * w * std::sin(ph);
    }
    return s;
  };
  for (Eigen::Index k = 0; k < n; ++k) {
    const double t = static_cast<double>(k) / rate_hz;
    const double x = eval(t, 0), v = eval(t, 1), a = eval(t, 2), vd = eval(t - m.tau_s, 1);
    const double a1 = vd > 0 ? m.a1p : m.a1n;
    const double a2 = v > 0 ? m.a2p : (v < 0 ? -m.a2n : 0.0);
    data(k, 0) = t;
    data(k, 1) = (a + a1 * vd + a2) / m.a3 + (u_noise_v > 0 ? noise(rng) : 0.0);
    data(k, 2) = quantum_m > 0 ? quantum_m * std::round(x / quantum_m) : x;
  }
  Recording r;
  r.source = "closed-form";
  r.names = {"t", "u", "x"};
  r.data = data;
  return r;
}

}  // namespace sysid::test

#endif  // SYSID_TESTS_IDENTIFY_SYNTHETIC_MOTION_HPP_
