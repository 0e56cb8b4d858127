// JSON of the derivative options (nested in the motion and comparison options).
#include "signal/signal_json.hpp"

#include <string>

#include "sysid/error.hpp"

namespace sysid::internal {

nlohmann::ordered_json JsonForm<DerivativeMethod>::Write(const DerivativeMethod& method) {
  return ToString(method);
}

void JsonForm<DerivativeMethod>::Read(const JsonNode& node, DerivativeMethod& method) {
  try {
    method = ParseDerivativeMethod(node.String());
  } catch (const OptionsError&) {
    node.Expected("\"central\", \"butterworth\" or \"savgol\"");
  }
}

}  // namespace sysid::internal
