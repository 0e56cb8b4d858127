// Private: the JSON form of the PI's anti-windup rule, for every reader and writer of PiOptions
// (core/json_fields.hpp), which the facts and pipeline options hold.
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

}  // namespace sysid::internal

#endif  // SYSID_SRC_CONTROL_CONTROL_JSON_HPP_
