// JSON of a tracking run's metrics (docs/cli.md: track --json "schemes" entries) and of the
// controller and reference-profile options.
#include <nlohmann/json.hpp>
#include <string>

#include "control/control_json.hpp"
#include "core/json_text.hpp"
#include "sysid/control.hpp"
#include "sysid/error.hpp"

namespace sysid {

std::string ToJson(const TrackingResult& r, int indent) {
  nlohmann::ordered_json j;
  j["max_error_m"] = r.max_error_m;
  j["rms_error_m"] = r.rms_error_m;
  j["rms_u_v"] = r.rms_u_v;
  j["max_abs_u_v"] = r.max_abs_u_v;
  j["total_variation_v"] = r.total_variation_v;
  j["saturated_samples"] = r.saturated_samples;
  return internal::DumpJson(j, indent);
}

TrackingResult TrackingResultFromJson(std::string_view text, const std::string& source_name) {
  const internal::JsonDocument doc(text, source_name);
  const internal::JsonNode root = doc.Root();
  root.ExpectObject({"max_error_m", "rms_error_m", "rms_u_v", "max_abs_u_v", "total_variation_v",
                     "saturated_samples"});
  using Rule = internal::NumberRule;
  TrackingResult r;
  r.max_error_m = root.Get("max_error_m").Number(Rule::NonNegative());
  r.rms_error_m = root.Get("rms_error_m").Number(Rule::NonNegative());
  r.rms_u_v = root.Get("rms_u_v").Number(Rule::NonNegative());
  r.max_abs_u_v = root.Get("max_abs_u_v").Number(Rule::NonNegative());
  r.total_variation_v = root.Get("total_variation_v").Number(Rule::NonNegative());
  r.saturated_samples = root.Get("saturated_samples").Integer(0, 1L << 40);
  return r;
}

std::string ToJson(const SchemeTracking& run, int indent) {
  nlohmann::ordered_json j = {{"ff", ToString(run.scheme)}};
  j.update(nlohmann::ordered_json::parse(ToJson(run.result, -1)));
  j["stage_limits"] = run.stage_limits;
  return internal::DumpJson(j, indent);
}

std::string TrackingSummaryToJson(const std::string& plant, const PositionReference& reference,
                                  const PiOptions& pi, const std::vector<SchemeTracking>& runs,
                                  int indent) {
  nlohmann::ordered_json j;
  j["plant"] = plant;
  j["reference"] = reference.description;
  j["kp_v_per_m"] = pi.kp_v_per_m;
  j["ki_v_per_m_s"] = pi.ki_v_per_m_s;
  j["schemes"] = nlohmann::ordered_json::array();
  for (const auto& run : runs) j["schemes"].push_back(nlohmann::ordered_json::parse(ToJson(run)));
  if (runs.size() == 1) {
    j["max_error_m"] = runs[0].result.max_error_m;
    j["rms_error_m"] = runs[0].result.rms_error_m;
  }
  return internal::DumpJson(j, indent);
}

namespace {

std::string AntiWindupName(AntiWindup a) {
  return a == AntiWindup::kNone ? "none" : "conditional-integration";
}

}  // namespace

namespace internal {

nlohmann::ordered_json PiOptionsJson(const PiOptions& o) {
  nlohmann::ordered_json j;
  j["kp_v_per_m"] = o.kp_v_per_m;
  j["ki_v_per_m_s"] = o.ki_v_per_m_s;
  j["sample_time_s"] = o.sample_time_s;
  j["u_max_v"] = o.u_max_v;
  j["anti_windup"] = AntiWindupName(o.anti_windup);
  return j;
}

void ReadPiOptions(const JsonNode& node, PiOptions& o) {
  node.ExpectObject({"kp_v_per_m", "ki_v_per_m_s", "sample_time_s", "u_max_v", "anti_windup"});
  ReadOptional(node, "kp_v_per_m", o.kp_v_per_m);
  ReadOptional(node, "ki_v_per_m_s", o.ki_v_per_m_s);
  ReadOptional(node, "sample_time_s", o.sample_time_s);
  ReadOptional(node, "u_max_v", o.u_max_v);
  if (node.Has("anti_windup")) {
    const JsonNode a = node.Get("anti_windup");
    const std::string s = a.String();
    if (s == AntiWindupName(AntiWindup::kNone)) o.anti_windup = AntiWindup::kNone;
    else if (s == AntiWindupName(AntiWindup::kConditionalIntegration))
      o.anti_windup = AntiWindup::kConditionalIntegration;
    else a.Expected("\"none\" or \"conditional-integration\"");
  }
}

}  // namespace internal

std::string ToJson(const PiOptions& o, int indent) {
  return internal::DumpJson(internal::PiOptionsJson(o), indent);
}

PiOptions PiOptionsFromJson(std::string_view text, const std::string& source_name) {
  return internal::OptionsFromJson<PiOptions>(text, source_name, internal::ReadPiOptions);
}

std::string ToJson(const SmoothProfileOptions& o, int indent) {
  nlohmann::ordered_json j;
  j["frequency_hz"] = o.frequency_hz;
  j["amplitude_m"] = o.amplitude_m;
  j["dwell_fraction"] = o.dwell_fraction;
  j["cycles"] = o.cycles;
  j["sample_rate_hz"] = o.sample_rate_hz;
  return internal::DumpJson(j, indent);
}

SmoothProfileOptions SmoothProfileOptionsFromJson(std::string_view text,
                                                  const std::string& source_name) {
  auto read = [](const internal::JsonNode& node, SmoothProfileOptions& o) {
    using internal::ReadOptional;
    node.ExpectObject({"frequency_hz", "amplitude_m", "dwell_fraction", "cycles", "sample_rate_hz"});
    ReadOptional(node, "frequency_hz", o.frequency_hz);
    ReadOptional(node, "amplitude_m", o.amplitude_m);
    ReadOptional(node, "dwell_fraction", o.dwell_fraction);
    ReadOptional(node, "cycles", o.cycles);
    ReadOptional(node, "sample_rate_hz", o.sample_rate_hz);
  };
  return internal::OptionsFromJson<SmoothProfileOptions>(text, source_name, read);
}

}  // namespace sysid
