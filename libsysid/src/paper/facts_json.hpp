// Private: FactsOptions as a JSON object, for the options that hold one (PipelineOptions).
#ifndef SYSID_SRC_PAPER_FACTS_JSON_HPP_
#define SYSID_SRC_PAPER_FACTS_JSON_HPP_

#include <nlohmann/json.hpp>

#include "control/control_json.hpp"
#include "core/json_fields.hpp"
#include "core/json_text.hpp"
#include "delay/delay_json.hpp"
#include "nn/nn_json.hpp"
#include "sysid/stage_facts.hpp"

namespace sysid::internal {

nlohmann::ordered_json FactsOptionsJson(const FactsOptions& options);
/// Reads the object's keys (each optional) over `options`; no Validate().
void ReadFactsOptions(const JsonNode& node, FactsOptions& options);

}  // namespace sysid::internal

#endif  // SYSID_SRC_PAPER_FACTS_JSON_HPP_
