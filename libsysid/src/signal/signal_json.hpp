// Private: DerivativeOptions as a JSON object, for the options that hold one (MotionOptions,
// CompareOptions). Its rules depend on the sample interval, so it has no reader of its own:
// the holder's Validate() (or the run) checks it.
#ifndef SYSID_SRC_SIGNAL_SIGNAL_JSON_HPP_
#define SYSID_SRC_SIGNAL_SIGNAL_JSON_HPP_

#include <nlohmann/json.hpp>

#include "core/json_fields.hpp"
#include "sysid/signal.hpp"

namespace sysid::internal {

/// "central", "butterworth" or "savgol".
template <>
struct JsonForm<DerivativeMethod> {
  static nlohmann::ordered_json Write(const DerivativeMethod& method);
  static void Read(const JsonNode& node, DerivativeMethod& method);
};

/// {"method", "cutoff_hz", "butterworth_order", "savgol_window", "savgol_order"}.
nlohmann::ordered_json DerivativeOptionsJson(const DerivativeOptions& options);
/// Reads that object's keys (each optional) over `options`; a bad type or an unknown method
/// or key is a positioned InputError.
void ReadDerivativeOptions(const JsonNode& node, DerivativeOptions& options);

}  // namespace sysid::internal

#endif  // SYSID_SRC_SIGNAL_SIGNAL_JSON_HPP_
