// JSON of a tracking run's metrics (docs/cli.md: track --json "schemes" entries), of the PI
// tuning and its behaviour (tune-pi --json), and of the controller and reference-profile
// options: the described structs through their field lists; the track summary (a plant's name
// and the headline metrics of a single run beside them) by hand.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "control/control_json.hpp"
#include "core/json_text.hpp"
#include "sysid/control.hpp"
#include "sysid/control_tuning.hpp"
#include "sysid/error.hpp"

namespace sysid {

std::string ToJson(const TrackingResult& r, int indent) {
  return internal::FieldsToJson(r, indent);
}

TrackingResult TrackingResultFromJson(std::string_view text, const std::string& source_name) {
  const internal::JsonDocument doc(text, source_name);
  TrackingResult r;
  internal::ReadFields(doc.Root(), r);
  return r;
}

std::string ToJson(const SchemeTracking& run, int indent) {
  return internal::FieldsToJson(run, indent);
}

std::string TrackingSummaryToJson(const std::string& plant, const PositionReference& reference,
                                  const PiOptions& pi, const std::vector<SchemeTracking>& runs,
                                  int indent) {
  nlohmann::ordered_json j;
  j["plant"] = plant;
  j["reference"] = reference.description;
  j["kp_v_per_m"] = pi.kp_v_per_m;
  j["ki_v_per_m_s"] = pi.ki_v_per_m_s;
  j["schemes"] = internal::JsonForm<std::vector<SchemeTracking>>::Write(runs);
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

nlohmann::ordered_json JsonForm<FeedforwardScheme>::Write(const FeedforwardScheme& s) {
  return ToString(s);
}

void JsonForm<FeedforwardScheme>::Read(const JsonNode& node, FeedforwardScheme& s) {
  const std::string name = node.String();
  try {
    s = ParseFeedforwardScheme(name);
  } catch (const OptionsError&) {
    node.Expected("one of \"none\", \"analytic\", \"nn\", \"hysteresis\"");
  }
}

nlohmann::ordered_json JsonForm<AntiWindup>::Write(const AntiWindup& a) {
  return AntiWindupName(a);
}

void JsonForm<AntiWindup>::Read(const JsonNode& node, AntiWindup& a) {
  a = ReadName(node, {AntiWindup::kNone, AntiWindup::kConditionalIntegration}, AntiWindupName);
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

std::string ToJson(const PiTuningResult& r, int indent) { return internal::FieldsToJson(r, indent); }

std::string ToJson(const LimitCycleCheck& c, int indent) {
  return internal::FieldsToJson(c, indent);
}

std::string ToJson(const PiBehaviour& b, int indent) { return internal::FieldsToJson(b, indent); }

std::string TunePiToJson(const std::string& plant, const PiTuningResult& result,
                         const PiBehaviour& behaviour, int indent) {
  return internal::FieldsToJson(TunePiSummary{plant, result, behaviour}, indent);
}

}  // namespace sysid
