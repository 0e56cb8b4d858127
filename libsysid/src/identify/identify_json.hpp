// Private: the JSON form of a pulse's status, for every reader and writer of the pulse estimates
// (core/json_fields.hpp).
#ifndef SYSID_SRC_IDENTIFY_IDENTIFY_JSON_HPP_
#define SYSID_SRC_IDENTIFY_IDENTIFY_JSON_HPP_

#include <nlohmann/json.hpp>

#include "core/json_fields.hpp"
#include "sysid/identify.hpp"

namespace sysid::internal {

/// "ok", "unsettled", "stuck", ... (ToString).
template <>
struct JsonForm<PulseStatus> {
  static nlohmann::ordered_json Write(const PulseStatus& status);
  static void Read(const JsonNode& node, PulseStatus& status);
};

}  // namespace sysid::internal

#endif  // SYSID_SRC_IDENTIFY_IDENTIFY_JSON_HPP_
