// JSON of the pulse-test procedure (the stage file's parameters are in stage_file.cpp).
#include "stage/stage_json.hpp"

#include <string>
#include <string_view>

namespace sysid {
namespace internal {

nlohmann::ordered_json PulseProcedureJson(const PulseProcedure& p) {
  nlohmann::ordered_json j;
  j["amplitudes_v"] = p.amplitudes_v;
  j["on_s"] = p.on_s;
  j["rest_s"] = p.rest_s;
  j["lead_s"] = p.lead_s;
  return j;
}

void ReadPulseProcedure(const JsonNode& node, PulseProcedure& p) {
  node.ExpectObject({"amplitudes_v", "on_s", "rest_s", "lead_s"});
  ReadOptional(node, "amplitudes_v", p.amplitudes_v);
  ReadOptional(node, "on_s", p.on_s);
  ReadOptional(node, "rest_s", p.rest_s);
  ReadOptional(node, "lead_s", p.lead_s);
}

}  // namespace internal

std::string ToJson(const PulseProcedure& procedure, int indent) {
  return internal::DumpJson(internal::PulseProcedureJson(procedure), indent);
}

PulseProcedure PulseProcedureFromJson(std::string_view text, const std::string& source_name) {
  return internal::OptionsFromJson<PulseProcedure>(text, source_name,
                                                   internal::ReadPulseProcedure);
}

}  // namespace sysid
