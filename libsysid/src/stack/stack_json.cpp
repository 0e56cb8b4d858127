// The stack file: JSON with the unit in every key, sections hysteresis, creep, mechanics, rig,
// integrator. Every key is optional (the bundled stack fills what a file leaves out) but
// "plant": "piezo-stack", which tells `sysid track --plant` a stack file from a stage file.
// Unknown keys are errors, so a typo never silently keeps a default.
#include <nlohmann/json.hpp>

#include "core/json_text.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"
#include "sysid/stack.hpp"

namespace sysid {
namespace {

constexpr const char* kPlantName = "piezo-stack";

using internal::FieldList;
using internal::JsonNode;

const FieldList<StackHysteresis>& HysteresisFields() {
  using H = StackHysteresis;
  static const FieldList<H> f = FieldList<H>()
                                    .Add("linear_gain_m_per_v", &H::linear_gain_m_per_v)
                                    .Add("thresholds_v", &H::thresholds_v)
                                    .Add("weights_m_per_v", &H::weights_m_per_v)
                                    .Add("rate_weights_m_s_per_v2", &H::rate_weights_m_s_per_v2);
  return f;
}
const FieldList<StackCreep>& CreepFields() {
  static const FieldList<StackCreep> f = FieldList<StackCreep>()
                                             .Add("time_constants_s", &StackCreep::time_constants_s)
                                             .Add("fractions", &StackCreep::fractions);
  return f;
}
const FieldList<StackMechanics>& MechanicsFields() {
  static const FieldList<StackMechanics> f =
      FieldList<StackMechanics>()
          .Add("resonance_hz", &StackMechanics::resonance_hz)
          .Add("damping_ratio", &StackMechanics::damping_ratio);
  return f;
}
const FieldList<StackRig>& RigFields() {
  using R = StackRig;
  static const FieldList<R> f = FieldList<R>()
                                    .Add("control_rate_hz", &R::control_rate_hz)
                                    .Add("voltage_min_v", &R::voltage_min_v)
                                    .Add("voltage_max_v", &R::voltage_max_v)
                                    .Add("dac_bits", &R::dac_bits)
                                    .Add("sensor_resolution_m", &R::sensor_resolution_m)
                                    .Add("sensor_noise_m", &R::sensor_noise_m);
  return f;
}
nlohmann::ordered_json MethodJson(const StackMethod& m) { return ToString(m); }
void ReadMethod(const JsonNode& node, StackMethod& m) {
  try {
    m = ParseStackMethod(node.String());
  } catch (const OptionsError&) {
    node.Expected("\"cvode\" or \"exact\"");
  }
}

const FieldList<StackIntegrator>& IntegratorFields() {
  using I = StackIntegrator;
  static const FieldList<I> f = FieldList<I>()
                                    .Nested("method", &I::method, MethodJson, ReadMethod)
                                    .Add("relative_tolerance", &I::relative_tolerance)
                                    .Add("position_tolerance_m", &I::position_tolerance_m);
  return f;
}

template <class T, const FieldList<T>& (*Fields)()>
nlohmann::ordered_json WriteSection(const T& v) {
  return Fields().Write(v);
}
template <class T, const FieldList<T>& (*Fields)()>
void ReadSection(const JsonNode& node, T& v) {
  Fields().Read(node, v, {"units", "note"});
}

void ReadPlant(const JsonNode& node, std::string&) {
  if (node.String() != kPlantName) node.Expected("\"piezo-stack\"");
}

}  // namespace

StackParameters ParseStackParameters(std::string_view json_text, const std::string& source) {
  const internal::JsonDocument doc(json_text, source);
  const JsonNode root = doc.Root();
  root.ExpectObject({"plant", "name", "hysteresis", "creep", "mechanics", "rig", "integrator"},
                    {"units", "note"});
  if (!root.Has("plant"))
    root.Fail("missing required key 'plant' (a stack file names \"plant\": \"piezo-stack\")");
  std::string scratch;
  ReadPlant(root.Get("plant"), scratch);
  StackParameters p = StackParameters::Default();
  if (root.Has("name")) p.name = root.Get("name").String(true);
  if (root.Has("hysteresis"))
    ReadSection<StackHysteresis, HysteresisFields>(root.Get("hysteresis"), p.hysteresis);
  if (root.Has("creep")) ReadSection<StackCreep, CreepFields>(root.Get("creep"), p.creep);
  if (root.Has("mechanics"))
    ReadSection<StackMechanics, MechanicsFields>(root.Get("mechanics"), p.mechanics);
  if (root.Has("rig")) ReadSection<StackRig, RigFields>(root.Get("rig"), p.rig);
  if (root.Has("integrator"))
    ReadSection<StackIntegrator, IntegratorFields>(root.Get("integrator"), p.integrator);
  internal::ValidateOptions(doc, [&] { p.Validate(); });
  return p;
}

StackParameters ReadStackParameters(const std::string& path) {
  return ParseStackParameters(ReadFile(path), path);
}

std::string StackParametersToJson(const StackParameters& p) {
  nlohmann::ordered_json j;
  j["plant"] = kPlantName;
  j["name"] = p.name;
  j["hysteresis"] = WriteSection<StackHysteresis, HysteresisFields>(p.hysteresis);
  j["creep"] = WriteSection<StackCreep, CreepFields>(p.creep);
  j["mechanics"] = WriteSection<StackMechanics, MechanicsFields>(p.mechanics);
  j["rig"] = WriteSection<StackRig, RigFields>(p.rig);
  j["integrator"] = WriteSection<StackIntegrator, IntegratorFields>(p.integrator);
  return internal::DumpJson(j, 2);
}

bool IsStackFileText(std::string_view json_text) {
  const auto j = nlohmann::json::parse(json_text.begin(), json_text.end(), nullptr, false);
  if (j.is_discarded() || !j.is_object()) return false;
  const auto it = j.find("plant");
  return it != j.end() && it->is_string() && it->get<std::string>() == kPlantName;
}

StackParameters LoadStack(const std::string& preset_or_path) {
  if (IsStackPresetName(preset_or_path)) return StackParameters::Default();
  return ReadStackParameters(preset_or_path);
}

}  // namespace sysid
