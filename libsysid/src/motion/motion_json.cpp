// JSON of the motion options.
#include "motion/motion_json.hpp"

#include <string>
#include <string_view>

#include "signal/signal_json.hpp"

namespace sysid {
namespace internal {

nlohmann::ordered_json MotionOptionsJson(const MotionOptions& o) {
  nlohmann::ordered_json j;
  j["derivative"] = DerivativeOptionsJson(o.derivative);
  j["velocity_column"] = o.velocity_column;
  j["prefer_velocity_column"] = o.prefer_velocity_column;
  j["max_relative_jitter"] = o.max_relative_jitter;
  return j;
}

void ReadMotionOptions(const JsonNode& node, MotionOptions& o) {
  node.ExpectObject(
      {"derivative", "velocity_column", "prefer_velocity_column", "max_relative_jitter"});
  if (node.Has("derivative")) ReadDerivativeOptions(node.Get("derivative"), o.derivative);
  ReadOptional(node, "velocity_column", o.velocity_column);
  ReadOptional(node, "prefer_velocity_column", o.prefer_velocity_column);
  ReadOptional(node, "max_relative_jitter", o.max_relative_jitter);
}

}  // namespace internal

std::string ToJson(const MotionOptions& options, int indent) {
  return internal::DumpJson(internal::MotionOptionsJson(options), indent);
}

MotionOptions MotionOptionsFromJson(std::string_view text, const std::string& source_name) {
  return internal::OptionsFromJson<MotionOptions>(text, source_name, internal::ReadMotionOptions);
}

}  // namespace sysid
