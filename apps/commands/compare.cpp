// sysid compare --model M.json [--nn NN.json] [--json] [-o DIR] DATA.csv...
// Measured voltage vs the analytic inverse and the network, per recording.
#include "sysid/compare.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cli/common.hpp"
#include "cli/motion_flags.hpp"
#include "cli/output_folder.hpp"
#include "cli/recording_flags.hpp"
#include "cli/registry.hpp"
#include "sysid/io.hpp"
#include "sysid/io_containers.hpp"
#include "sysid/report.hpp"

namespace sysid::cli {
namespace {

struct CompareCliOptions {
  std::string model_path;
  std::string nn_path;
  std::vector<std::string> files;
  std::string out_dir;
  bool force = false;
  std::string derivative;  // empty: the recordings' v, a columns (else central from x)
  bool json = false;
  bool plots = true;
  int trim = 5;
  std::string traces = "csv";  // csv or mat: the per-recording traces files
  RecordingFlags recording;
};

/// "v, a: columns v, a (give --derivative to derive them from x)" once per distinct source.
std::string MotionSourcesNote(const std::vector<InverseComparison>& results) {
  std::vector<std::string> seen;
  std::string out;
  for (const auto& c : results) {
    if (std::find(seen.begin(), seen.end(), c.motion_from) != seen.end()) continue;
    seen.push_back(c.motion_from);
    out += MotionSourceNote(c.motion_from) + "\n";
  }
  return out;
}

void RunCompare(const CompareCliOptions& o) {
  namespace fs = std::filesystem;
  // The output folder is checked before any work (cli/output_folder.hpp).
  std::vector<std::string> inputs = o.files;
  inputs.insert(inputs.end(), {o.model_path, o.nn_path});
  const auto folder = OptionalOutputFolder(o.out_dir, o.force, inputs, "compare");
  const FrictionModel model = ReadModel(o.model_path);
  std::optional<NeuralNetwork> nn;
  if (!o.nn_path.empty()) nn = ReadNeuralNetwork(o.nn_path);
  CompareOptions co;
  co.derivative.method = ParseDerivativeMethod(o.derivative.empty() ? "central" : o.derivative);
  co.use_recorded_columns = o.derivative.empty();  // the one rule (MotionOptions)
  co.trim_samples = o.trim;
  // Everything is computed before anything is written: a bad file leaves no partial output.
  std::vector<InverseComparison> results;
  for (size_t i = 0; i < o.files.size(); ++i) {
    Progress(fmt::format("compare: {}/{} {}", i + 1, o.files.size(), o.files[i]));
    results.push_back(CompareInverseModels(ReadRecording(o.files[i], o.recording.Apply({})), model,
                                           nn ? &*nn : nullptr, co));
  }
  ProgressDone();
  nlohmann::ordered_json j;
  j["model"] = o.model_path;
  if (nn) j["nn"] = o.nn_path;
  j["recordings"] = nlohmann::ordered_json::array();
  Table table({"recording", "model", "RMSE [V]", "peak [V]", "NRMSE", "R^2"});
  for (const auto& c : results) {
    const std::string name = fs::path(c.source).stem().string();
    j["recordings"].push_back(nlohmann::ordered_json::parse(ToJson(c)));
    auto row = [&](const char* which, const PredictionErrors& e) {
      table.AddRow(
          {name, which, Num(e.rmse_v, 4), Num(e.peak_error_v, 4), Num(e.nrmse, 4), Num(e.r2, 4)});
    };
    row("analytic", c.analytic);
    if (c.has_nn) row("nn", c.nn);
  }
  if (folder) {
    std::vector<std::string> notes;
    folder->Write([&](const fs::path& dir) {
      for (const auto& c : results) {
        const std::string stem = fs::path(c.source).stem().string();
        WriteRecordingByExtension((dir / (stem + "_traces." + o.traces)).string(),
                                  c.AsRecording());
        if (!o.plots) continue;
        PlotSpec spec;
        spec.title = "inverse models on " + stem;
        spec.x_label = "t [s]";
        spec.y_label = "u [V]";
        spec.series.push_back({"measured", c.t_s, c.u_measured_v, "lines"});
        spec.series.push_back({"analytic inverse", c.t_s, c.u_analytic_v, "lines"});
        if (c.has_nn) spec.series.push_back({"NN inverse", c.t_s, c.u_nn_v, "lines"});
        const auto p = WritePlot((dir / (stem + ".png")).string(), spec);
        if (!p.written) notes.push_back(p.message);
      }
      WriteFileAtomically((dir / "summary.csv").string(), ComparisonTableCsv(results));
      WriteFileAtomically((dir / "summary.json").string(), j.dump(2) + "\n");
    });
    for (const auto& n : notes) std::cerr << "sysid compare: " << n << '\n';
  }
  if (o.json) {
    std::cout << j.dump(2) << '\n';
  } else {
    std::cout << table.Render() << MotionSourcesNote(results);
  }
}

void AddCompareCommand(CLI::App& app) {
  auto o = std::make_shared<CompareCliOptions>();
  CLI::App* cmd = app.add_subcommand(
      "compare",
      "Compare inverse models on recordings: measured u beside the analytic inverse "
      "(x'' + a1 v(t-tau) + a2 sgn v)/a3 and the network's prediction; RMSE, peak error, NRMSE");
  cmd->add_option("--model", o->model_path, "friction model JSON (a1p, a1n, a2p, a2n, a3, tau)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--nn", o->nn_path,
                  "neural inverse model JSON (inputs by name: v [m/s], "
                  "a [m/s^2])")
      ->check(CLI::ExistingFile);
  cmd->add_option("files", o->files,
                  "recordings: t [s], u [V] and x [m] (or v [m/s] and a [m/s^2] columns)")
      ->required()
      ->type_name("DATA.csv");
  cmd->add_option("--derivative", o->derivative,
                  "derive v, a from x with this filter even when the file has v, a columns "
                  "(without it: the columns, else central): central | butterworth | savgol")
      ->check(CLI::IsMember({"central", "butterworth", "savgol"}))
      ->default_str("central");
  cmd->add_option("--trim", o->trim, "samples dropped at each end before scoring [samples]")
      ->check(CLI::NonNegativeNumber);
  AddOutputOption(cmd, o->out_dir,
                  "new folder for <name>_traces.csv, <name>.png, summary.csv, summary.json")
      ->type_name("DIR");
  cmd->add_flag("--force", o->force,
                "replace a folder an earlier sysid compare wrote (one holding .sysid-output)");
  cmd->add_flag("--json", o->json, "print one JSON object with the metrics per recording");
  cmd->add_flag("!--no-plots", o->plots, "skip the PNG plots in the output folder");
  cmd->add_option("--traces", o->traces,
                  "format of the per-recording traces in the output folder: csv, or mat (MAT v5, "
                  "one variable per column)")
      ->check(CLI::IsMember({"csv", "mat"}))
      ->capture_default_str();
  o->recording.Add(cmd);
  cmd->callback([o] { RunCompare(*o); });
}

const bool kRegistered = RegisterCommand(70, &AddCompareCommand);

}  // namespace
}  // namespace sysid::cli
