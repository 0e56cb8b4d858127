// pipeline_json.cpp: the run summary holds the model file's object, the networks' MSEs, each
// tracking run and the step times (the CLI test runs the whole pipeline; this one is cheap).
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "sysid/model.hpp"
#include "sysid/pipeline.hpp"

TEST_CASE("pipeline summary JSON", "[pipeline][json]") {
  sysid::PipelineResult r;
  r.model = sysid::FrictionModel::Paper();
  r.dominance.dominant = "velocity";
  r.nn_inputs = {"v"};
  r.network = sysid::NeuralNetwork({{"v", "m/s", -0.1, 0.1}}, {"u", "V", -10, 10}, 5);
  r.network_test_mse = 0.25;
  sysid::TrackingRow row;
  row.frequency_hz = 1.5;
  row.scheme = "nn";
  row.result.max_error_m = 2e-6;
  row.result.rms_error_m = 1e-6;
  r.tracking = {row};
  r.step_seconds = {{"identify", 0.5}, {"train", 2.0}};
  const auto j = nlohmann::json::parse(sysid::ToJson(r));
  CHECK(sysid::ModelToJson(sysid::ParseModel(j["model"].dump(), "model")) ==
        sysid::ModelToJson(r.model));
  CHECK(j["dominant"] == "velocity");
  CHECK(j["hidden"] == 5);
  CHECK(j["nn_test_mse"] == 0.25);
  CHECK_FALSE(j.contains("typical_test_mse"));  // no typical network
  CHECK_FALSE(j.contains("facts_required_met"));
  REQUIRE(j["tracking"].size() == 1);
  CHECK(j["tracking"][0]["ff"] == "nn");
  CHECK(j["tracking"][0]["max_error_m"] == 2e-6);
  CHECK(j["steps"]["train"] == 2.0);
}
