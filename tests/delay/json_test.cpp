// The delay-tuning and refinement results' JSON (delay_json.cpp): round trips, null for NaN,
// positioned errors. (tests/identify/cli_test.cpp checks the CLI prints this text.)
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <string>

#include "sysid/delay.hpp"
#include "sysid/error.hpp"

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
}

TEST_CASE("delay tuning JSON round-trips", "[delay][json]") {
  sysid::DelayTuningResult r;
  r.termination = sysid::Termination::kBudgetExhausted;
  r.message = "max evaluations";
  r.model = sysid::FrictionModel::Paper();
  r.tau_s = r.model.tau_s;
  r.cost = 0.125;
  r.rms_error_mps = 1.5e-3;
  r.evaluations = 40;
  r.simulations = 440;
  r.segments = 11;
  r.samples = 7100;
  r.curve = {{0.001, 0.5}, {0.0035, 0.125}};
  r.warnings = {"tau at the bound"};
  r.wall_time_s = 0.25;
  const std::string text = sysid::ToJson(r);
  const auto back = sysid::DelayTuningResultFromJson(text, "d.json");
  CHECK(back.termination == r.termination);
  CHECK(back.message == r.message);
  CHECK(sysid::ModelToJson(back.model) == sysid::ModelToJson(r.model));
  CHECK(back.tau_s == r.tau_s);
  CHECK(back.cost == r.cost);
  CHECK(back.evaluations == r.evaluations);
  CHECK(back.simulations == r.simulations);
  CHECK(back.samples == r.samples);
  CHECK(back.curve == r.curve);
  CHECK(back.warnings == r.warnings);
  CHECK(sysid::ToJson(back) == text);
  // The model inside is checked by the model file's rules, at its place in this text.
  std::string bad = text;
  bad.replace(bad.find("\"a3\": 6"), 7, "\"a3\": -6");
  CHECK_THROWS_WITH(
      sysid::DelayTuningResultFromJson(bad, "d.json"),
      Catch::Contains("d.json:") && Catch::Contains("model.a3: expected a number > 0"));
  bad = text;
  bad.replace(bad.find("budget-exhausted"), 16, "gave-up");
  CHECK_THROWS_WITH(sysid::DelayTuningResultFromJson(bad, "d.json"),
                    Catch::Contains("termination: expected a termination"));
}

TEST_CASE("refinement JSON round-trips, singular standard errors as null", "[delay][json]") {
  sysid::RefineResult r;
  r.model = sysid::FrictionModel::Paper();
  r.names = {"a1p", "a1n", "a2p", "a2n", "tau"};
  r.std_error.resize(5);
  r.std_error << 0.5, 0.25, kNaN, 0.125, 1e-5;
  r.initial_cost = 2;
  r.final_cost = 1;
  r.rms_error_mps = 1e-3;
  r.iterations = 7;
  r.simulations = 99;
  r.termination = sysid::Termination::kConverged;
  r.message = "Function tolerance reached";
  r.warnings = {"a3 moved from its given value 6 to 2.5"};
  r.wall_time_s = 3.5;
  const std::string text = sysid::ToJson(r);
  CHECK_THAT(text, Catch::Contains("\"a2p\": null"));
  // A refined model file is the same text run to run: no wall time in it.
  CHECK_THAT(text, !Catch::Contains("wall_time_s"));
  const auto back = sysid::RefineResultFromJson(text, "r.json");
  CHECK(sysid::ModelToJson(sysid::ParseModel(text, "r.json")) ==
        sysid::ModelToJson(r.model));  // a model file too
  CHECK(sysid::ModelToJson(back.model) == sysid::ModelToJson(r.model));
  CHECK(back.names == r.names);
  CHECK(std::isnan(back.std_error[2]));
  CHECK(back.std_error[4] == r.std_error[4]);
  CHECK(back.iterations == r.iterations);
  CHECK(back.termination == r.termination);
  CHECK(back.warnings == r.warnings);
  CHECK(sysid::ToJson(back) == text);
}
