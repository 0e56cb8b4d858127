// NeuralNetwork evaluation and model files.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <string>
#include <vector>

#include "support/test_support.hpp"
#include "sysid/error.hpp"
#include "sysid/nn.hpp"

using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;

namespace {

sysid::NeuralNetwork SmallNet() {
  sysid::NeuralNetwork net({{"v", "m/s", -0.1, 0.1}, {"a", "m/s^2", -0.5, 1.5}},
                           {"u", "V", -3.0, 2.0}, 3);
  Eigen::VectorXd theta(13);
  theta << 0.5, -1.0, 2.0, 0.25, -0.7, 1.1,  // W1 rows (h0: 0.5 -1; h1: 2 0.25; h2: -0.7 1.1)
      0.1, -0.2, 0.3,                        // b1
      1.5, -0.5, 0.8,                        // w2
      -0.05;                                 // b2
  net.set_parameters(theta);
  return net;
}

// The network written out by hand from its definition (mapminmax in and out).
double ByHand(double v, double a) {
  const double zv = 2 * (v + 0.1) / 0.2 - 1, za = 2 * (a + 0.5) / 2.0 - 1;
  const double y = 1.5 * std::tanh(0.5 * zv - 1.0 * za + 0.1) +
                   -0.5 * std::tanh(2.0 * zv + 0.25 * za - 0.2) +
                   0.8 * std::tanh(-0.7 * zv + 1.1 * za + 0.3) - 0.05;
  return -3.0 + (y + 1) * 5.0 / 2;
}

}  // namespace

TEST_CASE("Evaluate and EvaluateBatch follow the definition", "[nn]") {
  const auto net = SmallNet();
  Eigen::MatrixXd X(700, 2);
  for (int k = 0; k < 700; ++k) X.row(k) << -0.12 + 0.24 * k / 699.0, std::sin(0.1 * k);
  const Eigen::VectorXd batch = net.EvaluateBatch(X);
  for (int k = 0; k < 700; ++k) {
    const double ref = ByHand(X(k, 0), X(k, 1));
    // Same arithmetic in a different order: a few ulps.
    CHECK(net.Evaluate(X.row(k).transpose()) == Approx(ref).margin(1e-13));
    CHECK(batch[k] == Approx(ref).margin(1e-13));
  }
  CHECK(net.parameter_count() == 13);
  CHECK(net.parameters() == SmallNet().parameters());
}

TEST_CASE("the constructor bounds the hidden size before allocating", "[nn]") {
  const std::vector<sysid::ScaledVariable> in{{"v", "m/s", -1.0, 1.0}};
  const sysid::ScaledVariable out{"u", "V", -1.0, 1.0};
  // 10^9 units would be 24 GB of weights: refused, naming the limit the CLI and files share.
  CHECK_THROWS_WITH(sysid::NeuralNetwork(in, out, 1000000000),
                    Contains("hidden = 1000000000. Violated constraint: 1 <= hidden <= 100000"));
  CHECK_THROWS_AS(sysid::NeuralNetwork(in, out, 0), sysid::OptionsError);
  CHECK(sysid::NeuralNetwork(in, out, sysid::kMaxHiddenUnits).hidden_size() == 100000);
}

TEST_CASE("model files round-trip exactly", "[nn][file]") {
  auto net = SmallNet();
  net.note = "hand-made";
  sysid::test::TempDir dir;
  sysid::WriteNeuralNetwork(dir / "n.json", net, R"({"epochs": 3})");
  const auto back = sysid::ReadNeuralNetwork(dir / "n.json");
  CHECK(back.parameters() == net.parameters());  // 17 significant digits survive JSON
  CHECK(back.input_names() == std::vector<std::string>{"v", "a"});
  CHECK(back.inputs()[1].unit == "m/s^2");
  CHECK(back.output().min == -3.0);
  CHECK(back.note == "hand-made");
}

TEST_CASE("model file errors name the place and the rule", "[nn][file]") {
  const std::string good = sysid::NeuralNetworkToJson(SmallNet());
  SECTION("syntax error: line and column") {
    std::string bad = good;
    bad.insert(bad.find("\"hidden\""), "oops ");
    try {
      sysid::ParseNeuralNetwork(bad, "net.json");
      FAIL("no error");
    } catch (const sysid::InputError& e) {
      // The inserted text starts at column 3 of the line that held "hidden".
      const std::string line = std::to_string(
          1 + std::count(good.begin(), good.begin() + static_cast<long>(good.find("\"hidden\"")),
                         '\n'));
      CHECK_THAT(e.what(), Contains("net.json:" + line + ":3: invalid JSON"));
    }
  }
  SECTION("unknown key") {
    std::string bad = good;
    bad.replace(bad.find("\"b2\""), 4, "\"b3\"");
    CHECK_THROWS_WITH(sysid::ParseNeuralNetwork(bad, "net.json"),
                      Contains("unknown key 'b3'") && Contains("net.json:"));
  }
  SECTION("wrong number of weights") {
    std::string bad = good;
    bad.replace(bad.find("\"hidden\": 3"), 11, "\"hidden\": 4");
    CHECK_THROWS_WITH(sysid::ParseNeuralNetwork(bad, "net.json"),
                      Contains(": W1: expected an array of 4 values, found an array of 3 values"));
  }
  SECTION("inverted range") {
    std::string bad = good;
    bad.replace(bad.find("\"max\": 2.0"), 10, "\"max\": -4.0");
    CHECK_THROWS_WITH(sysid::ParseNeuralNetwork(bad, "net.json"),
                      Contains(": output.max: expected a number > min (-3.0), max - min finite, "
                               "found -4.0"));
  }
  SECTION("not a number") {
    std::string bad = good;
    const size_t p = bad.find("\"b2\": ") + 6;
    bad.replace(p, bad.find('\n', p) - p, "\"x\"");
    CHECK_THROWS_WITH(sysid::ParseNeuralNetwork(bad, "net.json"),
                      Contains(": b2: expected a finite number, found string \"x\""));
  }
  SECTION("a hidden size past the bound is refused before allocation") {
    std::string bad = good;
    bad.replace(bad.find("\"hidden\": 3"), 11, "\"hidden\": 100000000");
    CHECK_THROWS_WITH(sysid::ParseNeuralNetwork(bad, "net.json"),
                      Contains(": hidden: expected an integer in [1, 100000], found 100000000"));
  }
  SECTION("a missing section is named") {
    std::string bad = good;
    bad.replace(bad.find("\"b1\""), 4, "\"_b1\"");
    CHECK_THROWS_WITH(sysid::ParseNeuralNetwork(bad, "net.json"),
                      StartsWith("net.json:1:1: missing required key 'b1'"));
  }
  SECTION("an element of an input variable") {
    std::string bad = good;
    bad.replace(bad.find("\"min\": "), 7, "\"min\": true, \"_x\": ");
    CHECK_THROWS_WITH(sysid::ParseNeuralNetwork(bad, "net.json"),
                      Contains(": inputs[0].min: expected a finite number, found true"));
  }
}
