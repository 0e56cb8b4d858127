// Private: the derivative method's JSON form, for the options that hold DerivativeOptions
// (MotionOptions, CompareOptions). Its rules depend on the sample interval, so the holder's
// Validate() (or the run) checks it.
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


}  // namespace sysid::internal

#endif  // SYSID_SRC_SIGNAL_SIGNAL_JSON_HPP_
