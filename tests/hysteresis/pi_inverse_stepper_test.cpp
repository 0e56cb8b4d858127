// The streaming Prandtl–Ishlinskii inverses against a hand-worked table (one play operator),
// against the forward model (Simulate of the stepper's output gives the reference back) and
// against the batch Invert.
#include <catch2/catch.hpp>
#include <cmath>

#include "support/known_pi.hpp"
#include "sysid/error.hpp"
#include "sysid/hysteresis_stepper.hpp"

namespace {

Eigen::VectorXd Loops(int n) {
  Eigen::VectorXd u(n);
  for (int k = 0; k < n; ++k)
    u[k] = 1.8 + 1.6 * std::sin(2 * M_PI * k / 300.0) * (0.6 + 0.4 * std::cos(k / 500.0));
  return u;
}

}  // namespace

TEST_CASE("pi inverse stepper: hand-worked table", "[hysteresis][stream]") {
  // y = u + F_1[u] from rest at 0; its inverse u = y - 0.5 F'_1[y] (Kuhnen: r' = 1, w' = -1/2).
  sysid::PiParameters p;
  p.thresholds = {1.0};
  p.weights = {1.0};
  p.polynomial = {1.0};
  p.input_min_v = -1;
  p.input_max_v = 3;
  sysid::PiInverseStepper s(sysid::PrandtlIshlinskiiModel(p), 1e-3);
  // y = 1: the operator has not moved, u = 1; y = 3: it moves, 2u - 1 = 3; back to y = 2: the
  // operator holds 1, u + 1 = 2; y = 0.5: it moves down, 2u + 1 = 0.5.
  const double y[] = {1, 3, 2, 0.5}, u[] = {1, 2, 1, -0.25};
  for (int k = 0; k < 4; ++k) CHECK(s.Step(y[k]) == u[k]);  // exact in binary
  CHECK_FALSE(s.saturation().saturated);
  // Beyond the range widened by 5 %: clamped to it and said.
  CHECK(s.Step(100) == Approx(3.2));
  CHECK(s.saturation().saturated);
}

TEST_CASE("pi, gpi and rdpi inverse steppers give the forward model's reference back and are "
          "Invert",
          "[hysteresis][stream]") {
  sysid::PiParameters pi = sysid::test::KnownPiParameters();
  sysid::PiParameters gpi = pi;
  gpi.form = sysid::PiForm::kPolynomial;
  gpi.polynomial = {4e-6, 0.0, 2e-8};
  sysid::PiParameters rd = pi;
  rd.form = sysid::PiForm::kRateDependent;
  rd.rate_weights = {1e-9, 2e-9, 0.0, 1e-9};  // error gain 4e-9 * 3.78 / (5e-3 * 4e-6) = 0.76
  const double dt = 5e-3;
  const Eigen::VectorXd u_true = Loops(1500);
  for (const auto& p : {pi, gpi, rd}) {
    const sysid::PrandtlIshlinskiiModel m(p);
    INFO(m.kind());
    const Eigen::VectorXd x = m.Simulate(u_true, dt);
    const Eigen::VectorXd batch = m.Invert(x, dt);
    sysid::PiInverseStepper s(m, dt);
    Eigen::VectorXd u(x.size());
    for (Eigen::Index k = 0; k < x.size(); ++k) u[k] = s.Step(x[k]);
    CHECK(u == batch);
    // The forward model's own rounding over slopes >= p0 = 4e-6 m/V: 1e-9 V; the closed form
    // and the bisection land far closer.
    CHECK((u - u_true).cwiseAbs().maxCoeff() <= 1e-9);
    s.Reset();
    CHECK(s.Step(x[0]) == u[0]);
  }
}
