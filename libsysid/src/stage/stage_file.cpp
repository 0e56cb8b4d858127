// The stage file: JSON with the unit in every key, grouped as model, drive, motor + rail
// (velocity source) or friction (actuator delay), rig, integrator. A section's keys are the
// fields of the structs it holds (their Serialize, sysid/serialize.hpp), read and written
// through the field archives (core/json_fields.hpp); the file's layout (which section holds
// which struct's fields) is this file's. Unknown keys are errors so that a typo never silently
// leaves a default.
#include <algorithm>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "core/json_fields.hpp"
#include "core/json_text.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"
#include "sysid/io_output.hpp"
#include "sysid/serialize.hpp"
#include "sysid/stage.hpp"

namespace sysid {
namespace {

using internal::JsonNode;
using Keys = std::vector<std::string>;
using OJ = nlohmann::ordered_json;

constexpr double kMaxStageSampleRateHz = 1e6;
// Why a key or section is required: said in every such message.
std::string CompleteRule() {
  return "a stage file gives every section and key of its model, or names \"preset\": NAME (" +
         StageParameters::PresetNameList() + ") whose values fill what it leaves out";
}

// The key of a struct's field in one section of the file; empty when the field is elsewhere.
using KeyOf = std::string (*)(const std::string& field);
std::string SameKey(const std::string& field) { return field; }

// The actuator-delay plant's force actuator is written in "drive": its gain and dead zone
// before the driver's keys, its map after them without the "drive_" prefix; its LuGre rail
// (the other fields) in "friction".
std::string ActuatorHeadKey(const std::string& field) {
  return field == "gain_mps2_per_v" || field == "dead_zone_v" ? field : "";
}
std::string ActuatorMapKey(const std::string& field) {
  return field.rfind("drive_", 0) == 0 ? field.substr(6) : "";
}
std::string ActuatorDriveKey(const std::string& field) {
  const std::string head = ActuatorHeadKey(field);
  return head.empty() ? ActuatorMapKey(field) : head;
}
std::string FrictionKey(const std::string& field) {
  return ActuatorDriveKey(field).empty() ? field : "";
}
// The rig's two rates are written as the file's rate keys (FileRates), the rest as they are.
std::string RigKey(const std::string& field) {
  return field == "sample_rate_hz" || field == "record_rate_hz" ? "" : field;
}

// The rig's rates as a file gives them: sample_rate_hz sets the control and the record rate
// alike (files written before the two rates existed); control_rate_hz and record_rate_hz set
// them apart.
struct FileRates {
  double sample_rate_hz = 0;
  double control_rate_hz = 0;
  double record_rate_hz = 0;
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(sample_rate_hz));
    a->Visit(SYSID_NVP(control_rate_hz));
    a->Visit(SYSID_NVP(record_rate_hz));
  }
};

// The fields of a struct that one section holds (`key_of`).
template <class T>
struct Share {
  T* fields;
  KeyOf key_of;
};
template <class T>
Share<T> ShareOf(T& fields, KeyOf key_of = SameKey) {
  return {&fields, key_of};
}

class KeyArchive {
 public:
  explicit KeyArchive(KeyOf key_of) : key_of_(key_of) {}
  template <class V>
  void Visit(const NameValue<V>& nv) {
    std::string key = key_of_(nv.name());
    if (!key.empty()) keys.push_back(std::move(key));
  }
  Keys keys;

 private:
  KeyOf key_of_;
};

// The keys of a share, in Serialize order.
template <class T>
Keys KeysOf(const Share<T>& share) {
  KeyArchive a(share.key_of);
  share.fields->Serialize(&a);  // visits the names only
  return std::move(a.keys);
}

// The keys of the actuator delay's force actuator in "drive" (map_in_v, not drive_map_in_v).
const Keys& ActuatorDriveKeys() {
  static const Keys keys = [] {
    ActuatorDelayPlant plant;
    return KeysOf(ShareOf(plant, ActuatorDriveKey));
  }();
  return keys;
}

template <class... T>
void ReadSection(const JsonNode& node, bool complete, const Keys& optional, const Keys& blocks,
                 const Share<T>&... shares);

// Reads each key of a share that the section holds over its field; a described field (a
// friction branch) is a section of its own.
class ShareReadArchive {
 public:
  ShareReadArchive(const JsonNode& node, KeyOf key_of, bool complete)
      : node_(node), key_of_(key_of), complete_(complete) {}
  template <class V>
  void Visit(const NameValue<V>& nv) {
    const std::string key = key_of_(nv.name());
    if (key.empty()) return;
    if constexpr (internal::IsDescribed<V>::value) {
      if (node_.Has(key)) ReadSection(node_.Get(key), complete_, {}, {}, ShareOf(*nv.value()));
    } else {
      internal::ReadField(node_, nv.Renamed(key.c_str()));
    }
  }

 private:
  JsonNode node_;
  KeyOf key_of_;
  bool complete_;
};

// Reads the object `node`, whose keys must all be the shares' or in `blocks` (objects the
// caller reads), besides the comments "units" and "note". With `complete` (a file that names no
// "preset") every share's key but those in `optional` must be written; otherwise keys left out
// keep the preset's value.
template <class... T>
void ReadSection(const JsonNode& node, bool complete, const Keys& optional, const Keys& blocks,
                 const Share<T>&... shares) {
  Keys fields;
  for (Keys share : {KeysOf(shares)...}) fields.insert(fields.end(), share.begin(), share.end());
  Keys known = fields;
  known.insert(known.end(), blocks.begin(), blocks.end());
  node.ExpectObject(known, {"units", "note"});
  auto read = [&](const auto& share) {
    ShareReadArchive a(node, share.key_of, complete);
    share.fields->Serialize(&a);
  };
  (read(shares), ...);
  if (!complete) return;
  for (const std::string& k : fields)
    if (!node.Has(k) && std::find(optional.begin(), optional.end(), k) == optional.end())
      node.Fail("missing required key '" + k + "' (" + CompleteRule() + ")");
}

// Writes the keys of a share into `section`, in Serialize order.
template <class T>
void WriteShare(const Share<T>& share, OJ& section) {
  const OJ all = internal::WriteFields(*share.fields);
  for (auto it = all.begin(); it != all.end(); ++it) {
    const std::string key = share.key_of(it.key());
    if (!key.empty()) section[key] = it.value();
  }
}

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
  // The actuator delay's map is written without its "drive_" prefix.
  const std::string map_key = ActuatorMapKey(suffix.substr(1));
  if (p.empty() && !map_key.empty()) p = doc.FindSuffix("/" + map_key);
  return p;
}

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
    for (const std::string& k : ActuatorDriveKeys())
      if (j["drive"].contains(k)) return StageModel::kActuatorDelay;
  return StageModel::kVelocitySource;
}

}  // namespace

// Long function: the stage file's schema, read section by section in the file's order, each
// section naming the structs whose fields it holds.
StageParameters ParseStageParameters(std::string_view json_text, const std::string& source) {
  const internal::JsonDocument doc(json_text, source);
  const JsonNode root = doc.Root();
  root.ExpectObject(
      {"name", "preset", "model", "drive", "motor", "rail", "friction", "rig", "integrator"},
      {"units", "note"});
  // "preset": the file changes a preset, which supplies every value it leaves out. Without
  // it the file must be complete (a missing section or key is an error, never a default).
  std::optional<StageParameters> preset;
  if (root.Has("preset")) {
    const JsonNode at = root.Get("preset");
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
  auto other_model = [&](const JsonNode& at) {
    const std::string key = at.pointer().substr(at.pointer().rfind('/') + 1);
    throw InputError(doc.Where(at.pointer()) + ": key '" + key + "' belongs to the " +
                     (vs ? "actuator-delay" : "velocity-source") + " model; this stage's model is " +
                     model_name + " (key 'model')");
  };
  for (const auto& [key, value] : root.json().items()) {
    if (key == "units" || key == "note" || key == "model" || key == "preset" ||
        (!key.empty() && key[0] == '_'))
      continue;
    const JsonNode section = root.Get(key);
    if (key == "name") {
      p.name = section.String();
    } else if (key == "drive") {
      if (vs && value.is_object())
        for (const std::string& k : ActuatorDriveKeys())
          if (value.contains(k)) other_model(section.Get(k));
      // The driver's shared keys, and the actuator delay's force actuator in the same block.
      const Keys blocks = {"hysteresis", "creep"};
      if (adp)
        ReadSection(section, complete, {}, blocks, ShareOf(*adp, ActuatorHeadKey),
                    ShareOf(p.driver), ShareOf(*adp, ActuatorMapKey));
      else
        ReadSection(section, complete, {}, blocks, ShareOf(p.driver));
      // The ceramic's hysteresis and creep (velocity source only); a file without a block has
      // none.
      if (section.Has("hysteresis")) {
        if (!vsp) other_model(section.Get("hysteresis"));
        ReadSection(section.Get("hysteresis"), complete, {}, {}, ShareOf(vsp->hysteresis));
      }
      if (section.Has("creep")) {
        if (!vsp) other_model(section.Get("creep"));
        ReadSection(section.Get("creep"), complete, {}, {}, ShareOf(vsp->creep));
      }
    } else if (key == "motor") {
      if (!vsp) other_model(section);
      ReadSection(section, complete, {"thrust_limit_mps2"}, {}, ShareOf(vsp->motor));
    } else if (key == "rail") {
      if (!vsp) other_model(section);
      ReadSection(section, complete, {"memory_time_s"}, {}, ShareOf(vsp->rail));
    } else if (key == "friction") {
      if (!adp) other_model(section);
      ReadSection(section, complete, {}, {}, ShareOf(*adp, FrictionKey));
    } else if (key == "rig") {
      if (section.Has("sample_rate_hz"))
        for (const char* other : {"control_rate_hz", "record_rate_hz"})
          if (section.Has(other))
            section.Get(other).Fail(std::string("give rig.sample_rate_hz (it sets both rates) or "
                                                "rig.control_rate_hz and rig.record_rate_hz, not "
                                                "both; found sample_rate_hz and ") +
                                    other);
      FileRates rates{p.rig.sample_rate_hz, p.rig.sample_rate_hz, p.rig.record_rate_hz};
      ReadSection(section, complete, KeysOf(ShareOf(rates)), {}, ShareOf(rates),
                  ShareOf(p.rig, RigKey));
      if (complete && !section.Has("sample_rate_hz") && !section.Has("control_rate_hz"))
        section.Fail(std::string("missing required key 'sample_rate_hz' (or 'control_rate_hz') (") +
                     CompleteRule() + ")");
      if (section.Has("sample_rate_hz")) {
        p.rig.sample_rate_hz = rates.sample_rate_hz;
        p.rig.record_rate_hz = 0;  // the control rate
      } else {
        p.rig.sample_rate_hz = rates.control_rate_hz;
        p.rig.record_rate_hz = rates.record_rate_hz;
      }
    } else if (key == "integrator") {
      ReadSection(section, complete, {"max_steps_per_sample"}, {}, ShareOf(p.integrator));
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
  if (p.rig.sample_rate_hz > kMaxStageSampleRateHz) {
    const JsonNode rig = root.Get("rig");
    rig.Get(rig.Has("sample_rate_hz") ? "sample_rate_hz" : "control_rate_hz")
        .Expected("a number in (0, 1e+06] (sample rate [Hz])");
  }
  return p;
}

StageParameters ReadStageParameters(const std::string& path) {
  return ParseStageParameters(ReadFile(path), path);
}

std::string StageParametersToJson(const StageParameters& p) {
  // Copies: a share names its struct's fields through a non-const pointer.
  StageParameters q = p;
  VelocitySourcePlant* const vs = std::get_if<VelocitySourcePlant>(&q.plant);
  ActuatorDelayPlant* const ad = std::get_if<ActuatorDelayPlant>(&q.plant);
  OJ j;
  j["name"] = q.name;
  j["model"] = ToString(q.model());
  j["note"] =
      "Virtual piezo stage for libsysid (docs/virtual_stage.md). SI units; each key ends with "
      "its unit (mps = m/s, mps2 = m/s^2, per_s = 1/s, per_s2 = 1/s^2, v = V). Forces are per "
      "unit mass. Only the sections of this model are written.";
  OJ drive = OJ::object();
  if (ad) WriteShare(ShareOf(*ad, ActuatorHeadKey), drive);
  WriteShare(ShareOf(q.driver), drive);
  if (vs && vs->hysteresis.enabled()) drive["hysteresis"] = internal::WriteFields(vs->hysteresis);
  if (vs && vs->creep.enabled()) drive["creep"] = internal::WriteFields(vs->creep);
  if (ad) WriteShare(ShareOf(*ad, ActuatorMapKey), drive);
  j["drive"] = drive;
  if (vs) {
    OJ motor = internal::WriteFields(vs->motor);
    if (!(vs->motor.thrust_limit_mps2 > 0)) motor.erase("thrust_limit_mps2");  // 0: no limit
    j["motor"] = motor;
    j["rail"] = internal::WriteFields(vs->rail);
  } else {
    OJ friction = OJ::object();
    WriteShare(ShareOf(*ad, FrictionKey), friction);
    j["friction"] = friction;
  }
  OJ rig = OJ::object();
  // One rate as before (sample_rate_hz sets both), or the two apart.
  if (q.rig.record_rate_hz > 0 && q.rig.record_rate_hz != q.rig.sample_rate_hz) {
    rig["control_rate_hz"] = q.rig.sample_rate_hz;
    rig["record_rate_hz"] = q.rig.record_rate_hz;
  } else {
    rig["sample_rate_hz"] = q.rig.sample_rate_hz;
  }
  WriteShare(ShareOf(q.rig, RigKey), rig);
  j["rig"] = rig;
  OJ integrator = internal::WriteFields(q.integrator);
  if (q.integrator.max_steps_per_sample == IntegratorSettings::kDefaultMaxStepsPerSample)
    integrator.erase("max_steps_per_sample");
  j["integrator"] = integrator;
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
