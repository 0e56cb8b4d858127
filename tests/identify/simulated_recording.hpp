// Test helper: pulse-test recordings made with the simulator, sampled like a real rig
// (1 kHz, encoder quantum 0.1 um, seeded position noise).
#ifndef SYSID_TESTS_IDENTIFY_SIMULATED_RECORDING_HPP_
#define SYSID_TESTS_IDENTIFY_SIMULATED_RECORDING_HPP_

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "sysid/input.hpp"
#include "sysid/io.hpp"
#include "sysid/simulate.hpp"

namespace sysid::test {

struct RigSampling {
  double rate_hz = 1000.0;
  double quantum_m = 1e-7;  ///< encoder resolution
  double noise_m = 5e-8;    ///< position noise before quantisation (sd)
  unsigned seed = 1;
};

/// Simulates `model` under `input` on [0, duration_s] and records t, u, x like a rig. As from a
/// DAC, the stage is driven by the zero-order hold of the recorded samples u_k = input(t_k), so
/// the recorded u is exactly what was applied (no edge falls between samples).
inline Recording RigRecording(const FrictionModel& model, const InputSignal& input,
                              double duration_s, const RigSampling& s,
                              const std::string& name = "simulated") {
  const auto n = static_cast<size_t>(std::round(duration_s * s.rate_hz)) + 1;
  std::vector<double> tk(n), uk(n);
  for (size_t k = 0; k < n; ++k) {
    tk[k] = static_cast<double>(k) / s.rate_hz;
    uk[k] = input.Value(tk[k]);
  }
  const PiecewiseConstantInput dac(tk, uk);
  SimulationOptions o;
  o.t_end_s = tk.back();
  o.output_times_s = tk;
  o.rtol = 1e-9;
  o.atol = 1e-12;
  const SimulationResult r = Simulate(model, dac, o);
  if (!r.summary.IsSolutionUsable()) throw std::runtime_error("test simulation failed: " + r.summary.message);
  const auto& tr = r.trajectory;
  std::mt19937 rng(s.seed);
  std::normal_distribution<double> noise(0.0, s.noise_m);
  Recording rec;
  rec.source = name;
  rec.names = {"t", "u", "x"};
  rec.data.resize(tr.t_s.size(), 3);
  for (Eigen::Index k = 0; k < tr.t_s.size(); ++k) {
    const double x = tr.x_m[k] + (s.noise_m > 0 ? noise(rng) : 0.0);
    rec.data(k, 0) = tr.t_s[k];
    rec.data(k, 1) = tr.u_v[k];
    rec.data(k, 2) = s.quantum_m > 0 ? s.quantum_m * std::round(x / s.quantum_m) : x;
  }
  return rec;
}

inline FrictionModel MakeModel(double a1p, double a1n, double a2p, double a2n, double a3,
                               double tau_s) {
  FrictionModel m;
  m.a1p = a1p;
  m.a1n = a1n;
  m.a2p = a2p;
  m.a2n = a2n;
  m.a3 = a3;
  m.tau_s = tau_s;
  return m;
}

}  // namespace sysid::test

#endif  // SYSID_TESTS_IDENTIFY_SIMULATED_RECORDING_HPP_
