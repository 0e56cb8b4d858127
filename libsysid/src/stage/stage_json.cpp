// JSON of the pulse-test procedure (the stage file's parameters are in stage_file.cpp).
#include <string>
#include <string_view>

#include "core/json_fields.hpp"
#include "sysid/stage.hpp"

namespace sysid {

std::string ToJson(const PulseProcedure& procedure, int indent) {
  return internal::FieldsToJson(procedure, indent);
}

PulseProcedure PulseProcedureFromJson(std::string_view text, const std::string& source_name) {
  return internal::FieldsFromJson<PulseProcedure>(text, source_name);
}

}  // namespace sysid
