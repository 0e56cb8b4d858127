// Private: the model object written into and read from any place in a JSON document, so that
// results holding a model ("model" of tune-delay's JSON, the keys of identify's) write it as the
// model file does and check it with the model file's rules and positions.
#ifndef SYSID_SRC_MODEL_MODEL_JSON_HPP_
#define SYSID_SRC_MODEL_MODEL_JSON_HPP_

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/json_text.hpp"
#include "sysid/model.hpp"

namespace sysid::internal {

/// The model file's object: the fields (FrictionModel::Serialize), then their "units".
nlohmann::ordered_json ModelJson(const FrictionModel& model);

/// Reads the model's fields from the object `node` of `doc` (other keys: `allowed_extra` or '_'
/// comments) and validates the model; errors name SOURCE:LINE:COL.
FrictionModel ModelFromJson(const JsonDocument& doc, const JsonNode& node,
                            const std::vector<std::string>& allowed_extra);

}  // namespace sysid::internal

#endif  // SYSID_SRC_MODEL_MODEL_JSON_HPP_
