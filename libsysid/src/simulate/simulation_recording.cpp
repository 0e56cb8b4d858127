// A run as files and as a full report: the trajectory as a recording and the event log as CSV (`sysid simulate`).
#include <fmt/format.h>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "model/model_json.hpp"
#include "sysid/io.hpp"
#include "sysid/io_csv_table.hpp"
#include "sysid/model.hpp"
#include "sysid/simulate.hpp"

namespace sysid {

Recording TrajectoryRecording(const Trajectory& tr, const std::string& source) {
  Recording r;
  r.source = source;
  r.SetColumn("t", tr.t_s);
  r.SetColumn("u", tr.u_v);
  r.SetColumn("x", tr.x_m);
  r.SetColumn("v", tr.v_mps);
  r.SetColumn("a", tr.a_mps2);
  return r;
}

Recording TrajectoryRecording(const SimulationResult& result, const FrictionModel& model,
                              const std::string& input_description,
                              const SimulationOptions& options) {
  Recording out = TrajectoryRecording(result.trajectory, std::string());
  out.metadata = {{"model", nlohmann::json(internal::ModelJson(model)).dump()},  // keys sorted
                  {"input", input_description},
                  {"simulator", fmt::format("CVODE {} rtol {} atol {}", ToString(options.method),
                                            options.rtol, options.atol)}};
  return out;
}

std::string SimulationSummary::FullReport() const {
  std::string s = BriefReport() + "\n";
  s += fmt::format("  termination: {}; usable: {}\n", ToString(termination),
                   IsSolutionUsable() ? "yes" : "no");
  if (!IsSolutionUsable())
    s += fmt::format("  stopped at t = {:.9g} s: {} ({})\n", failure_time_s, message, cvode_flag);
  return s;
}

std::string EventsToCsv(const std::vector<SimulationEvent>& events) {
  CsvTable csv({"t", "kind"});
  for (const auto& e : events) csv.Number(e.t_s, 17).Text(ToString(e.kind)).EndRow();
  return csv.str();
}

}  // namespace sysid
