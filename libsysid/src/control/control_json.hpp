// Private: the JSON forms of the control module's enums for the described structs that hold
// them (core/json_fields.hpp): the PI's anti-windup rule (PiOptions, which the facts and
// pipeline options hold) and a tracking run's feedforward scheme (SchemeTracking).
#ifndef SYSID_SRC_CONTROL_CONTROL_JSON_HPP_
#define SYSID_SRC_CONTROL_CONTROL_JSON_HPP_

#include <nlohmann/json.hpp>

#include "core/json_fields.hpp"
#include "sysid/control.hpp"

namespace sysid::internal {

/// "none" or "conditional-integration".
template <>
struct JsonForm<AntiWindup> {
  static nlohmann::ordered_json Write(const AntiWindup& a);
  static void Read(const JsonNode& node, AntiWindup& a);
};

/// "none", "analytic", "nn" or "hysteresis" (ToString).
template <>
struct JsonForm<FeedforwardScheme> {
  static nlohmann::ordered_json Write(const FeedforwardScheme& s);
  static void Read(const JsonNode& node, FeedforwardScheme& s);
};

}  // namespace sysid::internal

#endif  // SYSID_SRC_CONTROL_CONTROL_JSON_HPP_
