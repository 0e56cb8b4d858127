// Private: the JSON forms of the simulator's enums, for every reader and writer of its described
// structs (core/json_fields.hpp).
#ifndef SYSID_SRC_SIMULATE_SIMULATE_JSON_HPP_
#define SYSID_SRC_SIMULATE_SIMULATE_JSON_HPP_

#include <nlohmann/json.hpp>

#include "core/json_fields.hpp"
#include "sysid/simulate.hpp"

namespace sysid::internal {

/// "adams" or "bdf".
template <>
struct JsonForm<IntegratorMethod> {
  static nlohmann::ordered_json Write(const IntegratorMethod& method);
  static void Read(const JsonNode& node, IntegratorMethod& method);
};

/// An event's name: "stick", "slip+", "slip-", "reverse" or "a1-switch" (ToString).
template <>
struct JsonForm<EventKind> {
  static nlohmann::ordered_json Write(const EventKind& kind);
  static void Read(const JsonNode& node, EventKind& kind);
};

}  // namespace sysid::internal

#endif  // SYSID_SRC_SIMULATE_SIMULATE_JSON_HPP_
