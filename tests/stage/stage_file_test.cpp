// The stage parameter file: round trip, the bundled file, and error messages.
#include <algorithm>
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
                    Catch::StartsWith("s.json:1:10: rig.dac_bits: expected an integer"));
  CHECK_THROWS_WITH(sysid::ParseStageParameters("{\"rig\": [1,}", "s.json"),
                    Catch::StartsWith("s.json:1:12: invalid JSON"));
}

namespace {
// The bundled stage file with `from` replaced by `to` (which must occur).
std::string Edited(const std::string& from, const std::string& to) {
  std::string text = sysid::StageParametersToJson(sysid::StageParameters::Default());
  const size_t at = text.find(from);
  REQUIRE(at != std::string::npos);
  return text.replace(at, from.size(), to);
}
// "LINE:COL" of the first occurrence of `needle` in the bundled file after `from` was edited.
std::string At(const std::string& text, const std::string& needle) {
  const size_t at = text.find(needle);
  const auto line = 1 + std::count(text.begin(), text.begin() + static_cast<long>(at), '\n');
  const size_t col = at - (text.rfind('\n', at) + 1) + 1;
  return std::to_string(line) + ":" + std::to_string(col);
}
}  // namespace

TEST_CASE("stage file value errors are positioned: key, rule, found value", "[stage][file]") {
  auto bad = Edited("\"sample_rate_hz\": 1000.0", "\"sample_rate_hz\": 0");
  CHECK_THROWS_WITH(sysid::ParseStageParameters(bad, "s.json"),
                    Catch::Equals("s.json:" + At(bad, "\"sample_rate_hz\"") +
                                  ": rig.sample_rate_hz: expected sample_rate_hz > 0, found 0"));
  bad = Edited("\"coulomb_mps2\": ", "\"coulomb_mps2\": -1, \"_was\": ");
  CHECK_THROWS_WITH(sysid::ParseStageParameters(bad, "s.json"),
                    Catch::Equals("s.json:" + At(bad, "\"coulomb_mps2\"") +
                                  ": rail.coulomb_mps2: expected coulomb_mps2 > 0, found -1"));
  bad = Edited("\"saturation_v\": ", "\"saturation_v\": \"6\", \"_was\": ");
  CHECK_THROWS_WITH(sysid::ParseStageParameters(bad, "s.json"),
                    Catch::EndsWith(": drive.saturation_v: expected a finite number, found "
                                    "string \"6\""));
  // The actuator-delay preset: a cross-field rule (map lengths) at the key it names.
  std::string text = sysid::StageParametersToJson(sysid::StageParameters::ActuatorDelay());
  text.replace(text.find("\"map_out_v\": ["), 14, "\"map_out_v\": [-11,");
  CHECK_THROWS_WITH(sysid::ParseStageParameters(text, "s.json"),
                    Catch::StartsWith("s.json:" + At(text, "\"map_out_v\"") +
                                      ": drive.map_out_v: expected drive_map_out_v has as many "
                                      "knots as drive_map_in_v (13), found 14"));
  text = sysid::StageParametersToJson(sysid::StageParameters::ActuatorDelay());
  text.replace(text.find("\"coulomb_mps2\": "), 16, "\"coulomb_mps2\": -1, \"_was\": ");
  CHECK_THROWS_WITH(sysid::ParseStageParameters(text, "s.json"),
                    Catch::Equals("s.json:" + At(text, "\"coulomb_mps2\"") +
                                  ": friction.forward.coulomb_mps2: expected coulomb_mps2 > 0, "
                                  "found -1"));
}
