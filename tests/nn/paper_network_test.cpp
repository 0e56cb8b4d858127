// The paper's published 24-neuron network (datasets/paper/nn24.json) against the paper's own
// analytic inverse u = (a1 v + a2 sgn v) / 6 (a = 0, steady sliding), computed here from the
// printed coefficients.
#include <catch2/catch.hpp>
#include <cmath>

#include "support/test_support.hpp"
#include "sysid/nn.hpp"

namespace {

double AnalyticInverse(double v) {
  const double a1 = v > 0 ? 104.0154 : 117.1441, a2 = v > 0 ? 3.1023 : 6.8216;
  return (a1 * v + a2 * ((v > 0) - (v < 0))) / 6.0;
}

}  // namespace

TEST_CASE("the paper's 24-neuron network loads and matches the analytic inverse", "[nn][paper]") {
  const auto net = sysid::ReadNeuralNetwork(sysid::test::SourcePath("datasets/paper/nn24.json"));
  REQUIRE(net.hidden_size() == 24);
  REQUIRE(net.input_names() == std::vector<std::string>{"v"});
  // Spot checks of the transcription against the paper's printed values.
  CHECK(net.W1()(0, 0) == -35.3468);
  CHECK(net.W1()(23, 0) == 36.3986);
  CHECK(net.b1()[10] == 0.00042311);
  CHECK(net.w2()[11] == -85.532);
  CHECK(net.b2() == 0.0072113);

  double sum2 = 0, worst_sliding = 0;
  int count = 0;
  for (int k = -1000; k <= 1000; ++k) {
    const double v = 1e-4 * k;  // [m/s], the stage's range
    const double d = net.Evaluate(Eigen::VectorXd::Constant(1, v)) - AnalyticInverse(v);
    sum2 += d * d;
    ++count;
    if (std::abs(v) >= 0.01) worst_sliding = std::max(worst_sliding, std::abs(d));
  }
  const double rms = std::sqrt(sum2 / count);
  // The inferred scaling leaves 0.1331 V RMS (the network models the real stage, which the
  // rough analytic model does not match exactly). Regression bound, not a reference: the value
  // depends only on the printed weights and the scaling, so 0.14 V (+5 %) fails for any change
  // of either (a wrong scaling gives > 1 V, below).
  CHECK(rms < 0.14);
  // Away from the Coulomb step (|v| >= 0.01 m/s) the two agree within 0.296 V (bound 0.31 V,
  // +5 % as above).
  CHECK(worst_sliding < 0.31);
  // The Coulomb step itself: +0.517 V just above 0 and -1.137 V just below, within 0.1 V.
  CHECK(net.Evaluate(Eigen::VectorXd::Constant(1, 1e-3)) == Approx(0.534).margin(0.1));
  CHECK(net.Evaluate(Eigen::VectorXd::Constant(1, -1e-3)) == Approx(-1.156).margin(0.1));

  // The scaling matters: the same weights fed raw velocity [m/s] with the output in volts
  // disagree by more than 1 V RMS.
  sysid::NeuralNetwork raw({{"v", "m/s", -1.0, 1.0}}, {"u", "V", -1.0, 1.0}, 24);
  raw.set_parameters(net.parameters());
  double raw2 = 0;
  for (int k = -1000; k <= 1000; ++k) {
    const double v = 1e-4 * k;
    const double d = raw.Evaluate(Eigen::VectorXd::Constant(1, v)) - AnalyticInverse(v);
    raw2 += d * d;
  }
  CHECK(std::sqrt(raw2 / count) > 1.0);
}
