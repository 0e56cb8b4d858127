// compare_json.cpp: errors round-trip; `sysid compare --json` lists the library's objects.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>

#include "support/test_support.hpp"
#include "sysid/compare.hpp"
#include "sysid/io.hpp"
#include "sysid/model.hpp"
#include "sysid/nn.hpp"

TEST_CASE("comparison JSON: round trip and the CLI's recordings", "[compare][json]") {
  sysid::PredictionErrors e{0.5, 2.25, 0.1, std::numeric_limits<double>::quiet_NaN()};
  const std::string text = sysid::ToJson(e);
  CHECK_THAT(text, Catch::Contains("\"r2\": null"));
  const auto back = sysid::PredictionErrorsFromJson(text, "e.json");
  CHECK(back.rmse_v == e.rmse_v);
  CHECK(back.peak_error_v == e.peak_error_v);
  CHECK(back.nrmse_range == e.nrmse_range);
  CHECK(std::isnan(back.r2));
  CHECK_THROWS_WITH(sysid::PredictionErrorsFromJson("{\"rmse_v\": -1}", "e.json"),
                    Catch::Contains("e.json:1:2: rmse_v: expected a number >= 0"));

  sysid::test::TempDir dir;
  sysid::WriteModel(dir / "m.json", sysid::FrictionModel::Paper());
  const std::string nn = sysid::test::SourcePath("datasets/paper/nn24.json");
  const std::string rec = sysid::test::SourcePath("datasets/virtual/test.csv");
  const auto network = sysid::ReadNeuralNetwork(nn);
  const auto c = sysid::CompareInverseModels(sysid::ReadRecording(rec),
                                             sysid::FrictionModel::Paper(), &network);
  const auto cli =
      sysid::test::RunCli({"compare", "--json", "--model", dir / "m.json", "--nn", nn, rec});
  REQUIRE(cli.exit_code == 0);
  CHECK(nlohmann::json::parse(cli.out)["recordings"][0] == nlohmann::json::parse(sysid::ToJson(c)));
}
