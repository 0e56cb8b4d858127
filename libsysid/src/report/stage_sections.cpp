// The report's sections 7 and 8 (the paper's facts on the stage, the voltage-velocity loops)
// and its closing lines (the steps run, the run's notes).
#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "report/report_sections.hpp"
#include "sysid/io_csv_table.hpp"

namespace sysid::internal {

ReportSection FactsSection(const PipelineResult& r) {
  ReportSection s;
  if (!r.facts) return s;
  s.markdown = "\n## 7. The paper's facts on the stage (`sysid stage facts`)\n\n";
  s.markdown +=
      "Each fact of the paper measured on this stage by the paper's own experiment "
      "(docs/virtual_stage.md, \"Stage facts\"). F1-F6 and F8 are required of a stage that "
      "stands in for the paper's; F7 is reported (its figure pair is in section 4, F8's loop "
      "numbers in section 8).\n\n";
  s.markdown += r.facts->ToMarkdown();
  std::string failed;
  for (const auto& f : r.facts->facts)
    if (f.required && !f.met) failed += (failed.empty() ? "" : ", ") + f.id;
  s.markdown += failed.empty() ? "\nEvery required fact is met.\n"
                               : "\n**Not met on this stage: " + failed +
                                     ".** Numbers downstream of these facts describe this stage, "
                                     "not the paper's.\n";
  for (const auto& f : r.facts->facts)
    if (!f.met && !f.note.empty()) s.markdown += "- " + f.id + ": " + f.note + "\n";
  s.files.emplace_back("facts.json", r.facts->ToJson() + "\n");
  return s;
}

ReportSection LoopsSection(const PipelineResult& r) {
  ReportSection s;
  ReportSection fact = r.facts ? LoopFactSection(*r.facts) : ReportSection{};
  if (r.loops.empty() && fact.markdown.empty()) return s;
  s.markdown = "\n## 8. Voltage-velocity loop (slow open-loop sweep)\n\n";
  s.markdown +=
      "The paper's triangle test (its Fig. 3: an asymmetric loop). Velocity where |u| "
      "passes each level going up and going down (mean of ±10 samples; `sysid loop`); "
      "width = how much faster the stage runs on the way down. A static inverse (the "
      "analytic one, a network on v alone) follows one curve through the loop.\n";
  CsvTable csv({"source", "level_v", "v_rising_mps", "v_falling_mps", "width_mps"});
  auto volts = [](double u) { return std::isnan(u) ? std::string("never") : Sig(u, 4) + " V"; };
  auto mm = [](double v) {
    return std::isnan(v) ? std::string("-") : fmt::format("{:.2f}", 1e3 * v);
  };
  for (std::size_t i = 0; i < r.loops.size(); ++i) {
    const VoltageLoop& l = r.loops[i];
    const std::string name = std::filesystem::path(l.source).filename().string();
    s.markdown += fmt::format(
        "\n`{}`: u from {} to {} V; starts forward at {}, backward at {}; stops forward at "
        "{}, backward at {}.\n\n",
        name, Sig(l.peak_backward_v, 4), Sig(l.peak_forward_v, 4), volts(l.start_forward_v),
        volts(l.start_backward_v), volts(l.stop_forward_v), volts(l.stop_backward_v));
    std::vector<std::vector<std::string>> rows;
    for (const auto& lv : l.levels) {
      rows.push_back(
          {Sig(lv.level_v, 4), mm(lv.v_rising_mps), mm(lv.v_falling_mps), mm(lv.WidthMps())});
      csv.Text(name)
          .Number(lv.level_v)
          .Number(lv.v_rising_mps)
          .Number(lv.v_falling_mps)
          .Number(lv.WidthMps())
          .EndRow();
    }
    s.markdown += MarkdownTable(
        {"u [V]", "v, \\|u\\| rising [mm/s]", "v, \\|u\\| falling [mm/s]", "width [mm/s]"}, rows);
    PlotSpec spec{"voltage-velocity loop: " + name, "u [V]", "v [mm/s]", {}, false, 900, 600};
    spec.series.push_back({name, l.u_v, 1e3 * l.v_mps, "lines"});
    s.AddPlot(fmt::format("loop_{}.png", i + 1), spec, "voltage-velocity loop " + name);
    s.files.emplace_back(fmt::format("loop_{}.json", i + 1), ToJson(l) + "\n");
  }
  if (!r.loops.empty()) s.files.emplace_back("loops.csv", csv.str());
  s.Append(std::move(fact));
  return s;
}

ReportSection StepsSection(const PipelineResult& r) {
  ReportSection s;
  // Wall times go to stderr and `pipeline --json`, never into the report: the same inputs
  // and seed give a byte-identical report folder.
  s.markdown = "\n## Run\n\nSteps:";
  for (const auto& [name, seconds] : r.step_seconds) {
    (void)seconds;
    s.markdown += " " + name + ";";
  }
  s.markdown += " wall times are printed on stderr and in `sysid pipeline --json`.\n";
  if (!r.notes.empty()) {
    s.markdown += "\nNotes:\n";
    for (const auto& n : r.notes) s.markdown += "- " + n + "\n";
  }
  return s;
}

}  // namespace sysid::internal
