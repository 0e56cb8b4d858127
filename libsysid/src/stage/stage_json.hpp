// Private: PulseProcedure as a JSON object, for the options that hold one (FactsOptions).
#ifndef SYSID_SRC_STAGE_STAGE_JSON_HPP_
#define SYSID_SRC_STAGE_STAGE_JSON_HPP_

#include <nlohmann/json.hpp>

#include "core/json_text.hpp"
#include "sysid/stage.hpp"

namespace sysid::internal {

nlohmann::ordered_json PulseProcedureJson(const PulseProcedure& procedure);
/// Reads the object's keys (each optional) over `procedure`; no Validate().
void ReadPulseProcedure(const JsonNode& node, PulseProcedure& procedure);

}  // namespace sysid::internal

#endif  // SYSID_SRC_STAGE_STAGE_JSON_HPP_
