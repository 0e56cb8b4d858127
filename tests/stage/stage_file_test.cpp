// The stage parameter file: round trip, the bundled file, and error messages.
#include <algorithm>
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "support/test_support.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"
#include "sysid/stage.hpp"

TEST_CASE("the bundled stage.json is the built-in calibrated stage", "[stage][file]") {
  const auto file =
      sysid::ReadStageParameters(sysid::test::SourcePath("datasets/virtual/stage.json"));
  CHECK(sysid::StageParametersToJson(file) ==
        sysid::StageParametersToJson(sysid::StageParameters::Default()));
  const auto back = sysid::ParseStageParameters(sysid::StageParametersToJson(file), "mem.json");
  REQUIRE(back.model() == sysid::StageModel::kVelocitySource);
  CHECK(back.velocity_source().motor.speed_map_out_mps ==
        file.velocity_source().motor.speed_map_out_mps);
  CHECK(back.velocity_source().hysteresis.weights == file.velocity_source().hysteresis.weights);
  // The velocity source has no actuator-delay fields: asking for them is an error.
  CHECK_THROWS_AS(file.actuator_delay(), sysid::OptionsError);
}

TEST_CASE("the writer's layout is the published file's, byte for byte", "[stage][file]") {
  // The reference is the bundled file (written before the structs were described), less the
  // generator key WriteStageParameters adds.
  std::string bundled = sysid::ReadFile(sysid::test::SourcePath("datasets/virtual/stage.json"));
  const size_t at = bundled.find("  \"_generator\"");
  REQUIRE(at != std::string::npos);
  bundled.erase(at, bundled.find('\n', at) + 1 - at);
  CHECK(sysid::StageParametersToJson(sysid::StageParameters::Default()) == bundled);
  // The actuator delay's force actuator sits in "drive" around the driver's keys, its map
  // without the member's "drive_" prefix; its LuGre rail in "friction".
  const sysid::StageParameters delay = sysid::StageParameters::ActuatorDelay();
  const auto ad = nlohmann::ordered_json::parse(sysid::StageParametersToJson(delay));
  auto keys = [](const nlohmann::ordered_json& o) {
    std::vector<std::string> k;
    for (const auto& item : o.items()) k.push_back(item.key());
    return k;
  };
  CHECK(keys(ad) == std::vector<std::string>{"name", "model", "note", "drive", "friction", "rig",
                                             "integrator"});
  CHECK(keys(ad["drive"]) == std::vector<std::string>{"gain_mps2_per_v", "dead_zone_v",
                                                      "saturation_v", "transport_delay_s",
                                                      "lag_time_constant_s", "map_in_v",
                                                      "map_out_v"});
  CHECK(keys(ad["friction"]) == std::vector<std::string>{"bristle_stiffness_per_s2",
                                                         "bristle_damping_per_s", "forward",
                                                         "backward"});
  // One rate (record = control) is written as sample_rate_hz alone; the default work budget is
  // not written.
  CHECK(keys(ad["rig"]) == std::vector<std::string>{"sample_rate_hz", "dac_bits", "dac_range_v",
                                                    "encoder_resolution_m", "position_noise_m",
                                                    "travel_min_m", "travel_max_m",
                                                    "max_velocity_mps", "initial_position_m"});
  CHECK(keys(ad["integrator"]) ==
        std::vector<std::string>{"relative_tolerance", "position_tolerance_m"});
  CHECK(ad["drive"]["map_in_v"] == nlohmann::ordered_json(delay.actuator_delay().drive_map_in_v));
  CHECK(ad["friction"]["backward"]["coulomb_mps2"] == delay.actuator_delay().backward.coulomb_mps2);
}

TEST_CASE("the rail's memory: written, read back, 0 when a file predates it", "[stage][file]") {
  const sysid::StageParameters p = sysid::StageParameters::Default();
  REQUIRE(p.velocity_source().rail.memory_time_s > 0);
  std::string text = sysid::StageParametersToJson(p);
  CHECK(sysid::ParseStageParameters(text, "m.json").velocity_source().rail.memory_time_s ==
        p.velocity_source().rail.memory_time_s);
  // A complete file written before the key existed: no memory, everything else as written.
  const auto key = text.find("\"memory_time_s\"");
  REQUIRE(key != std::string::npos);
  const auto comma = text.rfind(',', key);
  text.erase(comma, text.find('\n', key) - comma);
  const auto old = sysid::ParseStageParameters(text, "old.json");
  CHECK(old.velocity_source().rail.memory_time_s == 0.0);
  CHECK(old.velocity_source().rail.static_mps2 == p.velocity_source().rail.static_mps2);
  // Out of range is a positioned error.
  CHECK_THROWS_WITH(
      sysid::ParseStageParameters(
          "{\"preset\": \"virtual\", \"rail\": {\"memory_time_s\": -0.01}}", "r.json"),
      Catch::Contains("rail.memory_time_s") && Catch::Contains("0 <= memory_time_s <= 1"));
}

TEST_CASE("the thrust limit: written when set, read back, absent means none", "[stage][file]") {
  sysid::StageParameters p = sysid::StageParameters::Default();
  REQUIRE(p.velocity_source().motor.thrust_limit_mps2 == 0);
  CHECK(sysid::StageParametersToJson(p).find("thrust_limit_mps2") == std::string::npos);
  p.velocity_source().motor.pole_per_s = 2000;
  p.velocity_source().motor.thrust_limit_mps2 = 8;
  const std::string text = sysid::StageParametersToJson(p);
  CHECK(sysid::ParseStageParameters(text, "t.json").velocity_source().motor.thrust_limit_mps2 == 8);
  CHECK_THROWS_WITH(
      sysid::ParseStageParameters(
          "{\"preset\": \"virtual\", \"motor\": {\"thrust_limit_mps2\": 2}}", "t.json"),
      Catch::Contains("motor.thrust_limit_mps2") && Catch::Contains("> rail.static_mps2"));
}

TEST_CASE("velocity-source is the loop-rate candidate C, virtual-1khz is C at 1 kHz",
          "[stage][file]") {
  const sysid::StageParameters c = sysid::StageParameters::VelocitySource();
  CHECK(c.rig.sample_rate_hz == 10000);
  CHECK(c.RecordRateHz() == 1000);
  CHECK(c.RecordStride() == 10);
  CHECK(c.driver.lag_time_constant_s == 0.0001);
  REQUIRE(sysid::StageParameters::IsPresetName("virtual-1khz"));
  const sysid::StageParameters a = sysid::LoadStage("virtual-1khz");
  CHECK(a.model() == sysid::StageModel::kVelocitySource);
  CHECK(a.rig.sample_rate_hz == 1000);
  CHECK(a.RecordRateHz() == 1000);
  CHECK(a.driver.lag_time_constant_s == 0.0003);
  // Both give the paper's pulse table (the speed map does not depend on the rates or the lag).
  for (const auto& [u, v] : sysid::StageParameters::PaperPulseTable()) {
    CHECK(c.SteadyVelocity(u) == Approx(v).epsilon(1e-10));
    CHECK(a.SteadyVelocity(u) == Approx(v).epsilon(1e-10));
  }
  // They differ in the two rates, the lag and the name only: the whole file compared.
  sysid::StageParameters moved = a;
  moved.name = c.name;
  moved.rig.sample_rate_hz = 10000;
  moved.rig.record_rate_hz = 1000;
  moved.driver.lag_time_constant_s = 0.0001;
  CHECK(sysid::StageParametersToJson(moved) == sysid::StageParametersToJson(c));
  CHECK(sysid::StageParametersToJson(sysid::LoadStage("velocity-source")) ==
        sysid::StageParametersToJson(c));
  // A file may change it like any preset.
  CHECK(sysid::ParseStageParameters("{\"preset\": \"virtual-1khz\", \"rig\": "
                                    "{\"position_noise_m\": 0}}",
                                    "a.json")
            .driver.lag_time_constant_s == 0.0003);
  CHECK_THROWS_WITH(sysid::StageParameters::Preset("fast"), Catch::Contains("virtual-1khz"));
  CHECK_THROWS_WITH(sysid::ParseStageParameters("{\"preset\": \"fast\"}", "p.json"),
                    Catch::Contains("virtual-1khz"));
}

TEST_CASE("every preset name loads, and every message that lists the presets lists them all",
          "[stage][file]") {
  const auto& names = sysid::StageParameters::PresetNames();
  REQUIRE(names.size() == 6);
  CHECK(names.front() == "virtual");
  for (const std::string& name : names) {
    INFO(name);
    CHECK(sysid::StageParameters::IsPresetName(name));
    const sysid::StageParameters p = sysid::StageParameters::Preset(name);
    CHECK_NOTHROW(p.Validate());
    // A file naming the preset and nothing else is the preset.
    CHECK(sysid::StageParametersToJson(
              sysid::ParseStageParameters("{\"preset\": \"" + name + "\"}", "p.json")) ==
          sysid::StageParametersToJson(p));
  }
  CHECK_FALSE(sysid::StageParameters::IsPresetName("Virtual"));
  CHECK_FALSE(sysid::StageParameters::IsPresetName(""));
  // The aliases are the same stage, the others differ from each other.
  CHECK(sysid::StageParametersToJson(sysid::StageParameters::Preset("virtual")) ==
        sysid::StageParametersToJson(sysid::StageParameters::Preset("drive-hysteresis")));
  CHECK(sysid::StageParametersToJson(sysid::StageParameters::Preset("velocity-source")) !=
        sysid::StageParametersToJson(sysid::StageParameters::Preset("virtual-1khz")));
  std::string preset_error, file_error, incomplete_error;
  try {
    sysid::StageParameters::Preset("fast");
  } catch (const std::exception& e) {
    preset_error = e.what();
  }
  try {
    sysid::ParseStageParameters("{\"preset\": \"fast\"}", "p.json");
  } catch (const std::exception& e) {
    file_error = e.what();
  }
  try {
    sysid::ParseStageParameters("{\"model\": \"velocity-source\"}", "c.json");
  } catch (const std::exception& e) {
    incomplete_error = e.what();
  }
  for (const std::string& name : names) {
    CHECK_THAT(preset_error, Catch::Contains("'fast'") && Catch::Contains(name));
    CHECK_THAT(file_error, Catch::Contains("p.json") && Catch::Contains(name));
    CHECK_THAT(incomplete_error, Catch::Contains("c.json") && Catch::Contains(name));
  }
}

TEST_CASE("the default is C with the drive's hysteresis and creep, files without them have none",
          "[stage][file]") {
  const sysid::StageParameters d = sysid::StageParameters::Default();
  const sysid::StageParameters c = sysid::StageParameters::VelocitySource();
  REQUIRE(d.velocity_source().hysteresis.enabled());
  REQUIRE(d.velocity_source().creep.enabled());
  CHECK_FALSE(c.velocity_source().hysteresis.enabled());
  CHECK_FALSE(c.velocity_source().creep.enabled());
  CHECK(d.velocity_source().hysteresis.thresholds_v == std::vector<double>{0.05, 0.1, 0.2});
  CHECK(d.velocity_source().creep.loop_share == 0.3);
  for (const char* name : {"virtual", "drive-hysteresis"})
    CHECK(sysid::StageParametersToJson(sysid::LoadStage(name)) ==
          sysid::StageParametersToJson(d));
  // Both settle on the paper's pulse table: the operators' held lag moved the dead zones and knots.
  for (const auto& [u, v] : sysid::StageParameters::PaperPulseTable())
    CHECK(d.SteadyVelocity(u) == Approx(v).epsilon(1e-10));
  // A complete file without the blocks (C's, as written) is read as it is, not as the default
  // it would otherwise be filled from; the default's own file keeps them.
  const std::string c_text = sysid::StageParametersToJson(c);
  REQUIRE(c_text.find("hysteresis") == std::string::npos);
  const sysid::StageParameters c_back = sysid::ParseStageParameters(c_text, "c.json");
  CHECK_FALSE(c_back.velocity_source().hysteresis.enabled());
  CHECK_FALSE(c_back.velocity_source().creep.enabled());
  CHECK(sysid::StageParametersToJson(c_back) == c_text);
  const std::string d_text = sysid::StageParametersToJson(d);
  CHECK(sysid::StageParametersToJson(sysid::ParseStageParameters(d_text, "d.json")) == d_text);
  // A preset file changes what it names and keeps the rest of its preset.
  const auto vs = sysid::ParseStageParameters(
      "{\"preset\": \"velocity-source\", \"rig\": {\"position_noise_m\": 0}}", "v.json");
  CHECK_FALSE(vs.velocity_source().hysteresis.enabled());
  const auto dv = sysid::ParseStageParameters(
      "{\"preset\": \"virtual\", \"rig\": {\"position_noise_m\": 0}}", "d.json");
  CHECK(dv.velocity_source().hysteresis.thresholds_v ==
        d.velocity_source().hysteresis.thresholds_v);
}

TEST_CASE("stage files name their model, presets load by name", "[stage][file]") {
  // The actuator-delay preset round-trips and keeps its model.
  const auto ad = sysid::StageParameters::ActuatorDelay();
  const auto back = sysid::ParseStageParameters(sysid::StageParametersToJson(ad), "ad.json");
  CHECK(back.model() == sysid::StageModel::kActuatorDelay);
  CHECK(sysid::StageParametersToJson(back) == sysid::StageParametersToJson(ad));
  CHECK(sysid::LoadStage("actuator-delay").driver.transport_delay_s == 0.002);
  CHECK(sysid::LoadStage("virtual").model() == sysid::StageModel::kVelocitySource);
  // A file without "model" written before the key existed (it has "friction") is actuator delay.
  std::string old_file = sysid::StageParametersToJson(sysid::StageParameters::ActuatorDelay());
  old_file.erase(old_file.find("\"model\""), old_file.find("\"note\"") - old_file.find("\"model\""));
  CHECK(sysid::ParseStageParameters(old_file, "o.json").model() ==
        sysid::StageModel::kActuatorDelay);
  // "preset": a partial file changes a preset, which gives the model and the other values.
  const auto partial = sysid::ParseStageParameters(
      "{\"preset\": \"actuator-delay\", \"friction\": {\"bristle_damping_per_s\": 900}}", "p.json");
  CHECK(partial.model() == sysid::StageModel::kActuatorDelay);
  CHECK(partial.actuator_delay().bristle_damping_per_s == 900);
  CHECK(partial.driver.transport_delay_s ==
        sysid::StageParameters::ActuatorDelay().driver.transport_delay_s);
  CHECK(sysid::ParseStageParameters("{\"preset\": \"virtual\", \"rig\": {\"position_noise_m\": 0}}",
                                    "n.json")
            .model() == sysid::StageModel::kVelocitySource);
  CHECK_THROWS_WITH(sysid::ParseStageParameters("{\"preset\": \"fast\"}", "p.json"),
                    Catch::StartsWith("p.json:1:2: preset: expected a preset name"));
  CHECK_THROWS_WITH(
      sysid::ParseStageParameters("{\"preset\": \"virtual\",\n \"model\": \"actuator-delay\"}",
                                  "p.json"),
      Catch::StartsWith("p.json:2:2: model: expected the model of preset 'virtual' "
                        "(velocity-source), found 'actuator-delay'"));
  // A section of the other model is an error naming both.
  CHECK_THROWS_WITH(
      sysid::ParseStageParameters("{\"model\": \"velocity-source\",\n \"friction\": {}}", "m.json"),
      Catch::StartsWith("m.json:2:2: key 'friction' belongs to the actuator-delay model"));
  CHECK_THROWS_WITH(sysid::ParseStageParameters("{\"model\": \"piezo\"}", "m.json"),
                    Catch::Contains("is not one of velocity-source, actuator-delay"));
  CHECK_THROWS_WITH(
      sysid::ParseStageParameters(
          "{\"preset\": \"virtual\", \"motor\": {\"dead_zone_forward_v\": 1.35}}", "m.json"),
      Catch::Contains("knots outside the dead zone"));
  CHECK_THROWS_AS(sysid::StageParameters::Preset("fast"), sysid::OptionsError);
}

TEST_CASE("a stage file without a preset must give every section and key", "[stage][file]") {
  // Issue #14: `{}` or a file missing `friction` used to run on built-in defaults.
  CHECK_THROWS_WITH(sysid::ParseStageParameters("{}", "e.json"),
                    Catch::StartsWith("e.json:1:1: expected section 'drive' of the "
                                      "velocity-source model, found none (a stage file gives "
                                      "every section and key of its model, or names \"preset\""));
  std::string text = sysid::StageParametersToJson(sysid::StageParameters::ActuatorDelay());
  const size_t from = text.find("  \"friction\"");
  const size_t to = text.find("  \"rig\"");
  REQUIRE(from != std::string::npos);
  REQUIRE(to != std::string::npos);
  CHECK_THROWS_WITH(sysid::ParseStageParameters(text.substr(0, from) + text.substr(to), "f.json"),
                    Catch::StartsWith("f.json:1:1: expected section 'friction' of the "
                                      "actuator-delay model"));
  // A missing key inside a section: at the section, naming the key.
  text = sysid::StageParametersToJson(sysid::StageParameters::Default());
  const size_t key = text.find("    \"dac_bits\"");
  REQUIRE(key != std::string::npos);
  text.erase(key, text.find('\n', key) + 1 - key);
  CHECK_THROWS_WITH(sysid::ParseStageParameters(text, "k.json"),
                    Catch::StartsWith("k.json:" + std::to_string(1 + std::count(text.begin(),
                                      text.begin() + static_cast<long>(text.find("\"rig\"")), '\n')) +
                                      ":3: rig: missing required key 'dac_bits'"));
  // The same file with a preset is complete: the key comes from the preset.
  text.insert(1, "\"preset\": \"virtual\",");
  CHECK(sysid::ParseStageParameters(text, "k.json").rig.dac_bits ==
        sysid::StageParameters::Default().rig.dac_bits);
  // The velocity-source drive section does not need the actuator-delay drive keys.
  CHECK_NOTHROW(sysid::ParseStageParameters(
      sysid::StageParametersToJson(sysid::StageParameters::Default()), "vs.json"));
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
  // The bundled stage writes its two rates apart (10 kHz loop, 1 kHz records); the control
  // rate is the library's sample_rate_hz.
  auto bad = Edited("\"control_rate_hz\": 10000.0", "\"control_rate_hz\": 0");
  CHECK_THROWS_WITH(sysid::ParseStageParameters(bad, "s.json"),
                    Catch::Equals("s.json:" + At(bad, "\"control_rate_hz\"") +
                                  ": rig.control_rate_hz: expected sample_rate_hz > 0, found 0"));
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
  // The encoder's resolution and the noise are bounded on both sides (1e-320 m made every
  // recorded position inf, noise of 1e308 m every tracking error).
  const std::string tiny = R"({"preset": "virtual", "rig": {"encoder_resolution_m": 1e-320}})";
  CHECK_THROWS_WITH(sysid::ParseStageParameters(tiny, "e.json"),
                    Catch::StartsWith("e.json:1:31: rig.encoder_resolution_m: expected 1e-15 <= "
                                      "encoder_resolution_m <= the travel"));
  const std::string loud = R"({"preset": "virtual", "rig": {"position_noise_m": 1e308}})";
  CHECK_THROWS_WITH(sysid::ParseStageParameters(loud, "n.json"),
                    Catch::StartsWith("n.json:1:31: rig.position_noise_m: expected 0 <= "
                                      "position_noise_m <= the travel"));
  CHECK_NOTHROW(sysid::ParseStageParameters(
      R"({"preset": "virtual", "rig": {"encoder_resolution_m": 1e-9, "position_noise_m": 1e-6}})",
      "ok.json"));
}

TEST_CASE("each plant validates its own fields over the shared driver", "[stage][file]") {
  using Catch::Contains;
  // The actuator delay: its dead zone must stay below the driver's clip, checked over the
  // driver (ValidateWithDriver) and by the stage's Validate; its own Validate does not see the
  // driver.
  sysid::StageParameters ad = sysid::StageParameters::ActuatorDelay();
  ad.actuator_delay().dead_zone_v = ad.driver.saturation_v;
  CHECK_THROWS_WITH(ad.Validate(), Contains("StageParameters::saturation_v") &&
                                       Contains("saturation_v > dead_zone_v"));
  CHECK_THROWS_WITH(
      ad.actuator_delay().ValidateWithDriver(ad.driver),
      Contains("StageParameters::saturation_v") && Contains("saturation_v > dead_zone_v"));
  CHECK_NOTHROW(ad.actuator_delay().Validate());
  sysid::DriverSettings wider = ad.driver;
  wider.saturation_v += 1;
  CHECK_NOTHROW(ad.actuator_delay().ValidateWithDriver(wider));
  // The velocity source: its dead zones likewise, named by the file's path.
  sysid::StageParameters vs = sysid::StageParameters::VelocitySource();
  vs.driver.saturation_v = vs.velocity_source().motor.dead_zone_forward_v;
  CHECK_THROWS_WITH(vs.Validate(), Contains("motor.dead_zone_forward_v") &&
                                       Contains("dead_zone_forward_v < saturation_v"));
  CHECK_THROWS_WITH(vs.velocity_source().ValidateWithDriver(vs.driver),
                    Contains("motor.dead_zone_forward_v"));
  CHECK_NOTHROW(vs.velocity_source().Validate());
  CHECK_NOTHROW(sysid::StageParameters::VelocitySource().velocity_source().Validate());
  // Each shared setting validates its own fields.
  sysid::DriverSettings driver;
  driver.lag_time_constant_s = 0;
  CHECK_THROWS_WITH(driver.Validate(), Contains("StageParameters::lag_time_constant_s = 0"));
  sysid::RigSettings rig;
  rig.travel_max_m = rig.travel_min_m;
  CHECK_THROWS_WITH(rig.Validate(), Contains("StageParameters::travel_max_m") &&
                                        Contains("travel_max_m > travel_min_m"));
  sysid::IntegratorSettings integrator;
  integrator.max_steps_per_sample = 9;
  CHECK_THROWS_WITH(integrator.Validate(), Contains("StageParameters::max_steps_per_sample = 9"));
  CHECK_NOTHROW(sysid::DriverSettings{}.Validate());
  CHECK_NOTHROW(sysid::RigSettings{}.Validate());
  CHECK_NOTHROW(sysid::IntegratorSettings{}.Validate());
  // The stage validates the plant it holds: the velocity source's rig with the actuator
  // delay's plant is a valid actuator-delay stage, and writes only that plant's sections.
  sysid::StageParameters swapped = sysid::StageParameters::VelocitySource();
  swapped.plant = sysid::StageParameters::ActuatorDelay().actuator_delay();
  CHECK_NOTHROW(swapped.Validate());
  CHECK(swapped.model() == sysid::StageModel::kActuatorDelay);
  CHECK_THROWS_WITH(swapped.velocity_source(), Contains("model is actuator-delay"));
  const std::string text = sysid::StageParametersToJson(swapped);
  CHECK(text.find("\"friction\"") != std::string::npos);
  CHECK(text.find("\"motor\"") == std::string::npos);
  CHECK(sysid::StageParametersToJson(sysid::ParseStageParameters(text, "s.json")) == text);
  // The shared settings are checked whichever plant is held.
  swapped.driver.saturation_v = 0;
  CHECK_THROWS_WITH(swapped.Validate(), Contains("StageParameters::saturation_v"));
}
