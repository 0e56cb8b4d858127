// JSON of a tracking run's metrics (docs/cli.md: track --json "schemes" entries) and of the
// controller and reference-profile options.
#include <nlohmann/json.hpp>
#include <string>

#include "control/control_json.hpp"
#include "core/json_text.hpp"
#include "sysid/control.hpp"
#include "sysid/control_tuning.hpp"
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

nlohmann::ordered_json JsonForm<AntiWindup>::Write(const AntiWindup& a) {
  return AntiWindupName(a);
}

void JsonForm<AntiWindup>::Read(const JsonNode& node, AntiWindup& a) {
  const std::string s = node.String();
  if (s == AntiWindupName(AntiWindup::kNone)) a = AntiWindup::kNone;
  else if (s == AntiWindupName(AntiWindup::kConditionalIntegration))
    a = AntiWindup::kConditionalIntegration;
  else node.Expected("\"none\" or \"conditional-integration\"");
}

}  // namespace internal

std::string ToJson(const PiOptions& o, int indent) { return internal::FieldsToJson(o, indent); }

PiOptions PiOptionsFromJson(std::string_view text, const std::string& source_name) {
  return internal::FieldsFromJson<PiOptions>(text, source_name);
}

std::string ToJson(const SmoothProfileOptions& o, int indent) {
  return internal::FieldsToJson(o, indent);
}

SmoothProfileOptions SmoothProfileOptionsFromJson(std::string_view text,
                                                  const std::string& source_name) {
  return internal::FieldsFromJson<SmoothProfileOptions>(text, source_name);
}

}  // namespace sysid

namespace sysid {

std::string ToJson(const PiTuningResult& r, const PiTuningOptions& o, int indent) {
  nlohmann::ordered_json j;
  j["kp_v_per_m"] = r.pi.kp_v_per_m;
  j["ki_v_per_m_s"] = r.pi.ki_v_per_m_s;
  j["sample_time_s"] = r.pi.sample_time_s;
  j["u_max_v"] = r.pi.u_max_v;
  j["targets"] = {{"phase_margin_deg", o.phase_margin_deg},
                  {"gain_margin_db", o.gain_margin_db},
                  {"crossover_per_integral_corner", o.crossover_per_integral_corner}};
  j["design_crossover_rad_s"] = r.design_crossover_rad_s;
  j["margins"] = nlohmann::ordered_json::parse(ToJson(r.margins));
  return internal::DumpJson(j, indent);
}

std::string ToJson(const LimitCycleCheck& c, int indent) {
  nlohmann::ordered_json j;
  j["window_s"] = c.window_s;
  j["threshold_m"] = c.threshold_m;
  j["error_peak_to_peak_m"] = c.error_peak_to_peak_m;
  j["control_peak_to_peak_v"] = c.control_peak_to_peak_v;
  j["limit_cycle"] = c.limit_cycle;
  return internal::DumpJson(j, indent);
}

std::string ToJson(const PiBehaviour& b, int indent) {
  using internal::NumberOrNull;
  nlohmann::ordered_json j;
  j["step"] = {{"step_m", b.step_m},
               {"overshoot", NumberOrNull(b.overshoot)},
               {"rise_time_s", NumberOrNull(b.rise_time_s)},
               {"settling_time_s", NumberOrNull(b.settling_time_s)},
               {"final_error_m", b.step_final_error_m},
               {"saturated_samples", b.step_saturated_samples},
               {"max_abs_u_v", b.step_max_abs_u_v}};
  nlohmann::ordered_json sine = {{"amplitude_m", b.sine_amplitude_m},
                                 {"frequency_hz", b.sine_frequency_hz}};
  const nlohmann::ordered_json metrics = nlohmann::ordered_json::parse(ToJson(b.sine));
  for (auto it = metrics.begin(); it != metrics.end(); ++it) sine[it.key()] = it.value();
  sine["limit_cycle"] = nlohmann::ordered_json::parse(ToJson(b.sine_hold));
  j["sine"] = sine;
  return internal::DumpJson(j, indent);
}

std::string TunePiToJson(const std::string& plant, const PiTuningResult& result,
                         const PiTuningOptions& options, const PiBehaviour& behaviour,
                         int indent) {
  nlohmann::ordered_json j;
  j["plant"] = plant;
  j["tuning"] = nlohmann::ordered_json::parse(ToJson(result, options));
  j["behaviour"] = nlohmann::ordered_json::parse(ToJson(behaviour));
  return internal::DumpJson(j, indent);
}

}  // namespace sysid
