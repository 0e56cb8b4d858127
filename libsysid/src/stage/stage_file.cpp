// The stage file: JSON with the unit in every key, grouped as model, drive, motor + rail
// (velocity source) or friction (actuator delay), rig, integrator. Unknown keys are errors so that a typo never silently leaves a default.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "detail/json_text.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"
#include "sysid/stage.hpp"

namespace sysid {
namespace {

using Json = nlohmann::json;

struct Context {
  std::string_view text;
  const std::string& source;
  [[noreturn]] void Fail(const std::string& parent, const std::string& key,
                         const std::string& what) const {
    throw InputError(source + ":" + detail::JsonKeyPosition(text, key, parent) + ": " + what);
  }
};

// Reads the object `j` (named `parent`), whose keys must all be in `numbers`, `ints`, `arrays`
// or `objects` (handled by the caller).
struct Section {
  std::vector<std::pair<const char*, double*>> numbers;
  std::vector<std::pair<const char*, int*>> ints;
  std::vector<std::pair<const char*, std::vector<double>*>> arrays;
  std::vector<const char*> objects;

  void Read(const Context& c, const std::string& parent, const Json& j) const {
    if (!j.is_object())
      c.Fail("", parent, "key '" + parent + "': expected an object, found " + j.type_name());
    for (const auto& [key, value] : j.items()) {
      if (key == "units" || key == "note" || (!key.empty() && key[0] == '_')) continue;
      bool known = false;
      for (const auto& [k, target] : numbers) {
        if (key != k) continue;
        known = true;
        if (!value.is_number())
          c.Fail(parent, key, "key '" + key + "': expected a number, found " + value.type_name());
        *target = value.get<double>();
      }
      for (const auto& [k, target] : ints) {
        if (key != k) continue;
        known = true;
        if (!value.is_number_integer())
          c.Fail(parent, key, "key '" + key + "': expected an integer, found " + value.dump());
        *target = value.get<int>();
      }
      for (const auto& [k, target] : arrays) {
        if (key != k) continue;
        known = true;
        if (!value.is_array())
          c.Fail(parent, key,
                 "key '" + key + "': expected an array of numbers, found " + value.type_name());
        target->clear();
        for (const auto& e : value) {
          if (!e.is_number())
            c.Fail(parent, key, "key '" + key + "': expected numbers, found " + e.dump());
          target->push_back(e.get<double>());
        }
      }
      for (const char* k : objects) known = known || key == k;
      if (!known) {
        std::string expected;
        for (const auto& n : numbers)
          expected += std::string(expected.empty() ? "" : ", ") + n.first;
        for (const auto& n : ints) expected += std::string(expected.empty() ? "" : ", ") + n.first;
        for (const auto& n : arrays)
          expected += std::string(expected.empty() ? "" : ", ") + n.first;
        for (const char* n : objects) expected += std::string(expected.empty() ? "" : ", ") + n;
        c.Fail(parent, key,
               "unknown key '" + key + "' in '" + (parent.empty() ? "(top)" : parent) +
                   "' (expected " + expected + ")");
      }
    }
  }
};

Section BranchSection(FrictionBranch& b) {
  return Section{{{"coulomb_mps2", &b.coulomb_mps2},
                  {"static_mps2", &b.static_mps2},
                  {"stribeck_velocity_mps", &b.stribeck_velocity_mps},
                  {"viscous_per_s", &b.viscous_per_s}},
                 {},
                 {},
                 {}};
}

}  // namespace

namespace {

// The model a file describes: its "model" key, else inferred from its sections (files written
// before the key existed describe the actuator-delay stage and carry "friction" or the drive's
// force-actuator keys), else the default velocity source.
StageModel FileModel(const Context& c, const Json& j) {
  if (j.contains("model")) {
    const Json& m = j["model"];
    if (!m.is_string())
      c.Fail("", "model", "key 'model': expected \"velocity-source\" or \"actuator-delay\"");
    try {
      return ParseStageModel(m.get<std::string>());
    } catch (const OptionsError& e) {
      c.Fail("", "model", std::string("key 'model': ") + e.what());
    }
  }
  if (j.contains("friction")) return StageModel::kActuatorDelay;
  if (j.contains("drive") && j["drive"].is_object())
    for (const char* k : {"gain_mps2_per_v", "dead_zone_v", "map_in_v", "map_out_v"})
      if (j["drive"].contains(k)) return StageModel::kActuatorDelay;
  return StageModel::kVelocitySource;
}

}  // namespace

StageParameters ParseStageParameters(std::string_view json_text, const std::string& source) {
  const Json j = detail::ParseJsonText(json_text, source);
  const Context c{json_text, source};
  if (!j.is_object())
    throw InputError(source +
                     ":1:1: expected a JSON object with keys name, model, drive, motor, rail "
                     "(velocity-source) or friction (actuator-delay), rig, integrator");
  const StageModel model = FileModel(c, j);
  const bool vs = model == StageModel::kVelocitySource;
  StageParameters p =
      vs ? StageParameters::Default() : StageParameters::ActuatorDelay();
  const std::string model_name = ToString(model);
  auto other_model = [&](const std::string& parent, const std::string& key) {
    c.Fail(parent, key,
           "key '" + key + "' belongs to the " + (vs ? "actuator-delay" : "velocity-source") +
               " model; this stage's model is " + model_name + " (key 'model')");
  };
  for (const auto& [key, value] : j.items()) {
    if (key == "units" || key == "note" || key == "model" || (!key.empty() && key[0] == '_'))
      continue;
    if (key == "name") {
      if (!value.is_string()) c.Fail("", key, "key 'name': expected a string");
      p.name = value.get<std::string>();
    } else if (key == "drive") {
      if (vs && value.is_object())
        for (const char* k : {"gain_mps2_per_v", "dead_zone_v", "map_in_v", "map_out_v"})
          if (value.contains(k)) other_model(key, k);
      Section{{{"gain_mps2_per_v", &p.gain_mps2_per_v},
               {"dead_zone_v", &p.dead_zone_v},
               {"saturation_v", &p.saturation_v},
               {"transport_delay_s", &p.transport_delay_s},
               {"lag_time_constant_s", &p.lag_time_constant_s}},
              {},
              {{"map_in_v", &p.drive_map_in_v}, {"map_out_v", &p.drive_map_out_v}},
              {}}
          .Read(c, key, value);
    } else if (key == "motor") {
      if (!vs) other_model("", key);
      Section{{{"pole_per_s", &p.motor.pole_per_s},
               {"dead_zone_forward_v", &p.motor.dead_zone_forward_v},
               {"dead_zone_backward_v", &p.motor.dead_zone_backward_v}},
              {},
              {{"speed_map_in_v", &p.motor.speed_map_in_v},
               {"speed_map_out_mps", &p.motor.speed_map_out_mps}},
              {}}
          .Read(c, key, value);
    } else if (key == "rail") {
      if (!vs) other_model("", key);
      Section{{{"coulomb_mps2", &p.rail.coulomb_mps2},
               {"static_mps2", &p.rail.static_mps2},
               {"stribeck_velocity_mps", &p.rail.stribeck_velocity_mps}},
              {},
              {},
              {}}
          .Read(c, key, value);
    } else if (key == "friction") {
      if (vs) other_model("", key);
      Section{{{"bristle_stiffness_per_s2", &p.bristle_stiffness_per_s2},
               {"bristle_damping_per_s", &p.bristle_damping_per_s}},
              {},
              {},
              {"forward", "backward"}}
          .Read(c, key, value);
      if (value.contains("forward")) BranchSection(p.forward).Read(c, "forward", value["forward"]);
      if (value.contains("backward"))
        BranchSection(p.backward).Read(c, "backward", value["backward"]);
    } else if (key == "rig") {
      Section{{{"sample_rate_hz", &p.sample_rate_hz},
               {"dac_range_v", &p.dac_range_v},
               {"encoder_resolution_m", &p.encoder_resolution_m},
               {"position_noise_m", &p.position_noise_m},
               {"travel_min_m", &p.travel_min_m},
               {"travel_max_m", &p.travel_max_m},
               {"max_velocity_mps", &p.max_velocity_mps},
               {"initial_position_m", &p.initial_position_m}},
              {{"dac_bits", &p.dac_bits}},
              {},
              {}}
          .Read(c, key, value);
    } else if (key == "integrator") {
      Section{{{"relative_tolerance", &p.relative_tolerance},
               {"position_tolerance_m", &p.position_tolerance_m}},
              {},
              {},
              {}}
          .Read(c, key, value);
    } else {
      c.Fail("", key,
             "unknown key '" + key +
                 "' (expected name, model, drive, motor, rail, friction, rig, integrator)");
    }
  }
  try {
    p.Validate();
  } catch (const OptionsError& e) {
    throw InputError(source + ": invalid stage parameters: " + e.what());
  }
  return p;
}

StageParameters ReadStageParameters(const std::string& path) {
  return ParseStageParameters(ReadFile(path), path);
}

std::string StageParametersToJson(const StageParameters& p) {
  using OJ = nlohmann::ordered_json;
  auto branch = [](const FrictionBranch& b) {
    OJ o;
    o["coulomb_mps2"] = b.coulomb_mps2;
    o["static_mps2"] = b.static_mps2;
    o["stribeck_velocity_mps"] = b.stribeck_velocity_mps;
    o["viscous_per_s"] = b.viscous_per_s;
    return o;
  };
  const bool vs = p.model == StageModel::kVelocitySource;
  OJ j;
  j["name"] = p.name;
  j["model"] = ToString(p.model);
  j["note"] =
      "Virtual piezo stage for libsysid (docs/virtual_stage.md). SI units; each key ends with "
      "its unit (mps = m/s, mps2 = m/s^2, per_s = 1/s, per_s2 = 1/s^2, v = V). Forces are per "
      "unit mass. Only the sections of this model are written.";
  OJ drive;
  if (!vs) {
    drive["gain_mps2_per_v"] = p.gain_mps2_per_v;
    drive["dead_zone_v"] = p.dead_zone_v;
  }
  drive["saturation_v"] = p.saturation_v;
  drive["transport_delay_s"] = p.transport_delay_s;
  drive["lag_time_constant_s"] = p.lag_time_constant_s;
  if (!vs) {
    drive["map_in_v"] = p.drive_map_in_v;
    drive["map_out_v"] = p.drive_map_out_v;
  }
  j["drive"] = drive;
  if (vs) {
    OJ motor;
    motor["pole_per_s"] = p.motor.pole_per_s;
    motor["dead_zone_forward_v"] = p.motor.dead_zone_forward_v;
    motor["dead_zone_backward_v"] = p.motor.dead_zone_backward_v;
    motor["speed_map_in_v"] = p.motor.speed_map_in_v;
    motor["speed_map_out_mps"] = p.motor.speed_map_out_mps;
    j["motor"] = motor;
    OJ rail;
    rail["coulomb_mps2"] = p.rail.coulomb_mps2;
    rail["static_mps2"] = p.rail.static_mps2;
    rail["stribeck_velocity_mps"] = p.rail.stribeck_velocity_mps;
    j["rail"] = rail;
  } else {
    OJ friction;
    friction["bristle_stiffness_per_s2"] = p.bristle_stiffness_per_s2;
    friction["bristle_damping_per_s"] = p.bristle_damping_per_s;
    friction["forward"] = branch(p.forward);
    friction["backward"] = branch(p.backward);
    j["friction"] = friction;
  }
  OJ rig;
  rig["sample_rate_hz"] = p.sample_rate_hz;
  rig["dac_bits"] = p.dac_bits;
  rig["dac_range_v"] = p.dac_range_v;
  rig["encoder_resolution_m"] = p.encoder_resolution_m;
  rig["position_noise_m"] = p.position_noise_m;
  rig["travel_min_m"] = p.travel_min_m;
  rig["travel_max_m"] = p.travel_max_m;
  rig["max_velocity_mps"] = p.max_velocity_mps;
  rig["initial_position_m"] = p.initial_position_m;
  j["rig"] = rig;
  OJ integ;
  integ["relative_tolerance"] = p.relative_tolerance;
  integ["position_tolerance_m"] = p.position_tolerance_m;
  j["integrator"] = integ;
  return j.dump(2) + "\n";
}

StageParameters LoadStage(const std::string& preset_or_path) {
  if (StageParameters::IsPresetName(preset_or_path)) return StageParameters::Preset(preset_or_path);
  return ReadStageParameters(preset_or_path);
}

void WriteStageParameters(const std::string& path, const StageParameters& parameters) {
  WriteFileAtomically(path, StageParametersToJson(parameters));
}

}  // namespace sysid
