// The streaming analytic inverse against a hand-worked table (delay, direction-dependent a1
// and a2) and against the batch AnalyticInverse on the bundled tracking waveform.
#include <catch2/catch.hpp>
#include <cmath>

#include "sysid/compare.hpp"
#include "sysid/error.hpp"
#include "sysid/model_stepper.hpp"

namespace {

sysid::FrictionModel RoundModel(double tau_s) {
  sysid::FrictionModel m;
  m.a1p = 100;
  m.a1n = 120;
  m.a2p = 3;
  m.a2n = 7;
  m.a3 = 5;
  m.tau_s = tau_s;
  return m;
}

}  // namespace

TEST_CASE("friction inverse stepper: hand-worked table", "[model][stream]") {
  // dt = 0.5 s, tau = 1.25 s (2.5 samples): v(t_k - tau) = (v[k-2] + v[k-3]) / 2, v[j<0] = v[0].
  sysid::FrictionInverseStepper s(RoundModel(1.25), 0.5);
  struct Row {
    double v, a, u;
  };
  const Row rows[] = {
      {0.01, 0, 0.8},     // vd 0.01: (100*0.01 + 3) / 5
      {0.02, 0, 0.8},     // vd 0.01 (held)
      {0.03, 0, 0.8},     // vd (0.01 + 0.01) / 2
      {-0.01, 0, -1.1},   // vd 0.015, v < 0: (1.5 - 7) / 5
      {-0.02, 0, -0.9},   // vd 0.025: (2.5 - 7) / 5
      {-0.03, 2, -0.8},   // vd 0.01: (2 + 1 - 7) / 5
      {-0.03, 0, -1.76},  // vd -0.015, a1n: (-1.8 - 7) / 5
  };
  for (const auto& r : rows) {
    INFO("v = " << r.v);
    // Decimal data: a few roundings of numbers of order 1.
    CHECK(s.Step(r.v, r.a) == Approx(r.u).margin(1e-14));
  }
  s.Reset();
  CHECK(s.Step(0.01, 0) == Approx(0.8).margin(1e-14));
}

TEST_CASE("friction inverse stepper reproduces AnalyticInverse bit for bit", "[model][stream]") {
  const double dt = 1e-3;
  const int n = 4000;
  Eigen::VectorXd v(n), a(n);
  for (int k = 0; k < n; ++k) {
    const double t = k * dt;
    v[k] = 2e-3 * std::sin(2 * M_PI * t) + 1e-4 * std::sin(37 * t);
    a[k] = 2e-3 * 2 * M_PI * std::cos(2 * M_PI * t) + 37e-4 * std::cos(37 * t);
  }
  for (double tau : {0.0, 3.5e-3, 3.79e-3, 12e-3}) {
    sysid::FrictionModel m = sysid::FrictionModel::Paper();
    m.tau_s = tau;
    const Eigen::VectorXd batch = sysid::AnalyticInverse(m, dt, v, a);
    // The batch's reference: DelaySignal and InverseVoltage, the pre-stepper formula.
    const Eigen::VectorXd vd = sysid::DelaySignal(v, dt, tau);
    sysid::FrictionInverseStepper s(m, dt);
    for (int k = 0; k < n; ++k) {
      INFO("tau = " << tau << ", k = " << k);
      const double u = s.Step(v[k], a[k]);
      CHECK(u == batch[k]);
      CHECK(u == m.InverseVoltage(a[k], vd[k], v[k]));
    }
  }
}

TEST_CASE("friction inverse stepper refuses a bad model or step", "[model][stream]") {
  CHECK_THROWS_AS(sysid::FrictionInverseStepper(RoundModel(1e-3), 0.0), sysid::OptionsError);
  CHECK_THROWS_AS(sysid::FrictionInverseStepper(RoundModel(-1e-3), 1e-3), sysid::OptionsError);
  CHECK_THROWS_AS(sysid::FrictionInverseStepper(RoundModel(1e4), 1e-6), sysid::OptionsError);
}
