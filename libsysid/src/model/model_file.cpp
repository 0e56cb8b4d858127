#include <cmath>
#include <utility>
#include <nlohmann/json.hpp>
#include <string>

#include "core/json_text.hpp"
#include "model/model_json.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"
#include "sysid/model.hpp"
#include "sysid/io_output.hpp"

namespace sysid {
namespace internal {
FrictionModel ModelFromJson(const JsonDocument& doc, const JsonNode& node,
                            const std::vector<std::string>& allowed_extra) {
  node.ExpectObject({"a1p", "a1n", "a2p", "a2n", "a3", "tau"}, allowed_extra);
  using Rule = NumberRule;
  FrictionModel m;
  m.a1p = node.Get("a1p").Number(Rule::NonNegative());
  m.a1n = node.Get("a1n").Number(Rule::NonNegative());
  m.a2p = node.Get("a2p").Number(Rule::NonNegative());
  m.a2n = node.Get("a2n").Number(Rule::NonNegative());
  m.a3 = node.Get("a3").Number(Rule::Positive());
  // tau [s] is optional (0: no delay); a delay of more than a second is no actuator's.
  if (node.Has("tau")) m.tau_s = node.Get("tau").Number(Rule::Closed(0.0, 1.0));
  try {
    m.Validate();
  } catch (const OptionsError& e) {
    doc.FailValidation(e, e.field().empty() ? "" : node.pointer() + "/" + e.field());
  }
  return m;
}
}  // namespace internal

FrictionModel ParseModel(std::string_view json_text, const std::string& source) {
  const internal::JsonDocument doc(json_text, source);
  // Reports and comments may ride along: "diagnostics", "units", "note", "model", "_anything".
  return internal::ModelFromJson(doc, doc.Root(), {"diagnostics", "units", "note", "model"});
}

FrictionModel ReadModel(const std::string& path) { return ParseModel(ReadFile(path), path); }

std::string ModelToJson(const FrictionModel& m, int indent) {
  nlohmann::ordered_json j;
  j["a1p"] = m.a1p;
  j["a1n"] = m.a1n;
  j["a2p"] = m.a2p;
  j["a2n"] = m.a2n;
  j["a3"] = m.a3;
  j["tau"] = m.tau_s;
  j["units"] = {{"a1p", "1/s"},   {"a1n", "1/s"},      {"a2p", "m/s^2"},
                {"a2n", "m/s^2"}, {"a3", "m/(s^2 V)"}, {"tau", "s"}};
  return j.dump(indent) + "\n";
}

void WriteModel(const std::string& path, const FrictionModel& model) {
  // JSON has no inf or NaN (nlohmann writes null) and ReadModel refuses both.
  for (const auto& [name, v] : {std::pair<const char*, double>{"a1p", model.a1p},
                                {"a1n", model.a1n},
                                {"a2p", model.a2p},
                                {"a2n", model.a2n},
                                {"a3", model.a3},
                                {"tau", model.tau_s}})
    if (!std::isfinite(v))
      throw NumericalError(path + ": " + name + " = " + std::to_string(v) +
                           ": not written (a model file holds finite parameters)");
  WriteFileAtomically(path, WithGeneratorKey(ModelToJson(model)));
}

}  // namespace sysid
