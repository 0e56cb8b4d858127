// Private: the JSON form of the dominance options' candidate terms, for every reader and writer
// of DominanceOptions (core/json_fields.hpp).
#ifndef SYSID_SRC_DOMINANCE_DOMINANCE_JSON_HPP_
#define SYSID_SRC_DOMINANCE_DOMINANCE_JSON_HPP_

#include <nlohmann/json.hpp>
#include <vector>

#include "core/json_fields.hpp"
#include "sysid/dominance.hpp"

namespace sysid::internal {

/// [{"variable", "column", "gain"}, ...]: variable and column required and non-empty, gain
/// optional; the list replaces the default one.
template <>
struct JsonForm<std::vector<CandidateTerm>> {
  static nlohmann::ordered_json Write(const std::vector<CandidateTerm>& candidates);
  static void Read(const JsonNode& list, std::vector<CandidateTerm>& candidates);
};

}  // namespace sysid::internal

#endif  // SYSID_SRC_DOMINANCE_DOMINANCE_JSON_HPP_
