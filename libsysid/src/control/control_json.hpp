// Private: PiOptions as a JSON object, for the options that hold one (facts, pipeline).
#ifndef SYSID_SRC_CONTROL_CONTROL_JSON_HPP_
#define SYSID_SRC_CONTROL_CONTROL_JSON_HPP_

#include <nlohmann/json.hpp>

#include "core/json_text.hpp"
#include "sysid/control.hpp"

namespace sysid::internal {

nlohmann::ordered_json PiOptionsJson(const PiOptions& options);
/// Reads the object's keys (each optional) over `options`; no Validate().
void ReadPiOptions(const JsonNode& node, PiOptions& options);

}  // namespace sysid::internal

#endif  // SYSID_SRC_CONTROL_CONTROL_JSON_HPP_
