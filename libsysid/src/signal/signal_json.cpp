// JSON of the derivative options (nested in the motion and comparison options).
#include "signal/signal_json.hpp"

#include <string>

#include "sysid/error.hpp"

namespace sysid::internal {

nlohmann::ordered_json DerivativeOptionsJson(const DerivativeOptions& o) {
  nlohmann::ordered_json j;
  j["method"] = ToString(o.method);
  j["cutoff_hz"] = o.cutoff_hz;
  j["butterworth_order"] = o.butterworth_order;
  j["savgol_window"] = o.savgol_window;
  j["savgol_order"] = o.savgol_order;
  return j;
}

void ReadDerivativeOptions(const JsonNode& node, DerivativeOptions& o) {
  node.ExpectObject({"method", "cutoff_hz", "butterworth_order", "savgol_window", "savgol_order"});
  if (node.Has("method")) {
    const JsonNode m = node.Get("method");
    try {
      o.method = ParseDerivativeMethod(m.String());
    } catch (const OptionsError&) {
      m.Expected("\"central\", \"butterworth\" or \"savgol\"");
    }
  }
  ReadOptional(node, "cutoff_hz", o.cutoff_hz);
  ReadOptional(node, "butterworth_order", o.butterworth_order);
  ReadOptional(node, "savgol_window", o.savgol_window);
  ReadOptional(node, "savgol_order", o.savgol_order);
}

}  // namespace sysid::internal
