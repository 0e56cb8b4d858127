// JSON of the stage-facts options (the facts' results are StageFacts::ToJson).
#include <string>
#include <string_view>
#include <vector>

#include "control/control_json.hpp"
#include "core/json_fields.hpp"
#include "nn/nn_json.hpp"
#include "signal/signal_json.hpp"
#include "sysid/stage_facts.hpp"

namespace sysid {

std::string ToJson(const FactsOptions& options, int indent) {
  return internal::FieldsToJson(options, indent);
}

FactsOptions FactsOptionsFromJson(std::string_view text, const std::string& source_name) {
  return internal::FieldsFromJson<FactsOptions>(text, source_name);
}

}  // namespace sysid
