// The stack with an identified hysteresis model ahead of its mechanics (`sysid track --plant
// H.json`): the stack's own hysteresis as a model gives the stack back, sample for sample; a
// classical PI model runs as the rate-free stack whose slow response is the model's output;
// gpi and values no stack has are refused.
#include <catch2/catch.hpp>
#include <cmath>

#include "sysid/error.hpp"
#include "sysid/hysteresis.hpp"
#include "sysid/stack.hpp"

namespace sysid {
namespace {

TEST_CASE("stack with its own hysteresis as a model: the same plant", "[stack][plant]") {
  StackParameters base = StackParameters::Default();
  base.integrator.method = StackMethod::kExact;
  const StackParameters s = StackWithHysteresis(base, base.HysteresisPi(), "own.json");
  Eigen::VectorXd u(2000);
  for (Eigen::Index k = 0; k < u.size(); ++k) u[k] = 50 + 45 * std::sin(2 * M_PI * 20e-4 * k * 1.0);
  const StackRun a = RunStackOpenLoop(base, u, 3), b = RunStackOpenLoop(s, u, 3);
  CHECK((a.x_true_m - b.x_true_m).cwiseAbs().maxCoeff() == 0.0);
  CHECK(s.name == "piezo stack with the hysteresis of own.json");
}

TEST_CASE("stack with a classical PI model: a slow sweep follows the model", "[stack][plant]") {
  PiParameters p;
  p.form = PiForm::kClassical;
  p.thresholds = {10, 20, 30};
  p.weights = {0.05e-6, 0.04e-6, 0.03e-6};
  p.polynomial = {0.15e-6};
  p.input_min_v = 0;
  p.input_max_v = 100;
  StackParameters base = StackParameters::Default();
  base.integrator.method = StackMethod::kExact;
  base.creep = {};
  base.rig.sensor_noise_m = 0;
  base.rig.sensor_resolution_m = 1e-20;
  const StackParameters s = StackWithHysteresis(base, p, "pi.json");
  // 1 Hz against a 1 kHz resonance: the mechanics pass the hysteresis' output through (its
  // quasi-static error ~ (f / f_n)^2 and the lag 2 zeta / w_n per rate).
  const double ts = s.sample_time_s();
  Eigen::VectorXd u(static_cast<Eigen::Index>(1.0 / ts));
  for (Eigen::Index k = 0; k < u.size(); ++k)
    u[k] = 50 - 45 * std::cos(2 * M_PI * 1.0 * ts * static_cast<double>(k));
  const StackRun run = RunStackOpenLoop(s, u, 1);
  const Eigen::VectorXd y = PrandtlIshlinskiiModel(p).Simulate(u, ts);
  // x_(k+1) is the response to y_k held over a sample: behind it by the mechanics' lag
  // 2 zeta / w_n and half a sample, at most the steepest output rate times that; the DAC's
  // 16 bits over 140 V add 0.6 nm.
  const double lag = 2 * s.mechanics.damping_ratio / (2 * M_PI * s.mechanics.resonance_hz);
  const double slope = 0.27e-6 * 45 * 2 * M_PI;  // [m/s] the steepest output rate
  const Eigen::Index n = u.size() - 2001;
  const double worst = (run.x_true_m.tail(n) - y.segment(2000, n)).cwiseAbs().maxCoeff();
  INFO("max |x_(k+1) - y_k| = " << worst << " m, bound " << 1.5 * (lag + ts / 2) * slope + 1e-9);
  CHECK(worst < 1.5 * (lag + ts / 2) * slope + 1e-9);
  CHECK(worst > 0.2 * (lag + ts / 2) * slope);  // the lag is there: x is the mechanics' output
}

TEST_CASE("stack with a hysteresis model: gpi and negative weights refused", "[stack][plant]") {
  PiParameters p;
  p.form = PiForm::kPolynomial;
  p.thresholds = {10};
  p.weights = {0.1e-6};
  p.polynomial = {0.1e-6, 0, 1e-12};
  CHECK_THROWS_AS(StackWithHysteresis(StackParameters::Default(), p, "gpi.json"), OptionsError);
  p.form = PiForm::kClassical;
  p.polynomial = {0.1e-6};
  p.weights = {-0.1e-6};
  CHECK_THROWS_WITH(StackWithHysteresis(StackParameters::Default(), p, "neg.json"),
                    Catch::Contains("neg.json is not a stack's hysteresis"));
}

}  // namespace
}  // namespace sysid
