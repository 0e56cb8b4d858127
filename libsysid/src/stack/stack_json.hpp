// Private: the JSON form of the stack's integration method, for every reader and writer of the
// stack file's sections (core/json_fields.hpp).
#ifndef SYSID_SRC_STACK_STACK_JSON_HPP_
#define SYSID_SRC_STACK_STACK_JSON_HPP_

#include <nlohmann/json.hpp>

#include "core/json_fields.hpp"
#include "sysid/stack.hpp"

namespace sysid::internal {

/// "cvode" or "exact".
template <>
struct JsonForm<StackMethod> {
  static nlohmann::ordered_json Write(const StackMethod& method);
  static void Read(const JsonNode& node, StackMethod& method);
};

}  // namespace sysid::internal

#endif  // SYSID_SRC_STACK_STACK_JSON_HPP_
