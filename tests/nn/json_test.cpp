// nn_json.cpp: `sysid train --json` and `sysid sweep --json` carry the library's report
// (key for key, value for value; the CLI adds its data files and the test MSE).
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>
#include <string>

#include "support/test_support.hpp"
#include "sysid/nn.hpp"

using sysid::test::RunCli;
using sysid::test::SourcePath;

namespace {
// Every key of the library's object is in the CLI's with the same value (wall times excepted).
void CheckCarries(const nlohmann::json& cli, nlohmann::json lib) {
  for (auto& [key, value] : lib.items()) {
    INFO(key);
    REQUIRE(cli.contains(key));
    if (key != "wall_time_s" && key != "rows") CHECK(cli[key] == value);
  }
}
}  // namespace

TEST_CASE("train and sweep --json carry the library's reports", "[nn][json]") {
  const std::string train_path = SourcePath("datasets/virtual/training.csv");
  const auto train = sysid::ReadNeuralDataset(train_path, {"v"}, "u");
  sysid::NeuralTrainingOptions o;
  o.hidden = 3;
  o.max_epochs = 4;
  const auto r = sysid::TrainNeuralNetwork(train, nullptr, o);
  REQUIRE(r.stop == sysid::TrainingStop::kMaxEpochs);
  REQUIRE(r.warnings.size() == 1);  // four epochs: under-trained
  auto lib = nlohmann::json::parse(sysid::ToJson(r, o));
  CHECK(lib["history"].size() == r.history.size());
  CHECK(lib["validation_mse"].is_null());
  lib.erase("history");  // printed with --history only
  auto cli =
      RunCli({"train", "--json", "--train", train_path, "--hidden", "3", "--max-epochs", "4"});
  REQUIRE(cli.exit_code == 0);
  CheckCarries(nlohmann::json::parse(cli.out), lib);
  CHECK_THAT(cli.err, Catch::Contains("warning: " + r.warnings[0]));

  sysid::HiddenSweepOptions so;
  so.hidden_sizes = {2, 3};
  so.training = o;
  so.training.max_epochs = 3;
  const auto s = sysid::SweepHiddenSize(train, nullptr, nullptr, so);
  const auto slib = nlohmann::json::parse(sysid::ToJson(s, so));
  CHECK(slib["chosen_hidden"] == s.rows[static_cast<size_t>(s.chosen)].hidden);
  CHECK(slib["warnings"].size() == 2);
  cli = RunCli({"sweep", "--json", "--train", train_path, "--hidden", "2,3", "--max-epochs", "3"});
  REQUIRE(cli.exit_code == 0);
  const auto scli = nlohmann::json::parse(cli.out);
  CheckCarries(scli, slib);
  REQUIRE(scli["rows"].size() == 2);
  CHECK(scli["rows"][1]["train_mse"] == slib["rows"][1]["train_mse"]);
}
