// The operator-input network's inverse stepper against its definition (play operators of x by
// PlayOperator, then the network) and against the batch Invert.
#include <catch2/catch.hpp>
#include <cmath>

#include "sysid/hysteresis.hpp"
#include "sysid/nn_stepper.hpp"

namespace {

sysid::OperatorNetworkSide Side(double in_min, double in_max, double out_min, double out_max) {
  sysid::OperatorNetworkSide s;
  s.thresholds = {0.1 * (in_max - in_min), 0.3 * (in_max - in_min)};
  s.initial_input = in_min;
  s.network = sysid::NeuralNetwork({{"x", "m", in_min, in_max}, {"F1", "m", in_min, in_max},
                                    {"F2", "m", in_min, in_max}},
                                   {"u", "V", out_min, out_max}, 4);
  s.network.set_parameters(
      Eigen::VectorXd::LinSpaced(s.network.parameter_count(), -1.3, 1.1).array().sin());
  return s;
}

}  // namespace

TEST_CASE("nn-operators inverse stepper: the definition, and Invert", "[nn][stream]") {
  const sysid::OperatorNetworkModel model(Side(0, 3.6, 0, 1e-5), Side(0, 1e-5, 0, 3.6));
  const int n = 800;
  Eigen::VectorXd x(n);
  for (int k = 0; k < n; ++k) x[k] = 5e-6 + 4e-6 * std::sin(k / 40.0) * std::cos(k / 170.0);
  const sysid::OperatorNetworkSide& inv = model.inverse();
  const Eigen::VectorXd f1 = sysid::PlayOperator(x, inv.thresholds[0], inv.initial_input);
  const Eigen::VectorXd f2 = sysid::PlayOperator(x, inv.thresholds[1], inv.initial_input);
  const Eigen::VectorXd batch = model.Invert(x, 1e-3);
  sysid::OperatorNetworkInverseStepper s(model);
  for (int k = 0; k < n; ++k) {
    const double u = s.Step(x[k]);
    CHECK_FALSE(s.saturated());
    CHECK(u == inv.network.Evaluate(Eigen::Vector3d(x[k], f1[k], f2[k])));
    // EvaluateBatch sums in Eigen's order: a few ulps of the 3.6 V span.
    CHECK(u == Approx(batch[k]).margin(1e-13));
  }
  s.Reset();
  CHECK(s.Step(x[0]) == inv.network.Evaluate(Eigen::Vector3d(x[0], f1[0], f2[0])));
  s.Step(1.0);  // 1 m: far outside the widened range
  CHECK(s.saturated());
}
