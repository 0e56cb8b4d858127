// JSON of the motion options and of a recording extended with derivatives.
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "core/json_fields.hpp"
#include "signal/signal_json.hpp"
#include "sysid/error.hpp"
#include "sysid/motion.hpp"

namespace sysid {

std::string ToJson(const MotionOptions& options, int indent) {
  return internal::FieldsToJson(options, indent);
}

MotionOptions MotionOptionsFromJson(std::string_view text, const std::string& source_name) {
  return internal::FieldsFromJson<MotionOptions>(text, source_name);
}

std::string DerivedRecordingToJson(const Recording& recording, double dt_s,
                                   const DerivativeOptions& derivative, int indent) {
  auto stats = [&](const char* column) {
    if (!recording.has(column) || recording.rows() == 0)
      throw InputError(recording.source + ": no " + column + " samples to summarise");
    const Eigen::VectorXd s = recording.column(column);
    const double rms = std::sqrt(s.squaredNorm() / static_cast<double>(s.size()));
    return nlohmann::ordered_json{{"min", s.minCoeff()}, {"max", s.maxCoeff()}, {"rms", rms}};
  };
  nlohmann::ordered_json j;
  j["method"] = ToString(derivative.method);
  j["settings"] = recording.meta("derive", DescribeDerivative(derivative));
  j["rows"] = recording.rows();
  j["columns"] = recording.names;
  j["dt_s"] = dt_s;
  j["sample_rate_hz"] = 1.0 / dt_s;
  j["v_mps"] = stats("v");
  j["a_mps2"] = stats("a");
  return internal::DumpJson(j, indent);
}

}  // namespace sysid
