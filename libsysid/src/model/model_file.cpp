#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "core/json_fields.hpp"
#include "core/json_text.hpp"
#include "model/model_json.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"
#include "sysid/io_output.hpp"
#include "sysid/model.hpp"

namespace sysid {
namespace internal {

nlohmann::ordered_json ModelJson(const FrictionModel& model) { return WriteFields(model); }

FrictionModel ModelFromJson(const JsonDocument& doc, const JsonNode& node,
                            const std::vector<std::string>& allowed_extra) {
  FrictionModel m;
  ReadFields(node, m, allowed_extra);
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
  return internal::DumpJson(internal::ModelJson(m), indent);
}

void WriteModel(const std::string& path, const FrictionModel& model) {
  // JSON has no inf or NaN (nlohmann writes null) and ReadModel refuses both.
  const nlohmann::ordered_json fields = internal::WriteFields(model);
  for (const auto& [name, value] : fields.items()) {
    if (!value.is_number()) continue;  // the units
    const double v = value.get<double>();
    if (!std::isfinite(v))
      throw NumericalError(path + ": " + name + " = " + std::to_string(v) +
                           ": not written (a model file holds finite parameters)");
  }
  WriteFileAtomically(path, WithGeneratorKey(ModelToJson(model)));
}

}  // namespace sysid
