// JSON of the pulse-test procedure (the stage file's parameters are in stage_file.cpp).
#include "stage/stage_json.hpp"

#include <string>
#include <string_view>

namespace sysid {
namespace internal {

namespace {
// The procedure's field table (FieldList): writer, allowed keys and reader.
const FieldList<PulseProcedure>& PulseProcedureFields() {
  using P = PulseProcedure;
  static const FieldList<P> fields = FieldList<P>()
                                         .Add("amplitudes_v", &P::amplitudes_v)
                                         .Add("on_s", &P::on_s)
                                         .Add("rest_s", &P::rest_s)
                                         .Add("lead_s", &P::lead_s);
  return fields;
}
}  // namespace

nlohmann::ordered_json PulseProcedureJson(const PulseProcedure& p) {
  return PulseProcedureFields().Write(p);
}

void ReadPulseProcedure(const JsonNode& node, PulseProcedure& p) {
  PulseProcedureFields().Read(node, p);
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
