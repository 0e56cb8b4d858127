// prediction.cpp: PredictColumn evaluates the network row by row, counts extrapolating rows and
// scores against the true output; `sysid predict --json` prints the library's summary.
#include <catch2/catch.hpp>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "support/test_support.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"
#include "sysid/nn.hpp"

namespace {
sysid::NeuralNetwork SmallNet() {
  sysid::NeuralNetwork net({{"v", "m/s", -0.1, 0.1}}, {"u", "V", -10, 10}, 3);
  net.set_parameters(Eigen::VectorXd::LinSpaced(net.parameter_count(), -0.8, 0.9));
  return net;
}

sysid::Recording Data(bool with_output) {
  sysid::Recording rec;
  rec.source = "data.csv";
  Eigen::VectorXd v(4), u(4);
  v << -0.2, -0.05, 0.05, 0.15;  // rows 0 and 3 lie outside [-0.1, 0.1]
  u << 1.0, -2.0, 0.5, 3.0;
  rec.SetColumn("t", Eigen::VectorXd::LinSpaced(4, 0.0, 0.003));
  rec.SetColumn("v", v);
  if (with_output) rec.SetColumn("u", u);
  return rec;
}
}  // namespace

TEST_CASE("PredictColumn evaluates, counts extrapolation and scores", "[nn][predict]") {
  const auto net = SmallNet();
  sysid::Recording rec = Data(true);
  const sysid::NetworkPrediction p = sysid::PredictColumn(net, rec);
  CHECK(p.column == "u_nn");
  CHECK(p.rows == 4);
  CHECK(p.rows_outside_input_range == 2);
  // The reference: one Evaluate per row and the mean of squared errors by hand.
  double sse = 0;
  for (Eigen::Index k = 0; k < 4; ++k) {
    const double y = net.Evaluate(Eigen::VectorXd::Constant(1, rec.column("v")[k]));
    CHECK(rec.column("u_nn")[k] == Approx(y).epsilon(1e-14));
    sse += (y - rec.column("u")[k]) * (y - rec.column("u")[k]);
  }
  CHECK(p.mse == Approx(sse / 4).epsilon(1e-13));
  const auto j = nlohmann::json::parse(sysid::ToJson(p));
  CHECK(j["rows"] == 4);
  CHECK(j["column"] == "u_nn");
  CHECK(j["rows_outside_input_range"] == 2);
  CHECK(j["mse"].get<double>() == p.mse);

  // Without the true output there is no MSE (NaN, and no key).
  sysid::Recording bare = Data(false);
  const auto q = sysid::PredictColumn(net, bare, "u_hat");
  CHECK(std::isnan(q.mse));
  CHECK(bare.has("u_hat"));
  CHECK_FALSE(nlohmann::json::parse(sysid::ToJson(q)).contains("mse"));
}

TEST_CASE("PredictColumn refuses to overwrite and names missing inputs", "[nn][predict]") {
  const auto net = SmallNet();
  sysid::Recording rec = Data(true);
  CHECK_THROWS_AS(sysid::PredictColumn(net, rec, "u"), sysid::OptionsError);
  rec.SetColumn("u_nn", Eigen::VectorXd::Zero(4));
  CHECK_THROWS_WITH(sysid::PredictColumn(net, rec),
                    Catch::Contains("'u_nn' would overwrite a column of data.csv"));
  CHECK_NOTHROW(sysid::PredictColumn(net, rec, "u_nn"));  // chosen by name: replaced
  sysid::Recording other;
  other.source = "x.csv";
  other.SetColumn("a", Eigen::VectorXd::Zero(2));
  CHECK_THROWS_WITH(sysid::PredictColumn(net, other),
                    Catch::Contains("x.csv: no column 'v' (a network input)"));
}

TEST_CASE("sysid predict --json prints the library's summary", "[nn][predict][cli]") {
  sysid::test::TempDir dir;
  const auto net = SmallNet();
  sysid::WriteNeuralNetwork(dir / "nn.json", net);
  sysid::Recording rec = Data(true);
  sysid::WriteRecording(dir / "data.csv", rec);
  const auto r = sysid::test::RunCli({"predict", "--nn", dir / "nn.json", dir / "data.csv", "--json"});
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const auto j = nlohmann::ordered_json::parse(r.out);
  sysid::Recording lib = sysid::ReadRecording(dir / "data.csv");
  auto expected = nlohmann::ordered_json::parse(sysid::ToJson(sysid::PredictColumn(net, lib)));
  CHECK(j["nn"] == dir / "nn.json");
  CHECK(j["data"] == dir / "data.csv");
  for (const auto& [key, value] : expected.items()) CHECK(j[key] == value);
  const auto bad = sysid::test::RunCli(
      {"predict", "--nn", dir / "nn.json", dir / "data.csv", "--column", "u"});
  CHECK(bad.exit_code == 1);
  CHECK_THAT(bad.err, Catch::Contains("--column"));
}
