// The stack file: JSON with the unit in every key, sections hysteresis, creep, mechanics, rig,
// integrator. Every key is optional (the bundled stack fills what a file leaves out) but
// "plant": "piezo-stack", which tells `sysid track --plant` a stack file from a stage file.
// Unknown keys are errors, so a typo never silently keeps a default.
#include "stack/stack_json.hpp"

#include <nlohmann/json.hpp>

#include "core/json_text.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"
#include "sysid/stack.hpp"

namespace sysid {
namespace {

constexpr const char* kPlantName = "piezo-stack";

using internal::JsonNode;

// A section reads over the bundled stack's values; "units" and "note" are comments.
template <class T>
void ReadSection(const JsonNode& node, T& v) {
  internal::ReadFields(node, v, {"units", "note"});
}

void ReadPlant(const JsonNode& node, std::string&) {
  if (node.String() != kPlantName) node.Expected("\"piezo-stack\"");
}

}  // namespace

namespace internal {

nlohmann::ordered_json JsonForm<StackMethod>::Write(const StackMethod& method) {
  return ToString(method);
}

void JsonForm<StackMethod>::Read(const JsonNode& node, StackMethod& method) {
  try {
    method = ParseStackMethod(node.String());
  } catch (const OptionsError&) {
    node.Expected("\"cvode\" or \"exact\"");
  }
}

}  // namespace internal

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
  if (root.Has("hysteresis")) ReadSection(root.Get("hysteresis"), p.hysteresis);
  if (root.Has("creep")) ReadSection(root.Get("creep"), p.creep);
  if (root.Has("mechanics")) ReadSection(root.Get("mechanics"), p.mechanics);
  if (root.Has("rig")) ReadSection(root.Get("rig"), p.rig);
  if (root.Has("integrator")) ReadSection(root.Get("integrator"), p.integrator);
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
  j["hysteresis"] = internal::WriteFields(p.hysteresis);
  j["creep"] = internal::WriteFields(p.creep);
  j["mechanics"] = internal::WriteFields(p.mechanics);
  j["rig"] = internal::WriteFields(p.rig);
  j["integrator"] = internal::WriteFields(p.integrator);
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
