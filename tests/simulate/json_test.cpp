// simulate_json.cpp: options round-trip with positioned errors; `sysid simulate --json`
// reports the library's summary.
#include <algorithm>
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "support/test_support.hpp"
#include "sysid/error.hpp"
#include "sysid/input.hpp"
#include "sysid/simulate.hpp"

TEST_CASE("simulation options round-trip through JSON", "[simulate][json]") {
  sysid::SimulationOptions o;
  o.t_end_s = 2.5;
  o.output_times_s = {0.0, 0.5, 2.5};
  o.v0_mps = 0.01;
  o.rtol = 1e-8;
  o.method = sysid::IntegratorMethod::kBdf;
  o.max_steps = 1234;
  o.breakpoint_order = 3;
  const std::string text = sysid::ToJson(o);
  const auto back = sysid::SimulationOptionsFromJson(text, "o.json");
  CHECK(back.t_end_s == o.t_end_s);
  CHECK(back.output_times_s == o.output_times_s);
  CHECK(back.v0_mps == o.v0_mps);
  CHECK(back.rtol == o.rtol);
  CHECK(back.method == o.method);
  CHECK(back.max_steps == o.max_steps);
  CHECK(back.breakpoint_order == o.breakpoint_order);
  CHECK(sysid::ToJson(back) == text);
  // Absent keys keep their defaults; Validate()'s rules are positioned in the text.
  CHECK(sysid::SimulationOptionsFromJson("{}", "e.json").rtol == sysid::SimulationOptions{}.rtol);
  CHECK_THROWS_WITH(sysid::SimulationOptionsFromJson("{\n  \"rtol\": -1\n}", "o.json"),
                    Catch::Contains("o.json:2:3: rtol"));
  CHECK_THROWS_WITH(sysid::SimulationOptionsFromJson("{\"method\": \"euler\"}", "o.json"),
                    Catch::Contains("o.json:1:2: method: expected \"adams\" or \"bdf\""));
}

TEST_CASE("simulate --json carries the library's run summary", "[simulate][json]") {
  sysid::PulseTrainSpec spec;
  spec.amplitudes_v = {1.6, -2.3};
  spec.repeats = 1;
  const auto input = sysid::MakePulseTrain(spec);
  sysid::SimulationOptions o;
  o.t_end_s = 1.0;
  o.rtol = 1e-8;
  o.atol = 1e-10;
  const auto r = sysid::Simulate(sysid::FrictionModel::Paper(), input, o);
  const auto lib = nlohmann::json::parse(sysid::ToJson(r, o));
  const auto cli =
      sysid::test::RunCli({"simulate", "--json", "--paper-model", "--waveform", "paper-pulses",
                           "--t-end", "1", "--rtol", "1e-8", "--atol", "1e-10"});
  REQUIRE(cli.exit_code == 0);
  const auto j = nlohmann::json::parse(cli.out);
  CHECK(j["summary"]["termination"] == "converged");
  CHECK(j["summary"]["method"] == "adams");
  CHECK(j["summary"]["rtol"] == 1e-8);
  CHECK(lib["summary"]["rtol"] == 1e-8);
  CHECK(lib["samples"] == 1001);
  CHECK(j["samples"] == 1001);
  CHECK(lib["events"].size() == r.events.size());
  for (const auto& [key, value] : lib["summary"].items()) CHECK(j["summary"].contains(key));
  CHECK(j["summary"].size() == lib["summary"].size());
}

TEST_CASE("a run's summary states the stop only when the run stopped short", "[simulate][json]") {
  sysid::PulseTrainSpec spec;
  spec.amplitudes_v = {1.6};
  spec.repeats = 1;
  const auto input = sysid::MakePulseTrain(spec);
  sysid::SimulationOptions o;
  o.t_end_s = 1.0;
  const std::vector<std::string> counts = {"steps", "rhs_evaluations", "root_evaluations",
                                           "events", "reinitialisations", "wall_time_s"};
  auto keys = [](const nlohmann::ordered_json& j) {
    std::vector<std::string> k;
    for (auto it = j.begin(); it != j.end(); ++it) k.push_back(it.key());
    return k;
  };
  std::vector<std::string> usable = {"termination", "method", "rtol", "atol"};
  usable.insert(usable.end(), counts.begin(), counts.end());
  const auto done = sysid::Simulate(sysid::FrictionModel::Paper(), input, o);
  REQUIRE(done.summary.IsSolutionUsable());
  CHECK(keys(nlohmann::ordered_json::parse(sysid::ToJson(done, o))["summary"]) == usable);

  o.max_steps = 5;  // far fewer than the pulse's edges need: CV_TOO_MUCH_WORK
  const auto stopped = sysid::Simulate(sysid::FrictionModel::Paper(), input, o);
  REQUIRE_FALSE(stopped.summary.IsSolutionUsable());
  const auto s = nlohmann::ordered_json::parse(sysid::ToJson(stopped, o))["summary"];
  std::vector<std::string> with_stop = usable;
  with_stop.insert(with_stop.end(), {"message", "cvode_flag", "failure_time_s"});
  CHECK(keys(s) == with_stop);
  CHECK(s["termination"] == sysid::ToString(stopped.summary.termination));
  CHECK(s["cvode_flag"] == stopped.summary.cvode_flag);
  CHECK(s["failure_time_s"] == stopped.summary.failure_time_s);
}

TEST_CASE("simulate --json's model is the model file's object, keys sorted", "[simulate][json]") {
  const auto cli = sysid::test::RunCli(
      {"simulate", "--json", "--paper-model", "--pulses", "1.6", "--t-end", "1"});
  REQUIRE(cli.exit_code == 0);
  const auto j = nlohmann::ordered_json::parse(cli.out);
  const auto file = nlohmann::json::parse(sysid::ModelToJson(sysid::FrictionModel::Paper()));
  CHECK(j["model"] == nlohmann::ordered_json(file));
  std::vector<std::string> keys;
  for (auto it = j["model"].begin(); it != j["model"].end(); ++it) keys.push_back(it.key());
  CHECK(std::is_sorted(keys.begin(), keys.end()));
  std::vector<std::string> top;
  for (auto it = j.begin(); it != j.end(); ++it) top.push_back(it.key());
  CHECK(top == std::vector<std::string>{"model", "input", "t_end_s", "samples", "output",
                                        "events_file", "events", "summary"});
}
