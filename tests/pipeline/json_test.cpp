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
  r.margins = sysid::AnalyzePiMargins(sysid::FrictionModel::Paper(), sysid::PiOptions{});
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
  REQUIRE(back.margins);
  CHECK(back.margins->forward().phase_margin_deg == r.margins->forward().phase_margin_deg);
  CHECK(back.margins->backward().gain_margin == r.margins->backward().gain_margin);
  CHECK_FALSE(back.margins->forward().Stable());  // the paper's gains on its delayed model
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
  // The margins' verdict is derived from the margins.
  r.margins = sysid::AnalyzePiMargins(sysid::FrictionModel::Paper(), sysid::PiOptions{});
  auto m = nlohmann::ordered_json::parse(sysid::ToJson(r));
  REQUIRE(m["margins"][0]["stable"] == false);
  m["margins"][0]["stable"] = true;
  CHECK_THROWS_WITH(sysid::PipelineResultFromJson(m.dump(1), "p.json"),
                    Contains("stable: expected false"));
  m["margins"][0]["stable"] = false;
  m["margins"][0]["direction"] = "backward";
  CHECK_THROWS_WITH(sysid::PipelineResultFromJson(m.dump(1), "p.json"),
                    Contains("direction: expected \"forward\""));
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

TEST_CASE("pipeline options round-trip through JSON", "[pipeline][json]") {
  sysid::PipelineOptions o;
  o.a3 = 5.5;
  o.tune_delay = false;
  o.delay.tau_max_s = 0.012;
  o.refine = true;
  o.hidden_sizes = {8, 12};
  o.training.max_epochs = 42;
  o.nn_inputs = {"v", "a"};
  o.typical = false;
  o.typical_hidden = 30;
  o.track_frequencies_hz = {0.25};
  o.pi = sysid::PiOptions::ForActuatorDelayStage();
  o.facts = true;
  o.facts_options = sysid::FactsOptions::Reduced();
  o.facts_options.facts = {"F1", "F3"};
  o.facts_options.pulse.amplitudes_v = {-1.0, 1.0};
  o.facts_options.seed = 9;
  o.reference_path = "paper.json";
  o.threads = 2;
  const std::string text = sysid::ToJson(o);
  const auto back = sysid::PipelineOptionsFromJson(text, "p.json");
  CHECK(back.a3 == 5.5);
  CHECK_FALSE(back.tune_delay);
  CHECK(back.delay.tau_max_s == 0.012);
  CHECK(back.hidden_sizes == o.hidden_sizes);
  CHECK(back.training.max_epochs == 42);
  CHECK(back.nn_inputs == o.nn_inputs);
  CHECK(back.pi.kp_v_per_m == 3000);
  CHECK(back.facts_options.facts == o.facts_options.facts);
  CHECK(back.facts_options.pulse.amplitudes_v == o.facts_options.pulse.amplitudes_v);
  CHECK(back.facts_options.training.hidden == o.facts_options.training.hidden);
  CHECK(back.reference_path == "paper.json");
  CHECK(sysid::ToJson(back) == text);
  // The pipeline's own defaults (DefaultTraining: the output layer re-solved) for absent keys.
  CHECK(sysid::PipelineOptionsFromJson("{}", "e.json").training.solve_output_layer);
  CHECK(sysid::ToJson(sysid::FactsOptionsFromJson(sysid::ToJson(o.facts_options), "f.json")) ==
        sysid::ToJson(o.facts_options));
  CHECK(sysid::PulseProcedureFromJson(sysid::ToJson(o.facts_options.pulse), "pp.json").amplitudes_v ==
        o.facts_options.pulse.amplitudes_v);
}

TEST_CASE("pipeline options JSON: bad input names the place", "[pipeline][json]") {
  using Catch::Contains;
  CHECK_THROWS_WITH(sysid::PipelineOptionsFromJson("{\"typical_stride\": 0}", "p.json"),
                    Contains("p.json:1:2: typical_stride: expected typical_stride >= 1, found 0"));
  CHECK_THROWS_WITH(
      sysid::PipelineOptionsFromJson("{\"pi\": {\n \"u_max_v\": -1}}", "p.json"),
      Contains("p.json:2:2: pi.u_max_v: expected u_max_v > 0, found -1"));
  CHECK_THROWS_WITH(
      sysid::PipelineOptionsFromJson("{\"facts_options\": {\"facts\": [\"F9\"]}}", "p.json"),
      Contains("p.json:1:20: facts_options.facts: expected ids are F1, F2, F3, F4, F5, F6, F7, "
               "F8, found 'F9'"));
  CHECK_THROWS_WITH(
      sysid::PipelineOptionsFromJson("{\"facts_options\": {\"pulse\": {\"on\": 1}}}", "p.json"),
      Contains("unknown key 'on' in 'facts_options.pulse'"));
  // A nested options' error is placed inside facts_options, not at the pipeline's own key of
  // the same name (line 2 holds the valid top-level delay, line 3 the nested one).
  CHECK_THROWS_WITH(sysid::PipelineOptionsFromJson("{\"delay\": {\"tau_min_s\": 0.001},\n"
                                                   " \"facts_options\": {\"delay\": {\n"
                                                   "  \"tau_min_s\": -1}}}",
                                                   "p.json"),
                    Contains("p.json:3:3: ") && Contains("tau_min_s"));
  CHECK_THROWS_WITH(sysid::PulseProcedureFromJson("{\"amplitudes_v\": [12]}", "pp.json"),
                    Contains("amplitudes_v"));
}
