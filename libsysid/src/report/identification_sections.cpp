// The report's sections 1 and 2: the pulse test's model and the delay of its viscous term.
#include <fmt/format.h>

#include <filesystem>
#include <string>
#include <tuple>
#include <vector>

#include "report/report_sections.hpp"
#include "sysid/io_csv_table.hpp"
#include "sysid/model.hpp"

namespace sysid::internal {
namespace {
namespace fs = std::filesystem;

// Measured velocity of the first pulse recording beside the model with tau = 0 and tuned.
void AddVelocityPlot(const PipelineFigures& f, ReportSection& s) {
  if (!f.pulse_velocity_note.empty()) {
    s.notes.push_back(f.pulse_velocity_note);
    return;
  }
  if (f.pulse_velocity.empty()) return;
  PlotSpec spec{
      "pulse response: measured and simulated velocity", "t [s]", "v [m/s]", {}, false, 1100, 500};
  for (const auto& t : f.pulse_velocity) spec.series.push_back({t.label, t.x, t.y, "lines"});
  s.AddPlot("pulse_velocity.png", spec, "measured vs simulated velocity");
}

// The pulse method's estimates (a3 given, tau = 0) beside the final model after the delay (and
// refinement), so that neither hides the other; the reference's values in a last column.
std::string ParameterTable(const PipelineResult& r) {
  const auto& p = r.pulse;
  const PipelineReference* ref = r.reference && r.reference->model ? &*r.reference : nullptr;
  std::vector<std::string> header{"parameter", "pulse LS", "std. error", "final model"};
  if (ref) header.push_back(ref->label);
  std::vector<std::vector<std::string>> rows;
  const std::vector<std::tuple<const char*, double, double>> values{
      {"a1p", p.model.a1p, r.model.a1p}, {"a1n", p.model.a1n, r.model.a1n},
      {"a2p", p.model.a2p, r.model.a2p}, {"a2n", p.model.a2n, r.model.a2n},
      {"a3", p.model.a3, r.model.a3},    {"tau", p.model.tau_s, r.model.tau_s}};
  for (const auto& [name, pulse_value, final_value] : values) {
    std::string se = "—";
    for (size_t i = 0; i < p.fit.names.size(); ++i)
      if (p.fit.names[i] == name) se = Sig(p.fit.std_error[static_cast<Eigen::Index>(i)], 3);
    std::vector<std::string> row{name, Sig(pulse_value, 7), se, Sig(final_value, 7)};
    if (ref) {
      const auto v = ref->ModelValue(name);
      row.push_back(v ? Sig(*v, 7) : "");
    }
    rows.push_back(row);
  }
  return MarkdownTable(header, rows);
}

}  // namespace

ReportSection PulseSection(const PipelineResult& r) {
  ReportSection s;
  const auto& p = r.pulse;
  s.markdown = "\n## 1. Pulse-test identification\n\n";
  std::vector<std::vector<std::string>> rows;
  CsvTable csv(
      {"source", "t_start_s", "duration_s", "u_v", "v_mps", "v_stderr_mps", "status", "reason"});
  for (const auto& e : p.pulses) {
    rows.push_back({fs::path(e.pulse.source).filename().string(), Sig(e.pulse.t_start_s, 4),
                    Sig(e.pulse.amplitude_v, 4), Sig(e.v_mps, 5), ToString(e.status), e.reason});
    csv.Text(e.pulse.source)
        .Number(e.pulse.t_start_s)
        .Number(e.pulse.duration_s)
        .Number(e.pulse.amplitude_v)
        .Number(e.v_mps)
        .Number(e.v_stderr_mps)
        .Text(ToString(e.status))
        .Quoted(e.reason)
        .EndRow();
  }
  s.markdown += MarkdownTable(
      {"recording", "t start [s]", "u [V]", "steady v [m/s]", "status", "reason"}, rows);
  s.files.emplace_back("pulses.csv", csv.str());
  s.markdown += "\nLeast squares (column-pivoted QR), condition number " +
                Sig(p.fit.condition_number, 4) + ", relative residual " +
                Sig(p.fit.relative_error, 3) + ":\n\n";
  s.markdown += ParameterTable(r);
  if (!p.a3_given) s.markdown += "\n**Warning:** " + DescribeA3(p.model.a3, false) + ".\n";
  s.markdown +=
      "\nThe final model (" + std::string(p.a3_given ? "a3 given" : "a3 the default") +
      ", then the delay" +
      std::string(r.refine ? " and the output-error refinement of all six parameters" : "") +
      ") is `model.json`.\n";
  s.writes.emplace_back("model.json", [&r](const std::string& path) { WriteModel(path, r.model); });
  return s;
}

ReportSection DelaySection(const PipelineResult& r) {
  ReportSection s;
  if (!r.delay) return s;
  const auto& d = *r.delay;
  s.markdown = "\n## 2. Delay of the viscous term\n\n";
  s.markdown += fmt::format(
      "NLopt (DIRECT-L then BOBYQA) over tau: **tau = {:.4g} ms**, cost {:.4g} m²/s² (RMS "
      "velocity error {:.3g} m/s), {} evaluations, {} simulations. {}\n",
      1e3 * d.tau_s, d.cost, d.rms_error_mps, d.evaluations, d.simulations, d.message);
  if (r.reference)
    if (const auto tau = r.reference->ModelValue("tau"))
      s.markdown += fmt::format("\n{}: tau = {:.4g} ms.\n", r.reference->label, 1e3 * *tau);
  Eigen::VectorXd tau(static_cast<Eigen::Index>(d.curve.size())), cost(tau.size());
  for (size_t i = 0; i < d.curve.size(); ++i) {
    tau[static_cast<Eigen::Index>(i)] = 1e3 * d.curve[i].first;
    cost[static_cast<Eigen::Index>(i)] = d.curve[i].second;
  }
  s.AddPlot("delay_cost.png",
            {"delay fit: cost against tau",
             "tau [ms]",
             "cost [m^2/s^2]",
             {{"sum of squared velocity errors", tau, cost, "linespoints"}},
             true,
             900,
             500},
            "cost against tau");
  if (r.refine)
    s.markdown += "\nOutput-error refinement (Ceres): " + r.refine->BriefReport() + "\n";
  AddVelocityPlot(r.figures, s);
  return s;
}

}  // namespace sysid::internal
