// simulate_json.cpp: options round-trip with positioned errors; `sysid simulate --json`
// reports the library's summary.
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>
#include <string>

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
