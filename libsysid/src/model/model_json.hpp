// Private: the model object read from any place in a JSON document, so that results holding a
// model ("model" of tune-delay's JSON) check it with the model file's rules and positions.
#ifndef SYSID_SRC_MODEL_MODEL_JSON_HPP_
#define SYSID_SRC_MODEL_MODEL_JSON_HPP_

#include <string>
#include <vector>

#include "core/json_text.hpp"
#include "sysid/model.hpp"

namespace sysid::internal {

/// Reads a1p, a1n, a2p, a2n, a3 and optional tau from the object `node` of `doc` (other keys:
/// `allowed_extra` or '_' comments) and validates the model; errors name SOURCE:LINE:COL.
FrictionModel ModelFromJson(const JsonDocument& doc, const JsonNode& node,
                            const std::vector<std::string>& allowed_extra);

}  // namespace sysid::internal

#endif  // SYSID_SRC_MODEL_MODEL_JSON_HPP_
