// JSON of the stage-facts options (the facts' results are StageFacts::ToJson).
#include "paper/facts_json.hpp"

#include <string>
#include <string_view>
#include <vector>

#include "control/control_json.hpp"
#include "delay/delay_json.hpp"
#include "nn/nn_json.hpp"

namespace sysid {
namespace internal {

nlohmann::ordered_json FactsOptionsJson(const FactsOptions& o) { return WriteFields(o); }

void ReadFactsOptions(const JsonNode& node, FactsOptions& o) { ReadFields(node, o); }

}  // namespace internal

std::string ToJson(const FactsOptions& options, int indent) {
  return internal::DumpJson(internal::FactsOptionsJson(options), indent);
}

FactsOptions FactsOptionsFromJson(std::string_view text, const std::string& source_name) {
  return internal::OptionsFromJson<FactsOptions>(text, source_name, internal::ReadFactsOptions);
}

}  // namespace sysid
