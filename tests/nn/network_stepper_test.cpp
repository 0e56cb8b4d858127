// The network stepper against the definition written out by hand and against Evaluate.
#include <catch2/catch.hpp>
#include <cmath>

#include "sysid/error.hpp"
#include "sysid/nn_stepper.hpp"

TEST_CASE("network stepper: the definition, and Evaluate bit for bit", "[nn][stream]") {
  sysid::NeuralNetwork net({{"v", "m/s", -0.1, 0.1}, {"a", "m/s^2", -0.5, 1.5}},
                           {"u", "V", -3.0, 2.0}, 2);
  Eigen::VectorXd theta(9);
  theta << 0.5, -1.0, 2.0, 0.25, 0.1, -0.2, 1.5, -0.5, -0.05;
  net.set_parameters(theta);
  sysid::NetworkStepper s(net);
  CHECK(s.input_count() == 2);
  for (int k = 0; k < 200; ++k) {
    const double x[2] = {-0.12 + 0.24 * k / 199.0, std::sin(0.1 * k)};
    const double zv = 2 * (x[0] + 0.1) / 0.2 - 1, za = 2 * (x[1] + 0.5) / 2.0 - 1;
    const double y = 1.5 * std::tanh(0.5 * zv - 1.0 * za + 0.1) -
                     0.5 * std::tanh(2.0 * zv + 0.25 * za - 0.2) - 0.05;
    const double u = s.Step(x);
    // Same operations in another order: a few ulps of the 5 V output span.
    CHECK(u == Approx(-3.0 + (y + 1) * 2.5).margin(1e-13));
    CHECK(u == net.Evaluate(Eigen::Vector2d(x[0], x[1])));
  }
}

TEST_CASE("network stepper refuses non-finite weights", "[nn][stream]") {
  sysid::NeuralNetwork net({{"v", "m/s", -1, 1}}, {"u", "V", -1, 1}, 1);
  Eigen::VectorXd theta(4);
  theta << 1, 0, NAN, 0;
  net.set_parameters(theta);
  CHECK_THROWS_AS(sysid::NetworkStepper(net), sysid::OptionsError);
}
