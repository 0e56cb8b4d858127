// nn_json.cpp: `sysid train --json` and `sysid sweep --json` carry the library's report
// (key for key, value for value; the CLI adds its data files and the test MSE).
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
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

TEST_CASE("training JSON round-trips, the network is attached from its file", "[nn][json]") {
  const auto train =
      sysid::ReadNeuralDataset(SourcePath("datasets/virtual/training.csv"), {"v"}, "u");
  sysid::NeuralTrainingOptions o;
  o.hidden = 3;
  o.max_epochs = 4;
  o.momentum = 0.25;
  o.seed = 18446744073709551615ULL;  // the largest uint64: the seed is not read as a long
  for (const bool validated : {false, true}) {
    INFO("validated " << validated);
    const auto r = sysid::TrainNeuralNetwork(train, validated ? &train : nullptr, o);
    const std::string text = sysid::ToJson(r, o);
    sysid::NeuralTrainingOptions bo;
    bo.max_epochs = 99;  // not in the report: kept
    auto back = sysid::NeuralTrainingResultFromJson(text, "t.json", &bo);
    CHECK(bo.hidden == o.hidden);
    CHECK(bo.trainer == o.trainer);
    CHECK(bo.momentum == o.momentum);
    CHECK(bo.solve_output_layer == o.solve_output_layer);
    CHECK(bo.seed == o.seed);
    CHECK(bo.max_epochs == 99);
    CHECK(back.network.parameter_count() == 1);  // empty: the weights are not in the report
    CHECK(back.termination == r.termination);
    CHECK(back.stop == r.stop);
    CHECK(back.message == r.message);
    CHECK(back.epochs == r.epochs);
    CHECK(back.restart == r.restart);
    CHECK(back.train_mse == r.train_mse);
    CHECK(std::isnan(back.validation_mse) == !validated);
    if (validated) CHECK(back.validation_mse == r.validation_mse);
    CHECK(back.wall_time_s == r.wall_time_s);
    CHECK(back.warnings == r.warnings);
    REQUIRE(back.history.size() == r.history.size());
    REQUIRE(!r.history.empty());
    const auto& e = back.history.back();
    CHECK(e.epoch == r.history.back().epoch);
    CHECK(e.restart == r.history.back().restart);
    CHECK(e.mu == r.history.back().mu);
    CHECK(e.gradient_norm == r.history.back().gradient_norm);
    CHECK(e.train_mse == r.history.back().train_mse);
    CHECK(std::isnan(e.validation_mse) == !validated);
    back.network = r.network;  // as read from the network file
    CHECK(sysid::ToJson(back, bo) == text);
  }
}

TEST_CASE("training JSON errors name the place and the key", "[nn][json]") {
  sysid::NeuralTrainingResult r;
  r.network = sysid::NeuralNetwork({{"v", "m/s", -1, 1}, {"a", "m/s^2", -2, 2}},
                                   {"u", "V", -10, 10}, 4);
  r.stop = sysid::TrainingStop::kSmallGradient;
  r.termination = sysid::TerminationOf(r.stop);
  r.history = {{1, 0, 1e-3, 0.5, 0.25, 0.1}};
  sysid::NeuralTrainingOptions o;
  o.hidden = 4;
  const std::string text = sysid::ToJson(r, o);
  REQUIRE_NOTHROW(sysid::NeuralTrainingResultFromJson(text, "t.json"));
  auto replaced = [&](const std::string& from, const std::string& to) {
    std::string t = text;
    REQUIRE(t.find(from) != std::string::npos);
    return t.replace(t.find(from), from.size(), to);
  };
  // The line of a key's first appearance in the indented text.
  const auto line = [&](const std::string& key) {
    const std::string head = text.substr(0, text.find("\"" + key + "\""));
    return std::to_string(std::count(head.begin(), head.end(), '\n') + 1);
  };
  CHECK_THROWS_WITH(
      sysid::NeuralTrainingResultFromJson(replaced("\"mu\": 0.001", "\"mu\": -1"), "t.json"),
      Catch::StartsWith("t.json:" + line("mu") + ":7: history[0].mu: expected a number >= 0"));
  CHECK_THROWS_WITH(
      sysid::NeuralTrainingResultFromJson(replaced("small_gradient", "tired"), "t.json"),
      Catch::StartsWith("t.json:" + line("stop_reason") + ":3: stop_reason: expected a stopping "
                        "rule (max_epochs, ") &&
          Catch::Contains("found string \"tired\""));
  CHECK_THROWS_WITH(
      sysid::NeuralTrainingResultFromJson(replaced("\"converged\"", "\"failure\""), "t.json"),
      Catch::StartsWith("t.json:" + line("termination") +
                        ":3: termination: expected \"converged\" (stop_reason \"small_gradient\")"));
  // P = 4 n + 9 fits n = 2 (17), not 18.
  CHECK_THROWS_WITH(
      sysid::NeuralTrainingResultFromJson(replaced("\"parameters\": 17", "\"parameters\": 18"),
                                          "t.json"),
      Catch::StartsWith("t.json:3:3: parameters: expected H n + 2 H + 1 parameters"));
}
