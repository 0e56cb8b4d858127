// The pipeline's report for a stack data set (PipelineInputs::IsStack): the hysteresis models'
// table (fitted on the first part of each recording, scored on the rest), the dominance of x,
// v, a, the forward and inverse plots, the model files, models.csv and summary.json.
#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "report/report_sections.hpp"
#include "sysid/io.hpp"
#include "sysid/io_csv_table.hpp"
#include "sysid/report.hpp"

namespace sysid {
namespace {
namespace fs = std::filesystem;
using internal::SigOrDash;

std::string Pct(double v) {
  return std::isnan(v) ? std::string("-") : fmt::format("{:.2f} %", 100 * v);
}

// Markdown cells may not hold a bare '|'.
std::string Cell(std::string s) {
  for (size_t i = 0; (i = s.find('|', i)) != std::string::npos; i += 2) s.replace(i, 1, "\\|");
  return s;
}

// Section 1: the dominance table of `sysid hysteresis dominance` per recording.
std::string DominanceSection(const PipelineResult& r) {
  std::string md;
  md += "\n## 1. Which variable carries the input (`sysid hysteresis dominance`)\n\n";
  md +=
      "A linear inverse model u ≈ c + θ_x x + θ_v v + θ_a a + Σ θ_i F_ri[x] on each "
      "recording's fitted part, the variables ranked by the RMS of their terms:\n\n";
  std::vector<std::vector<std::string>> drows;
  for (const auto& d : r.stack_dominance) {
    std::string terms;
    for (const auto& t : d.ranking)
      terms += (terms.empty() ? "" : ", ") + t.name + " " + SigOrDash(t.rms, 3);
    const bool clear = d.margin >= kClearDominanceMargin;
    drows.push_back({fs::path(d.source).filename().string(),
                     clear ? "**" + d.dominant + "**" : "none clear (" + d.dominant + " leads)",
                     SigOrDash(d.margin, 3), terms, SigOrDash(d.r2, 3)});
  }
  md += MarkdownTable({"recording", "dominant", "margin (top / second)", "term RMS [V]", "R²"},
                      drows);
  md += fmt::format("\nA variable is called dominant at a margin of {:g} or more.\n",
                    kClearDominanceMargin);

  return md;
}

// Section 2: the models' forward and inverse scores (models.csv beside it) and their files.
std::string ModelsSection(const PipelineResult& r,
                          const std::function<std::string(const std::string&)>& path) {
  std::string md;
  md += "\n## 2. Hysteresis models: forward and inverse on the scored part\n\n";
  std::vector<std::vector<std::string>> rows;
  CsvTable csv({"model", "kind", "parameters", "fit_time_s", "train_samples", "test_samples",
                "forward_rms_m", "forward_nrmse_std", "inverse_rms_v", "inverse_nrmse_std",
                "inverse_error", "error"});
  for (size_t i = 0; i < r.stack_models.size(); ++i) {
    const auto& s = r.stack_models[i];
    const std::string inverse =
        s.inverse_error.empty() ? SigOrDash(s.inverse_rms_v) : "- (" + Cell(s.inverse_error) + ")";
    rows.push_back(
        {std::to_string(i + 1), s.label, s.error.empty() ? std::to_string(s.parameters) : "-",
         s.error.empty() ? SigOrDash(s.fit_time_s, 3) : "- (" + Cell(s.error) + ")",
         SigOrDash(s.forward_rms_m), Pct(s.forward_nrmse_std), inverse, Pct(s.inverse_nrmse_std)});
    csv.Quoted(s.label)
        .Text(s.kind)
        .Integer(s.parameters)
        .Number(s.fit_time_s, 6)
        .Integer(s.train_samples)
        .Integer(s.test_samples)
        .Number(s.forward_rms_m)
        .Number(s.forward_nrmse_std)
        .Number(s.inverse_rms_v)
        .Number(s.inverse_nrmse_std)
        .Quoted(s.inverse_error)
        .Quoted(s.error)
        .EndRow();
    if (s.model)
      WriteFileAtomically(path(fmt::format("model_{}_{}.json", i + 1, s.kind)),
                          s.model->ToJson(2) + "\n");
  }
  md += MarkdownTable({"#", "model", "parameters", "fit time [s]", "forward e_RMS [m]",
                       "forward nrmse_std", "inverse e_RMS [V]", "inverse nrmse_std"},
                      rows);
  md +=
      "\nThe fitted models are `model_<row>_<kind>.json` (`sysid hysteresis simulate|invert "
      "--model FILE`); the table is `models.csv`, the run's summary `summary.json`. Fit times "
      "are wall times on this machine (the only numbers of this report that vary between runs).\n";
  WriteFileAtomically(path("models.csv"), csv.str());

  return md;
}

}  // namespace

std::vector<std::string> WriteStackReport(const PipelineResult& r, const std::string& dir) {
  fs::create_directories(dir);
  auto path = [&](const std::string& name) { return (fs::path(dir) / name).string(); };
  std::vector<std::string> notes;
  PlotColours colours;  // one colour per model across the report's plots
  std::vector<std::pair<std::string, PlotSpec>> drawn;
  auto plot = [&](const std::string& file, PlotSpec spec, std::string& md) {
    DrawMeasuredLast(spec);
    colours.Apply(spec);
    const PlotOutcome p = WritePlot(path(file), spec);
    drawn.emplace_back(file, std::move(spec));
    if (p.written) {
      md += "\n![" + spec.title + "](" + file + ")\n";
    } else {
      md += "\n*(plot `" + file + "` not drawn: " + p.message + ")*\n";
      notes.push_back(p.message);
    }
  };
  std::string md = "# libsysid pipeline report: a stack data set\n\n";
  md += "Inputs: `" + r.inputs.root + "` — " + std::to_string(r.inputs.stack.size()) +
        " recording(s) of a stack actuator (columns t [s], u [V], x [m]; no pulse test, so the "
        "stage's friction model is not identified):";
  for (const auto& p : r.inputs.stack) md += " `" + fs::path(p).filename().string() + "`";
  md += "." + internal::MappingSentence(r.inputs) + "\n\n";
  md += fmt::format(
      "**Split.** Every model is fitted on the first {0:g} % of each recording's rows and "
      "scored on the remaining {1:g} %; nothing is chosen on the scored part (the models and "
      "their settings are fixed beforehand: docs/hysteresis.md). Forward: the model simulated "
      "from u alone over the whole recording (its state runs through the fitted part), e_RMS "
      "[m] and nrmse_std = e_RMS / std(x) over the scored rows. Inverse: the model inverted on the "
      "measured x over the whole recording, e_RMS [V] and nrmse_std = e_RMS / std(u) over the "
      "scored rows.\n",
      100 * kStackTrainFraction, 100 * (1 - kStackTrainFraction));

  md += DominanceSection(r);
  md += ModelsSection(r, path);

  // The first recording's scored part, its first samples (a few periods: the loops stay
  // readable): measured beside each model, forward and inverse (the pipeline's traces).
  const PipelineFigures& f = r.figures;
  if (!f.stack_position.empty()) {
    const std::string name = fs::path(f.stack_source).filename().string();
    PlotSpec fwd{"forward models: the start of the scored part of " + name,
                 "t [s]",
                 "x [um]",
                 {},
                 false,
                 1000,
                 550};
    PlotSpec inv{"inverse models: the start of the scored part of " + name,
                 "t [s]",
                 "u [V]",
                 {},
                 false,
                 1000,
                 550};
    for (const auto& t : f.stack_position) fwd.series.push_back({t.label, t.x, 1e6 * t.y, "lines"});
    for (const auto& t : f.stack_voltage) inv.series.push_back({t.label, t.x, t.y, "lines"});
    md += "\nThe first " + std::to_string(f.stack_position.front().x.size()) +
          " scored samples of `" + name +
          "` (legend: the table's row and model; each model keeps its colour in both plots, the "
          "measured trace is black, drawn last):\n";
    plot("stack_forward.png", fwd, md);
    plot("stack_inverse.png", inv, md);
  }

  md += "\n## Run\n\nSteps:";
  for (const auto& [step, seconds] : r.step_seconds) {
    (void)seconds;
    md += " " + step + ";";
  }
  md += " wall times are in `summary.json` and on stderr.\n";
  if (!r.notes.empty()) {
    md += "\nNotes:\n";
    for (const auto& n : r.notes) md += "- " + n + "\n";
  }
  WriteFileAtomically(path("summary.json"), ToJson(StackSummaryOf(r)) + "\n");
  if (!drawn.empty()) WriteFileAtomically(path("plots.json"), PlotIndexJson(drawn));
  WriteFileAtomically(path("report.md"), md);
  return notes;
}

}  // namespace sysid
