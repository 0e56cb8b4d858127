// JSON of the simulation options and results (docs/cli.md: simulate --json): the described
// fields (sysid/serialize.hpp), with the run's frame (samples, the integrator beside the
// termination, the stop's details only after a stop) written here.
#include "simulate/simulate_json.hpp"

#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "core/json_fields.hpp"
#include "core/json_text.hpp"
#include "model/model_json.hpp"
#include "sysid/error.hpp"
#include "sysid/simulate.hpp"

namespace sysid {
namespace internal {

nlohmann::ordered_json JsonForm<IntegratorMethod>::Write(const IntegratorMethod& method) {
  return ToString(method);
}

void JsonForm<IntegratorMethod>::Read(const JsonNode& node, IntegratorMethod& method) {
  try {
    method = ParseIntegratorMethod(node.String());
  } catch (const OptionsError&) {
    node.Expected("\"adams\" or \"bdf\"");
  }
}

nlohmann::ordered_json JsonForm<EventKind>::Write(const EventKind& kind) {
  return ToString(kind);
}

void JsonForm<EventKind>::Read(const JsonNode& node, EventKind& kind) {
  kind = ReadName(node,
                  {EventKind::kStick, EventKind::kSlipForward, EventKind::kSlipBackward,
                   EventKind::kReverse, EventKind::kViscousSwitch},
                  [](EventKind k) { return ToString(k); });
}

}  // namespace internal

namespace {

using Json = nlohmann::ordered_json;

// The summary's described fields, the integrator of `options` after the termination; a usable
// run has no stop to describe.
Json SummaryJson(const SimulationSummary& s, const SimulationOptions& options) {
  const Json fields = internal::WriteFields(s);
  Json j;
  for (auto it = fields.begin(); it != fields.end(); ++it) {
    const std::string& key = it.key();
    if (s.IsSolutionUsable() && (key == "message" || key == "cvode_flag" ||
                                 key == "failure_time_s"))
      continue;
    j[key] = *it;
    if (key == "termination") {
      j["method"] = internal::JsonForm<IntegratorMethod>::Write(options.method);
      j["rtol"] = options.rtol;
      j["atol"] = options.atol;
    }
  }
  return j;
}

Json EventsJson(const std::vector<SimulationEvent>& events) {
  return internal::JsonForm<std::vector<SimulationEvent>>::Write(events);
}

}  // namespace

std::string ToJson(const SimulationOptions& o, int indent) {
  return internal::FieldsToJson(o, indent);
}

SimulationOptions SimulationOptionsFromJson(std::string_view text, const std::string& source_name) {
  return internal::FieldsFromJson<SimulationOptions>(text, source_name);
}

std::string ToJson(const SimulationResult& r, const SimulationOptions& options, int indent) {
  Json j;
  j["samples"] = r.trajectory.t_s.size();
  j["events"] = EventsJson(r.events);
  j["summary"] = SummaryJson(r.summary, options);
  return internal::DumpJson(j, indent);
}

std::string SimulationReportJson(const SimulationResult& result, const FrictionModel& model,
                                 const std::string& input_description,
                                 const SimulationOptions& options,
                                 const std::string& output_path, const std::string& events_path,
                                 int indent) {
  auto path_or_null = [](const std::string& path) {
    return path.empty() ? Json(nullptr) : Json(path);
  };
  Json j;
  j["model"] = nlohmann::json(internal::ModelJson(model));  // keys sorted, as the metadata's
  j["input"] = input_description;
  j["t_end_s"] = options.t_end_s;
  j["samples"] = result.trajectory.t_s.size();
  j["output"] = path_or_null(output_path);
  j["events_file"] = path_or_null(events_path);
  j["events"] = EventsJson(result.events);
  j["summary"] = SummaryJson(result.summary, options);
  return internal::DumpJson(j, indent);
}

}  // namespace sysid
