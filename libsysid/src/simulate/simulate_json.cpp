// JSON of the simulation options and results (docs/cli.md: simulate --json).
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "core/json_text.hpp"
#include "sysid/error.hpp"
#include "sysid/simulate.hpp"

namespace sysid {
namespace {
using internal::JsonNode;
using Json = nlohmann::ordered_json;
}  // namespace

std::string ToJson(const SimulationOptions& o, int indent) {
  Json j;
  j["t0_s"] = o.t0_s;
  j["t_end_s"] = o.t_end_s;
  j["dt_out_s"] = o.dt_out_s;
  j["output_times_s"] = o.output_times_s;
  j["x0_m"] = o.x0_m;
  j["v0_mps"] = o.v0_mps;
  j["history_v_mps"] = o.history_v_mps;
  j["rtol"] = o.rtol;
  j["atol"] = o.atol;
  j["method"] = ToString(o.method);
  j["max_steps"] = o.max_steps;
  j["max_step_s"] = o.max_step_s;
  j["breakpoint_order"] = o.breakpoint_order;
  j["max_order"] = o.max_order;
  return internal::DumpJson(j, indent);
}

SimulationOptions SimulationOptionsFromJson(std::string_view text, const std::string& source_name) {
  const internal::JsonDocument doc(text, source_name);
  const JsonNode root = doc.Root();
  root.ExpectObject({"t0_s", "t_end_s", "dt_out_s", "output_times_s", "x0_m", "v0_mps",
                     "history_v_mps", "rtol", "atol", "method", "max_steps", "max_step_s",
                     "breakpoint_order", "max_order"});
  // Every key is optional: an absent one keeps its default. The rules are Validate()'s.
  SimulationOptions o;
  auto number = [&](const char* key, double& field) {
    if (root.Has(key)) field = root.Get(key).Number();
  };
  number("t0_s", o.t0_s);
  number("t_end_s", o.t_end_s);
  number("dt_out_s", o.dt_out_s);
  if (root.Has("output_times_s")) o.output_times_s = root.Get("output_times_s").Numbers();
  number("x0_m", o.x0_m);
  number("v0_mps", o.v0_mps);
  number("history_v_mps", o.history_v_mps);
  number("rtol", o.rtol);
  number("atol", o.atol);
  if (root.Has("method")) {
    const JsonNode m = root.Get("method");
    try {
      o.method = ParseIntegratorMethod(m.String());
    } catch (const OptionsError&) {
      m.Expected("\"adams\" or \"bdf\"");
    }
  }
  if (root.Has("max_steps"))
    o.max_steps = root.Get("max_steps").Integer(1, std::numeric_limits<long>::max());
  number("max_step_s", o.max_step_s);
  if (root.Has("breakpoint_order"))
    o.breakpoint_order = static_cast<int>(root.Get("breakpoint_order").Integer(-1000, 1000));
  if (root.Has("max_order"))
    o.max_order = static_cast<int>(root.Get("max_order").Integer(-1000, 1000));
  try {
    o.Validate();
  } catch (const OptionsError& e) {
    doc.FailValidation(e, e.field().empty() ? "" : "/" + e.field());
  }
  return o;
}

std::string ToJson(const SimulationResult& r, const SimulationOptions& options, int indent) {
  Json j;
  j["samples"] = r.trajectory.t_s.size();
  Json ev = Json::array();
  for (const auto& e : r.events) ev.push_back({{"t_s", e.t_s}, {"kind", ToString(e.kind)}});
  j["events"] = ev;
  const SimulationSummary& s = r.summary;
  j["summary"] = {{"termination", ToString(s.termination)},
                  {"method", ToString(options.method)},
                  {"rtol", options.rtol},
                  {"atol", options.atol},
                  {"steps", s.steps},
                  {"rhs_evaluations", s.rhs_evaluations},
                  {"root_evaluations", s.root_evaluations},
                  {"events", s.events},
                  {"reinitialisations", s.reinitialisations},
                  {"wall_time_s", s.wall_time_s}};
  if (!s.IsSolutionUsable()) {
    j["summary"]["message"] = s.message;
    j["summary"]["cvode_flag"] = s.cvode_flag;
    j["summary"]["failure_time_s"] = s.failure_time_s;
  }
  return internal::DumpJson(j, indent);
}

}  // namespace sysid
