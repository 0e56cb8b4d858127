// pipeline_json.cpp: the run summary holds the model file's object, the chosen network, the
// networks' MSEs, each tracking run, the facts' verdicts and the step times in run order, and
// reads back losslessly (the CLI test runs the whole pipeline; this one is cheap).
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>
#include <string>

#include "sysid/error.hpp"
#include "sysid/model.hpp"
#include "sysid/pipeline.hpp"

namespace {
sysid::PipelineResult Summary() {
  sysid::PipelineResult r;
  r.model = sysid::FrictionModel::Paper();
  r.dominance.dominant = "velocity";
  r.nn_inputs = {"v"};
  r.network = sysid::NeuralNetwork({{"v", "m/s", -0.1, 0.1}}, {"u", "V", -10, 10}, 5);
  r.network.set_parameters(Eigen::VectorXd::LinSpaced(r.network.parameter_count(), -0.5, 0.7));
  r.network_test_mse = 0.25;
  sysid::TrackingRow row;
  row.frequency_hz = 1.5;
  row.scheme = "nn";
  row.result.max_error_m = 2e-6;
  row.result.rms_error_m = 1e-6;
  r.tracking = {row};
  // Not in sorted order: the array keeps the run's order.
  r.step_seconds = {{"train", 2.0}, {"identify", 0.5}};
  return r;
}
}  // namespace

TEST_CASE("pipeline summary JSON", "[pipeline][json]") {
  const sysid::PipelineResult r = Summary();
  const auto j = nlohmann::json::parse(sysid::ToJson(r));
  CHECK(sysid::ModelToJson(sysid::ParseModel(j["model"].dump(), "model")) ==
        sysid::ModelToJson(r.model));
  CHECK(j["dominant"] == "velocity");
  CHECK(j["hidden"] == 5);
  CHECK(sysid::NeuralNetworkToJson(sysid::ParseNeuralNetwork(j["network"].dump(), "net")) ==
        sysid::NeuralNetworkToJson(r.network));
  CHECK(j["nn_test_mse"] == 0.25);
  CHECK_FALSE(j.contains("typical_test_mse"));  // no typical network
  CHECK_FALSE(j.contains("facts_required_met"));
  REQUIRE(j["tracking"].size() == 1);
  CHECK(j["tracking"][0]["ff"] == "nn");
  CHECK(j["tracking"][0]["max_error_m"] == 2e-6);
  REQUIRE(j["steps"].size() == 2);
  CHECK(j["steps"][0]["name"] == "train");
  CHECK(j["steps"][0]["wall_time_s"] == 2.0);
  CHECK(j["steps"][1]["name"] == "identify");
}

TEST_CASE("pipeline summary JSON round-trips", "[pipeline][json]") {
  sysid::PipelineResult r = Summary();
  r.typical.emplace();
  r.typical->train_mse = 0.01;
  r.typical_test_mse = 0.4;
  r.facts.emplace();
  r.facts->facts.resize(2);
  r.facts->facts[0].id = "F1";
  r.facts->facts[0].met = true;
  r.facts->facts[1].id = "F7";
  r.facts->facts[1].required = false;  // not met, but not required: required_met stays true
  const std::string text = sysid::ToJson(r);
  const sysid::PipelineResult back = sysid::PipelineResultFromJson(text, "p.json");
  CHECK(back.model.a1p == r.model.a1p);
  CHECK(back.dominance.dominant == "velocity");
  CHECK(back.nn_inputs == r.nn_inputs);
  CHECK(back.network.parameters() == r.network.parameters());
  REQUIRE(back.typical);
  CHECK(back.typical->train_mse == 0.01);
  CHECK(back.typical_test_mse == 0.4);
  REQUIRE(back.facts);
  CHECK(back.facts->RequiredMet());
  CHECK(back.step_seconds == r.step_seconds);
  CHECK(sysid::ToJson(back) == text);
  // The CLI's output (the report path in front) reads too.
  auto cli = nlohmann::ordered_json::parse(text);
  nlohmann::ordered_json with_report;
  with_report["report"] = "out/report.md";
  with_report.update(cli);
  CHECK(sysid::ToJson(sysid::PipelineResultFromJson(with_report.dump(2), "cli.json")) == text);
}

TEST_CASE("pipeline summary JSON: derived values are checked", "[pipeline][json]") {
  using Catch::Contains;
  sysid::PipelineResult r = Summary();
  r.facts.emplace();
  r.facts->facts.resize(1);
  r.facts->facts[0].id = "F2";  // required, not met
  auto j = nlohmann::ordered_json::parse(sysid::ToJson(r));
  j["hidden"] = 6;
  CHECK_THROWS_WITH(sysid::PipelineResultFromJson(j.dump(1), "p.json"),
                    Contains("hidden: expected 5 (the network's hidden units), found 6"));
  j["hidden"] = 5;
  j["facts_required_met"] = true;
  CHECK_THROWS_WITH(sysid::PipelineResultFromJson(j.dump(1), "p.json"),
                    Contains("facts_required_met: expected false (every required fact's met)"));
  j["facts_required_met"] = false;
  CHECK_NOTHROW(sysid::PipelineResultFromJson(j.dump(1), "p.json"));
  j.erase("facts");
  CHECK_THROWS_WITH(sysid::PipelineResultFromJson(j.dump(1), "p.json"),
                    Contains("facts and facts_required_met come together"));
  // The old form (steps as an object) is rejected with the expected form named.
  auto old = nlohmann::ordered_json::parse(sysid::ToJson(Summary()));
  old["steps"] = {{"identify", 0.5}};
  CHECK_THROWS_WITH(sysid::PipelineResultFromJson(old.dump(1), "p.json"),
                    Contains("steps: expected an array, found an object"));
  old = nlohmann::ordered_json::parse(sysid::ToJson(Summary()));
  old["dominant_variable"] = "velocity";
  CHECK_THROWS_WITH(sysid::PipelineResultFromJson(old.dump(1), "p.json"),
                    Contains("unknown key 'dominant_variable'"));
}
