// Private: the JSON forms of the hysteresis models' enums, for the model files' described
// fields (core/json_fields.hpp).
#ifndef SYSID_SRC_HYSTERESIS_HYSTERESIS_JSON_HPP_
#define SYSID_SRC_HYSTERESIS_HYSTERESIS_JSON_HPP_

#include <nlohmann/json.hpp>

#include "core/json_fields.hpp"
#include "core/json_text.hpp"
#include "sysid/hysteresis.hpp"
#include "sysid/hysteresis_bouc_wen.hpp"

namespace sysid::internal {

/// "cvode", "benchmark-chain" or "fixed-step" (a model's; "auto" is written, never read).
template <>
struct JsonForm<BoucWenIntegrator> {
  static nlohmann::ordered_json Write(const BoucWenIntegrator& integrator);
  static void Read(const JsonNode& node, BoucWenIntegrator& integrator);
};

/// "hold", "linear" or "band-limited" (a model's; "auto" is written, never read).
template <>
struct JsonForm<InputInterpolation> {
  static nlohmann::ordered_json Write(const InputInterpolation& input);
  static void Read(const JsonNode& node, InputInterpolation& input);
};

/// "pi", "gpi" or "rdpi" (ToString's names).
template <>
struct JsonForm<PiForm> {
  static nlohmann::ordered_json Write(const PiForm& form);
  static void Read(const JsonNode& node, PiForm& form);
};

}  // namespace sysid::internal

#endif  // SYSID_SRC_HYSTERESIS_HYSTERESIS_JSON_HPP_
