// The stage file: JSON with the unit in every key, grouped as model, drive, motor + rail
// (velocity source) or friction (actuator delay), rig, integrator. Unknown keys are errors so that a typo never silently leaves a default.
#include <algorithm>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "core/json_text.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"
#include "sysid/io_output.hpp"
#include "sysid/stage.hpp"

namespace sysid {
namespace {

constexpr double kMaxStageSampleRateHz = 1e6;
// Why a key or section is required: said in every such message.
std::string CompleteRule() {
  return "a stage file gives every section and key of its model, or names \"preset\": NAME (" +
         StageParameters::PresetNameList() + ") whose values fill what it leaves out";
}

// Reads the object `node`, whose keys must all be in `numbers`, `ints`, `arrays` or `objects`
// (handled by the caller). With `complete` (a file that names no "preset") every key but those
// in `optional` must be written; otherwise keys left out keep the preset's value.
struct Section {
  std::vector<std::pair<const char*, double*>> numbers;
  std::vector<std::pair<const char*, int*>> ints;
  std::vector<std::pair<const char*, std::vector<double>*>> arrays;
  std::vector<const char*> objects;

  void Read(const internal::JsonNode& node, bool complete,
            const std::vector<std::string>& optional = {}) const {
    std::vector<std::string> known;
    for (const auto& n : numbers) known.push_back(n.first);
    for (const auto& n : ints) known.push_back(n.first);
    for (const auto& n : arrays) known.push_back(n.first);
    for (const char* n : objects) known.push_back(n);
    node.ExpectObject(known, {"units", "note"});
    for (const auto& [k, target] : numbers)
      if (node.Has(k)) *target = node.Get(k).Number();
    for (const auto& [k, target] : ints)
      if (node.Has(k))
        *target = static_cast<int>(node.Get(k).Integer(std::numeric_limits<int>::min(),
                                                       std::numeric_limits<int>::max()));
    for (const auto& [k, target] : arrays)
      if (node.Has(k)) *target = node.Get(k).Numbers();
    if (!complete) return;
    for (const auto& k : known)
      if (!node.Has(k) && std::find(optional.begin(), optional.end(), k) == optional.end())
        node.Fail("missing required key '" + k + "' (" + CompleteRule() + ")");
  }
};

// The JSON pointer of the StageParameters field an OptionsError names (its field():
// "forward.coulomb_mps2", "drive_map_in_v[3]", "sample_rate_hz"); empty when not in the file.
std::string FieldPointer(const internal::JsonDocument& doc, const std::string& field) {
  std::string suffix = "/";
  for (char ch : field) {
    if (ch == '.' || ch == '[') suffix += '/';
    else if (ch != ']') suffix += ch;
  }
  std::string p = doc.FindSuffix(suffix);
  // The control rate is written either as sample_rate_hz (both rates) or as control_rate_hz.
  if (p.empty() && suffix == "/sample_rate_hz") p = doc.FindSuffix("/control_rate_hz");
  if (p.empty() && suffix.rfind("/drive_", 0) == 0) p = doc.FindSuffix("/" + suffix.substr(7));
  return p;
}

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
StageModel FileModel(const internal::JsonNode& root, const StageParameters* preset) {
  const nlohmann::json& j = root.json();
  if (preset) {
    if (root.Has("model") && root.Get("model").String() != ToString(preset->model()))
      root.Get("model").Fail("expected the model of preset '" + root.Get("preset").String() +
                             "' (" + ToString(preset->model()) + "), found '" +
                             root.Get("model").String() + "'");
    return preset->model();
  }
  if (root.Has("model")) {
    const internal::JsonNode m = root.Get("model");
    const std::string name = m.String();
    try {
      return ParseStageModel(name);
    } catch (const OptionsError& e) {
      m.Fail(e.what());
    }
  }
  if (j.contains("friction")) return StageModel::kActuatorDelay;
  if (j.contains("drive") && j["drive"].is_object())
    for (const char* k : {"gain_mps2_per_v", "dead_zone_v", "map_in_v", "map_out_v"})
      if (j["drive"].contains(k)) return StageModel::kActuatorDelay;
  return StageModel::kVelocitySource;
}

}  // namespace

// Long function: the stage file's schema, read section by section in the file's order, each
// section's keys next to the fields they set.
StageParameters ParseStageParameters(std::string_view json_text, const std::string& source) {
  const internal::JsonDocument doc(json_text, source);
  const internal::JsonNode root = doc.Root();
  root.ExpectObject(
      {"name", "preset", "model", "drive", "motor", "rail", "friction", "rig", "integrator"},
      {"units", "note"});
  // "preset": the file changes a preset, which supplies every value it leaves out. Without
  // it the file must be complete (a missing section or key is an error, never a default).
  std::optional<StageParameters> preset;
  if (root.Has("preset")) {
    const internal::JsonNode at = root.Get("preset");
    const std::string name = at.String();
    if (!StageParameters::IsPresetName(name))
      at.Expected("a preset name (" + StageParameters::PresetNameList() + ")");
    preset = StageParameters::Preset(name);
  }
  const bool complete = !preset;
  const StageModel model = FileModel(root, preset ? &*preset : nullptr);
  const bool vs = model == StageModel::kVelocitySource;
  StageParameters p =
      preset ? *preset : vs ? StageParameters::Default() : StageParameters::ActuatorDelay();
  // The plant's own fields: exactly one of these is set, that of `model`.
  VelocitySourcePlant* const vsp = std::get_if<VelocitySourcePlant>(&p.plant);
  ActuatorDelayPlant* const adp = std::get_if<ActuatorDelayPlant>(&p.plant);
  // A complete file written before the rail had memory leaves the key out: no memory; one
  // without the drive's hysteresis or creep blocks has none (the default stage has both).
  if (complete && vsp) {
    vsp->rail.memory_time_s = 0.0;
    vsp->hysteresis = DriveHysteresis{};
    vsp->creep = DriveCreep{};
  }
  const std::string model_name = ToString(model);
  auto other_model = [&](const internal::JsonNode& at) {
    const std::string key = at.pointer().substr(at.pointer().rfind('/') + 1);
    throw InputError(doc.Where(at.pointer()) + ": key '" + key + "' belongs to the " +
                     (vs ? "actuator-delay" : "velocity-source") + " model; this stage's model is " +
                     model_name + " (key 'model')");
  };
  for (const auto& [key, value] : root.json().items()) {
    if (key == "units" || key == "note" || key == "model" || key == "preset" ||
        (!key.empty() && key[0] == '_'))
      continue;
    if (key == "name") {
      p.name = root.Get(key).String();
    } else if (key == "drive") {
      if (vs && value.is_object())
        for (const char* k : {"gain_mps2_per_v", "dead_zone_v", "map_in_v", "map_out_v"})
          if (value.contains(k)) other_model(root.Get(key).Get(k));
      // The driver's shared keys, and the actuator delay's force actuator in the same block.
      Section drive{{{"saturation_v", &p.saturation_v},
                     {"transport_delay_s", &p.transport_delay_s},
                     {"lag_time_constant_s", &p.lag_time_constant_s}},
                    {},
                    {},
                    {"hysteresis", "creep"}};
      if (adp) {
        drive.numbers.insert(drive.numbers.begin(), {{"gain_mps2_per_v", &adp->gain_mps2_per_v},
                                                     {"dead_zone_v", &adp->dead_zone_v}});
        drive.arrays = {{"map_in_v", &adp->drive_map_in_v}, {"map_out_v", &adp->drive_map_out_v}};
      }
      drive.Read(root.Get(key), complete, {"hysteresis", "creep"});
      if (root.Get(key).Has("hysteresis")) {
        // The ceramic's hysteresis (velocity source only); a file without the block has none.
        const internal::JsonNode h = root.Get(key).Get("hysteresis");
        if (!vsp) other_model(h);
        DriveHysteresis& dh = vsp->hysteresis;
        Section{{{"rate_time_constant_s", &dh.rate_time_constant_s}, {"asymmetry", &dh.asymmetry}},
                {},
                {{"thresholds_v", &dh.thresholds_v},
                 {"weights", &dh.weights},
                 {"rate_weights_s_per_v", &dh.rate_weights_s_per_v}},
                {}}
            .Read(h, complete);
      }
      if (root.Get(key).Has("creep")) {
        // The ceramic's creep (velocity source only); a file without the block has none.
        const internal::JsonNode c = root.Get(key).Get("creep");
        if (!vsp) other_model(c);
        DriveCreep& dc = vsp->creep;
        Section{{{"voltage_share", &dc.voltage_share},
                 {"loop_share", &dc.loop_share},
                 {"time_constant_s", &dc.time_constant_s}},
                {},
                {},
                {}}
            .Read(c, complete);
      }
    } else if (key == "motor") {
      if (!vsp) other_model(root.Get(key));
      MotorParameters& motor = vsp->motor;
      Section{{{"pole_per_s", &motor.pole_per_s},
               {"dead_zone_forward_v", &motor.dead_zone_forward_v},
               {"dead_zone_backward_v", &motor.dead_zone_backward_v},
               {"thrust_limit_mps2", &motor.thrust_limit_mps2}},
              {},
              {{"speed_map_in_v", &motor.speed_map_in_v},
               {"speed_map_out_mps", &motor.speed_map_out_mps}},
              {}}
          .Read(root.Get(key), complete, {"thrust_limit_mps2"});
    } else if (key == "rail") {
      if (!vsp) other_model(root.Get(key));
      RailFriction& rail = vsp->rail;
      Section{{{"coulomb_mps2", &rail.coulomb_mps2},
               {"static_mps2", &rail.static_mps2},
               {"stribeck_velocity_mps", &rail.stribeck_velocity_mps},
               {"memory_time_s", &rail.memory_time_s}},
              {},
              {},
              {}}
          .Read(root.Get(key), complete, {"memory_time_s"});
    } else if (key == "friction") {
      if (!adp) other_model(root.Get(key));
      Section{{{"bristle_stiffness_per_s2", &adp->bristle_stiffness_per_s2},
               {"bristle_damping_per_s", &adp->bristle_damping_per_s}},
              {},
              {},
              {"forward", "backward"}}
          .Read(root.Get(key), complete);
      if (root.Get(key).Has("forward"))
        BranchSection(adp->forward).Read(root.Get(key).Get("forward"), complete);
      if (root.Get(key).Has("backward"))
        BranchSection(adp->backward).Read(root.Get(key).Get("backward"), complete);
    } else if (key == "rig") {
      // The rates: sample_rate_hz sets the control and the record rate alike (files written
      // before the two rates existed); control_rate_hz and record_rate_hz set them apart.
      const internal::JsonNode rig = root.Get(key);
      double alias = p.sample_rate_hz, control = p.sample_rate_hz, record = p.record_rate_hz;
      if (rig.Has("sample_rate_hz"))
        for (const char* other : {"control_rate_hz", "record_rate_hz"})
          if (rig.Has(other))
            rig.Get(other).Fail(std::string("give rig.sample_rate_hz (it sets both rates) or "
                                            "rig.control_rate_hz and rig.record_rate_hz, not "
                                            "both; found sample_rate_hz and ") + other);
      Section{{{"sample_rate_hz", &alias},
               {"control_rate_hz", &control},
               {"record_rate_hz", &record},
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
          .Read(rig, complete, {"sample_rate_hz", "control_rate_hz", "record_rate_hz"});
      if (complete && !rig.Has("sample_rate_hz") && !rig.Has("control_rate_hz"))
        rig.Fail(std::string("missing required key 'sample_rate_hz' (or 'control_rate_hz') (") +
                 CompleteRule() + ")");
      if (rig.Has("sample_rate_hz")) {
        p.sample_rate_hz = alias;
        p.record_rate_hz = 0;  // the control rate
      } else {
        p.sample_rate_hz = control;
        p.record_rate_hz = record;
      }
    } else if (key == "integrator") {
      Section{{{"relative_tolerance", &p.relative_tolerance},
               {"position_tolerance_m", &p.position_tolerance_m}},
              {{"max_steps_per_sample", &p.max_steps_per_sample}},
              {},
              {}}
          .Read(root.Get(key), complete, {"max_steps_per_sample"});
    }
  }
  if (complete) {
    const std::vector<const char*> sections =
        vs ? std::vector<const char*>{"drive", "motor", "rail", "rig", "integrator"}
           : std::vector<const char*>{"drive", "friction", "rig", "integrator"};
    for (const char* section : sections)
      if (!root.Has(section))
        root.Fail(std::string("expected section '") + section + "' of the " + model_name +
                  " model, found none (" + CompleteRule() + ")");
  }
  try {
    p.Validate();
  } catch (const OptionsError& e) {
    doc.FailValidation(e, FieldPointer(doc, e.field()));
  }
  // A bound beyond the physics that keeps every procedure's work finite (1e12 Hz would ask for
  // terabytes); only a file can set it, so it is reported at its place.
  if (p.sample_rate_hz > kMaxStageSampleRateHz) {
    const internal::JsonNode rig = root.Get("rig");
    rig.Get(rig.Has("sample_rate_hz") ? "sample_rate_hz" : "control_rate_hz")
        .Expected("a number in (0, 1e+06] (sample rate [Hz])");
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
  const VelocitySourcePlant* const vs = std::get_if<VelocitySourcePlant>(&p.plant);
  const ActuatorDelayPlant* const ad = std::get_if<ActuatorDelayPlant>(&p.plant);
  OJ j;
  j["name"] = p.name;
  j["model"] = ToString(p.model());
  j["note"] =
      "Virtual piezo stage for libsysid (docs/virtual_stage.md). SI units; each key ends with "
      "its unit (mps = m/s, mps2 = m/s^2, per_s = 1/s, per_s2 = 1/s^2, v = V). Forces are per "
      "unit mass. Only the sections of this model are written.";
  OJ drive;
  if (ad) {
    drive["gain_mps2_per_v"] = ad->gain_mps2_per_v;
    drive["dead_zone_v"] = ad->dead_zone_v;
  }
  drive["saturation_v"] = p.saturation_v;
  drive["transport_delay_s"] = p.transport_delay_s;
  drive["lag_time_constant_s"] = p.lag_time_constant_s;
  if (vs && vs->hysteresis.enabled()) {
    OJ h;
    h["thresholds_v"] = vs->hysteresis.thresholds_v;
    h["weights"] = vs->hysteresis.weights;
    h["rate_weights_s_per_v"] = vs->hysteresis.rate_weights_s_per_v;
    h["rate_time_constant_s"] = vs->hysteresis.rate_time_constant_s;
    h["asymmetry"] = vs->hysteresis.asymmetry;
    drive["hysteresis"] = h;
  }
  if (vs && vs->creep.enabled()) {
    OJ c;
    c["voltage_share"] = vs->creep.voltage_share;
    c["loop_share"] = vs->creep.loop_share;
    c["time_constant_s"] = vs->creep.time_constant_s;
    drive["creep"] = c;
  }
  if (ad) {
    drive["map_in_v"] = ad->drive_map_in_v;
    drive["map_out_v"] = ad->drive_map_out_v;
  }
  j["drive"] = drive;
  if (vs) {
    OJ motor;
    motor["pole_per_s"] = vs->motor.pole_per_s;
    motor["dead_zone_forward_v"] = vs->motor.dead_zone_forward_v;
    motor["dead_zone_backward_v"] = vs->motor.dead_zone_backward_v;
    motor["speed_map_in_v"] = vs->motor.speed_map_in_v;
    motor["speed_map_out_mps"] = vs->motor.speed_map_out_mps;
    if (vs->motor.thrust_limit_mps2 > 0) motor["thrust_limit_mps2"] = vs->motor.thrust_limit_mps2;
    j["motor"] = motor;
    OJ rail;
    rail["coulomb_mps2"] = vs->rail.coulomb_mps2;
    rail["static_mps2"] = vs->rail.static_mps2;
    rail["stribeck_velocity_mps"] = vs->rail.stribeck_velocity_mps;
    rail["memory_time_s"] = vs->rail.memory_time_s;
    j["rail"] = rail;
  } else {
    OJ friction;
    friction["bristle_stiffness_per_s2"] = ad->bristle_stiffness_per_s2;
    friction["bristle_damping_per_s"] = ad->bristle_damping_per_s;
    friction["forward"] = branch(ad->forward);
    friction["backward"] = branch(ad->backward);
    j["friction"] = friction;
  }
  OJ rig;
  // One rate as before (sample_rate_hz sets both), or the two apart.
  if (p.record_rate_hz > 0 && p.record_rate_hz != p.sample_rate_hz) {
    rig["control_rate_hz"] = p.sample_rate_hz;
    rig["record_rate_hz"] = p.record_rate_hz;
  } else {
    rig["sample_rate_hz"] = p.sample_rate_hz;
  }
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
  if (p.max_steps_per_sample != StageParameters::kDefaultMaxStepsPerSample)
    integ["max_steps_per_sample"] = p.max_steps_per_sample;
  j["integrator"] = integ;
  return j.dump(2) + "\n";
}

StageParameters LoadStage(const std::string& preset_or_path) {
  if (StageParameters::IsPresetName(preset_or_path)) return StageParameters::Preset(preset_or_path);
  return ReadStageParameters(preset_or_path);
}

void WriteStageParameters(const std::string& path, const StageParameters& parameters) {
  WriteFileAtomically(path, WithGeneratorKey(StageParametersToJson(parameters)));
}

}  // namespace sysid
