// sysid pipeline DIR|MANIFEST.json [-o OUT] [--json] ...: the whole workflow, recordings in,
// report + model files out.
#include "sysid/pipeline.hpp"
#include "sysid/report.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>

#include "cli/common.hpp"
#include "cli/field_flag.hpp"
#include "cli/output_folder.hpp"
#include "cli/pi_flags.hpp"
#include "cli/recording_flags.hpp"
#include "cli/registry.hpp"
#include "sysid/error.hpp"

namespace sysid::cli {
namespace {
namespace fs = std::filesystem;

struct PipelineCliOptions {
  std::string input;
  std::string out_dir = "sysid-report";
  bool force = false;
  PipelineOptions options;  // the flags' defaults are the library's
  std::string hidden;  // FIRST:LAST:STEP or a list; set from options.hidden_sizes
  std::string inputs;
  RecordingFlags recording;  // --var/--rate/--scale for every recording of the folder
  bool json = false;
};

// A stack data set's run: the hysteresis models' table (report.md has the same).
void PrintStackSummary(const PipelineResult& r, const fs::path& out, bool json) {
  if (json) {
    StackSummary summary = StackSummaryOf(r);
    summary.report = (out / "report.md").string();
    std::cout << ToJson(summary);
    return;
  }
  for (const auto& d : r.stack_dominance)
    std::cout << fmt::format(
        "{}: {}\n", fs::path(d.source).filename().string(),
        DominanceVerdict(d.dominant, d.ranking.size() > 1 ? d.ranking[1].name : "", d.margin));
  std::cout << fmt::format("stack data set: models fitted on the first {:g} % of each recording, "
                           "scored on the rest\n", 100 * kStackTrainFraction);
  Table t({"model", "params", "fit [s]", "fwd e_RMS [m]", "fwd nrmse_std", "inv e_RMS [V]",
           "inv nrmse_std"});
  auto pct = [](double v) { return std::isnan(v) ? std::string("-") : Num(100 * v, 3) + " %"; };
  auto num = [](double v) { return std::isnan(v) ? std::string("-") : Num(v, 4); };
  for (const auto& s : r.stack_models)
    t.AddRow({s.label, std::to_string(s.parameters), Num(s.fit_time_s, 3), num(s.forward_rms_m),
              pct(s.forward_nrmse_std), s.inverse_error.empty() ? num(s.inverse_rms_v) : "refused",
              pct(s.inverse_nrmse_std)});
  std::cout << t.Render();
  for (const auto& s : r.stack_models) {
    if (!s.error.empty()) std::cout << s.label << ": no score: " << s.error << '\n';
    if (!s.inverse_error.empty()) std::cout << s.label << ": no inverse: " << s.inverse_error << '\n';
  }
  std::cout << "report: " << (out / "report.md").string() << '\n';
}

void RunPipelineCommand(const PipelineCliOptions& o) {
  if (!(o.options.pulse_fit_fraction > 0))
    throw OptionsError(
        fmt::format("--fit-fraction {:g}: expected 0 < F <= 1", o.options.pulse_fit_fraction),
        "--fit-fraction");
  // Check the output folder before any work (cli/output_folder.hpp).
  const OutputFolder folder(o.out_dir, o.force, {o.input}, "pipeline");
  const fs::path& out = folder.path();
  std::error_code ec;  // a link loop is no folder: the manifest reader names it (exit 2)
  PipelineInputs inputs = fs::is_directory(o.input, ec) ? PipelineInputs::FromDirectory(o.input)
                                                         : PipelineInputs::FromManifest(o.input);
  inputs.mapping = o.recording.Mapping();
  PipelineOptions opt = o.options;
  opt.hidden_sizes = ParseHiddenSizes(o.hidden);
  if (!o.inputs.empty()) opt.nn_inputs = CLI::detail::split(o.inputs, ',');
  PipelineResult r = RunPipeline(inputs, opt, [](const std::string& step) {
    Progress("pipeline: " + step + " ...");
    ProgressDone();
  });
  // The report is written into a temporary sibling folder and renamed into place: a failure
  // never leaves a half-written report behind, and a previous one is replaced whole.
  std::vector<std::string> notes;
  // The report's own time (tables, model files, plots) is a step of the job like the others;
  // it is appended after the report is written, so report.md's step list never depends on it.
  Progress("pipeline: write report ...");
  ProgressDone();
  const auto report_t0 = std::chrono::steady_clock::now();
  folder.Write([&](const fs::path& dir) { notes = WritePipelineReport(r, dir.string()); });
  r.step_seconds.emplace_back(
      "write report (tables, plots)",
      std::chrono::duration<double>(std::chrono::steady_clock::now() - report_t0).count());
  for (const auto& n : notes) std::cerr << "sysid pipeline: " << n << '\n';
  {
    // Timing goes to stderr (and --json), not into the report, which stays reproducible.
    std::string times;
    for (const auto& [name, s] : r.step_seconds) times += fmt::format(" {} {:.3g} s;", name, s);
    std::cerr << "sysid pipeline: wall time:" << times << '\n';
  }
  if (inputs.IsStack()) {
    PrintStackSummary(r, out, o.json);
    return;
  }
  for (const auto& s : r.skipped) std::cerr << "sysid pipeline: skipped: " << s << '\n';

  if (!r.pulse.a3_given)
    std::cerr << "sysid pipeline: warning: " << DescribeA3(r.pulse.model.a3, false)
              << "; a1 and a2 scale with it (the report repeats this)\n";
  if (o.json) {
    std::cout << ToJson(r, (out / "report.md").string());
    return;
  }
  std::cout << fmt::format(
      "model: a1p={:.6g} a1n={:.6g} a2p={:.6g} a2n={:.6g} a3={:.6g} tau={:.4g} s\n", r.model.a1p,
      r.model.a1n, r.model.a2p, r.model.a2n, r.model.a3, r.model.tau_s);
  if (r.skipped.empty())
    std::cout << fmt::format(
        "dominant variable: {}; network {} hidden units, test MSE {:.4g} V^2\n",
        r.dominance.dominant, r.network.hidden_size(), r.network_test_mse);
  for (const auto& v : r.validations)
    for (const auto& out : v.outputs)
      std::cout << fmt::format("validation on {}: {} fit {:.4g} %\n",
                               fs::path(v.source).filename().string(), out.output,
                               out.scores.fit_percent);
  if (r.tuning)
    std::cout << fmt::format(
        "PI tuned on the model: Kp = {:.5g} V/m, Ki = {:.5g} V/(m s) at {:g} Hz\n",
        r.tuning->pi.kp_v_per_m, r.tuning->pi.ki_v_per_m_s, 1 / r.tuning->pi.sample_time_s);
  for (const auto& [title, rows] :
       {std::pair<std::string, const std::vector<TrackingRow>*>{"on the stage", &r.tracking},
        {"on the identified model", &r.model_tracking}}) {
    if (rows->empty()) continue;
    Table t({"freq [Hz]", "feedforward", "max |e| [mm]", "RMS e [mm]"});
    for (const auto& row : *rows)
      t.AddRow({Num(row.frequency_hz, 3), row.scheme, Num(1e3 * row.result.max_error_m, 4),
                Num(1e3 * row.result.rms_error_m, 4)});
    std::cout << "PI tracking " << title << ":\n" << t.Render();
  }
  std::cout << "report: " << (out / "report.md").string() << '\n';
}

void AddPipelineCommand(CLI::App& app) {
  auto o = std::make_shared<PipelineCliOptions>();
  CLI::App* cmd = app.add_subcommand(
      "pipeline",
      "The whole workflow on a stage's recordings: identify -> tune delay -> [refine] -> "
      "dominance -> NN sweep (+ typical (v, a) network) -> compare -> PI tracking -> report. "
      "DIR holds pulses*, training*, test*, waveform* and optionally "
      "loop* recordings (slow open-loop sweeps: the voltage-velocity loop) as .csv, .mat, .h5 "
      "or .hdf5 (--var/--rate/--scale map every one) and stage.json (enables "
      "tracking), or a manifest.json naming them. A folder with none of pulses*, train*, "
      "test* (or a manifest {\"stack\": [...]}) is a stack data set: its recordings (t, u, x) "
      "fit the hysteresis models on their first 40 % and score them on the rest. Pulse "
      "recordings alone (no training or test set) run identify, tune delay, [refine], "
      "validation on each pulse recording's held-out end (--fit-fraction), the PI gains' "
      "margins, PI tuning and tracking on the identified model, and name the recordings that "
      "would enable the other steps");
  cmd->add_option("input", o->input, "folder of recordings, or a manifest JSON")
      ->required()
      ->check(CLI::ExistingPath)
      ->type_name("DIR|MANIFEST");
  AddOutputOption(cmd, o->out_dir,
                  "report folder: new, empty, or an earlier sysid report with --force")
      ->type_name("DIR")
      ->capture_default_str();
  cmd->add_flag("--force", o->force,
                "replace an earlier sysid report folder (one holding .sysid-output)");
  PipelineOptions& p = o->options;
  o->hidden = FormatHiddenSizes(p.hidden_sizes);
  AddFieldOption(cmd, "--a3", p, p.a3,
                 "actuator gain for the pulse method [m/(s^2 V)] (a manifest's a3 wins); the "
                 "default is the paper's HR-8 data-sheet value, not your stage's")
      ->check(PositiveNumber())
      ->each([&p](const std::string&) { p.a3_given = true; });
  // --hidden and --inputs are text, parsed into hidden_sizes and nn_inputs when the command runs.
  BindField(cmd,
            cmd->add_option("--hidden", o->hidden,
                            "hidden sizes to sweep: first:last:step or a list")
                ->capture_default_str(),
            p, p.hidden_sizes);
  BindField(cmd,
            cmd->add_option("--inputs", o->inputs,
                            "network inputs, comma separated (v, a); default: the dominant "
                            "variable"),
            p, p.nn_inputs);
  AddFieldOption(cmd, "--max-epochs", p, p.training.max_epochs, "LM epoch limit per network")
      ->check(CLI::Range(std::uint64_t{0}, std::uint64_t{1} << 62));  // CLI11 would wrap -1
  AddFieldOption(cmd, "--typical-epochs", p, p.typical_max_epochs,
                 fmt::format("LM epoch limit of the typical {}-unit (v, a) network",
                             p.typical_hidden))
      ->check(CLI::Range(std::uint64_t{0}, std::uint64_t{1} << 62));  // CLI11 would wrap -1
  AddFieldOption(cmd, "--typical-stride", p, p.typical_stride,
                 "train the typical network on every n-th training row")
      ->check(PositiveNumber());
  BindField(cmd, AddOffFlag(cmd, "--no-typical", p.typical, "skip the typical (v, a) network"),
            p, p.typical);
  BindField(cmd, AddOffFlag(cmd, "--no-delay", p.tune_delay, "keep tau = 0 (no delay tuning)"),
            p, p.tune_delay);
  AddFieldFlag(cmd, "--refine", p, p.refine, "refine all parameters by output error (Ceres)");
  BindField(cmd, AddOffFlag(cmd, "--no-track", p.track, "skip the PI tracking experiment"), p,
            p.track);
  AddFieldOption(cmd, "--fit-fraction", p, p.pulse_fit_fraction,
                 "with pulse recordings alone: identify on the first fraction F of each pulse "
                 "recording's duration and validate on the rest, 0 < F <= 1 (unused with a "
                 "training set)")
      ->type_name("F")
      ->check(CLI::Range(0.0, 1.0));
  AddFieldFlag(cmd, "--facts", p, p.facts,
               "also check the paper's facts F1-F8 on the stage file (sysid stage facts, ~10 s): "
               "table in the report, facts.json");
  AddPiGainOptions(cmd, p, p.pi, "PI ");
  BindField(cmd, AddSeedOption(cmd, p.training.seed, "seed of the network initialisations"), p,
            p.training.seed);
  BindField(cmd,
            AddThreadsOption(cmd, p.threads,
                             "threads for every long step; 0 = all cores; results do not "
                             "depend on it"),
            p, p.threads);
  BindField(cmd,
            cmd->add_option("--reference", p.reference_path,
                            "JSON of reference numbers to set beside ours "
                            "(experiments/paper_numbers.json)")
                ->check(CLI::ExistingFile),
            p, p.reference_path);
  o->recording.Add(cmd);
  cmd->add_flag("--json", o->json,
                "print a JSON summary (model, dominant, MSEs, tracking, the PI gains' margins, "
                "facts' verdicts, steps)");
  cmd->callback([o] { RunPipelineCommand(*o); });
}

const bool kRegistered = RegisterCommand(90, &AddPipelineCommand);

}  // namespace
}  // namespace sysid::cli
