// Private: DelayTuningOptions as a JSON object, for the options that hold one (pipeline).
#ifndef SYSID_SRC_DELAY_DELAY_JSON_HPP_
#define SYSID_SRC_DELAY_DELAY_JSON_HPP_

#include <nlohmann/json.hpp>

#include "core/json_fields.hpp"
#include "core/json_text.hpp"
#include "motion/motion_json.hpp"
#include "sysid/delay.hpp"

namespace sysid::internal {

nlohmann::ordered_json DelayTuningOptionsJson(const DelayTuningOptions& options);
/// Reads the object's keys (each optional) over `options`; no Validate().
void ReadDelayTuningOptions(const JsonNode& node, DelayTuningOptions& options);

}  // namespace sysid::internal

#endif  // SYSID_SRC_DELAY_DELAY_JSON_HPP_
