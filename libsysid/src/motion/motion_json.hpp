// Private: MotionOptions as a JSON object, for the options that hold one (identification,
// delay tuning, refinement, dominance).
#ifndef SYSID_SRC_MOTION_MOTION_JSON_HPP_
#define SYSID_SRC_MOTION_MOTION_JSON_HPP_

#include <nlohmann/json.hpp>

#include "core/json_text.hpp"
#include "signal/signal_json.hpp"
#include "sysid/motion.hpp"

namespace sysid::internal {

nlohmann::ordered_json MotionOptionsJson(const MotionOptions& options);
/// Reads the object's keys (each optional) over `options`; no Validate().
void ReadMotionOptions(const JsonNode& node, MotionOptions& options);

}  // namespace sysid::internal

#endif  // SYSID_SRC_MOTION_MOTION_JSON_HPP_
