// JSON of a tracking run's metrics (docs/cli.md: track --json "schemes" entries).
#include <nlohmann/json.hpp>
#include <string>

#include "core/json_text.hpp"
#include "sysid/control.hpp"

namespace sysid {

std::string ToJson(const TrackingResult& r, int indent) {
  nlohmann::ordered_json j;
  j["max_error_m"] = r.max_error_m;
  j["rms_error_m"] = r.rms_error_m;
  j["rms_u_v"] = r.rms_u_v;
  j["max_abs_u_v"] = r.max_abs_u_v;
  j["total_variation_v"] = r.total_variation_v;
  j["saturated_samples"] = r.saturated_samples;
  return detail::DumpJson(j, indent);
}

}  // namespace sysid
