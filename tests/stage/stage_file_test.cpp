// The stage parameter file: round trip, the bundled file, and error messages.
#include <catch2/catch.hpp>
#include <string>

#include "support/test_support.hpp"
#include "sysid/error.hpp"
#include "sysid/stage.hpp"

TEST_CASE("the bundled stage.json is the built-in calibrated stage", "[stage][file]") {
  const auto file =
      sysid::ReadStageParameters(sysid::test::SourcePath("datasets/virtual/stage.json"));
  CHECK(sysid::StageParametersToJson(file) ==
        sysid::StageParametersToJson(sysid::StageParameters::Default()));
  const auto back = sysid::ParseStageParameters(sysid::StageParametersToJson(file), "mem.json");
  CHECK(back.backward.viscous_per_s == file.backward.viscous_per_s);
  CHECK(back.drive_map_out_v == file.drive_map_out_v);
}

TEST_CASE("stage files name their model, presets load by name", "[stage][file]") {
  // The actuator-delay preset round-trips and keeps its model.
  const auto ad = sysid::StageParameters::ActuatorDelay();
  const auto back = sysid::ParseStageParameters(sysid::StageParametersToJson(ad), "ad.json");
  CHECK(back.model == sysid::StageModel::kActuatorDelay);
  CHECK(sysid::StageParametersToJson(back) == sysid::StageParametersToJson(ad));
  CHECK(sysid::LoadStage("actuator-delay").transport_delay_s == 0.002);
  CHECK(sysid::LoadStage("virtual").model == sysid::StageModel::kVelocitySource);
  // A file without "model" written before the key existed (it has "friction") is actuator delay.
  CHECK(sysid::ParseStageParameters("{\"friction\": {\"bristle_damping_per_s\": 900}}", "o.json")
            .model == sysid::StageModel::kActuatorDelay);
  CHECK(sysid::ParseStageParameters("{\"rig\": {\"position_noise_m\": 0}}", "n.json").model ==
        sysid::StageModel::kVelocitySource);
  // A section of the other model is an error naming both.
  CHECK_THROWS_WITH(
      sysid::ParseStageParameters("{\"model\": \"velocity-source\",\n \"friction\": {}}", "m.json"),
      Catch::StartsWith("m.json:2:2: key 'friction' belongs to the actuator-delay model"));
  CHECK_THROWS_WITH(sysid::ParseStageParameters("{\"model\": \"piezo\"}", "m.json"),
                    Catch::Contains("is not one of velocity-source, actuator-delay"));
  CHECK_THROWS_WITH(
      sysid::ParseStageParameters("{\"motor\": {\"dead_zone_forward_v\": 1.35}}", "m.json"),
      Catch::Contains("knots outside the dead zone"));
  CHECK_THROWS_AS(sysid::StageParameters::Preset("fast"), sysid::OptionsError);
}

TEST_CASE("stage file errors name the place and the rule", "[stage][file]") {
  CHECK_THROWS_WITH(sysid::ParseStageParameters("{\"drive\": {\n  \"dead_zone\": 0.1}}", "s.json"),
                    Catch::StartsWith("s.json:2:3: unknown key 'dead_zone' in 'drive'"));
  CHECK_THROWS_WITH(sysid::ParseStageParameters("{\"rig\": {\"dac_bits\": 16.5}}", "s.json"),
                    Catch::Contains("s.json:1:10: key 'dac_bits': expected an integer"));
  CHECK_THROWS_WITH(sysid::ParseStageParameters(
                        "{\"friction\": {\"forward\": {\"static_mps2\": 1.0}}}", "s.json"),
                    Catch::Contains("forward.static_mps2 = 1. Violated constraint: static_mps2 >= "
                                    "coulomb_mps2"));
  CHECK_THROWS_WITH(sysid::ParseStageParameters("{\"rig\": [1,}", "s.json"),
                    Catch::StartsWith("s.json:1:12: invalid JSON"));
  CHECK_THROWS_WITH(sysid::ParseStageParameters(
                        "{\"drive\": {\"map_in_v\": [-1, 1], \"map_out_v\": [-1, 1]}}", "s.json"),
                    Catch::Contains("a knot at 0 V"));
}
