// Private: PulseDetectionOptions as a JSON object, for the options that cut recordings at
// pulse starts (delay tuning's segments, refinement).
#ifndef SYSID_SRC_IDENTIFY_IDENTIFY_JSON_HPP_
#define SYSID_SRC_IDENTIFY_IDENTIFY_JSON_HPP_

#include <nlohmann/json.hpp>

#include "core/json_text.hpp"
#include "sysid/identify.hpp"

namespace sysid::internal {

nlohmann::ordered_json PulseDetectionOptionsJson(const PulseDetectionOptions& options);
/// Reads the object's keys (each optional) over `options`; no Validate().
void ReadPulseDetectionOptions(const JsonNode& node, PulseDetectionOptions& options);

}  // namespace sysid::internal

#endif  // SYSID_SRC_IDENTIFY_IDENTIFY_JSON_HPP_
