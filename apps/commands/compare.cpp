// sysid compare [--model M.json] [--nn NN.json] [--hysteresis H.json]... [--json] [-o DIR] DATA.csv...
// Measured voltage vs the analytic inverse, the network and hysteresis models' inverses, per
// recording.
#include "sysid/compare.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "cli/common.hpp"
#include "cli/field_flag.hpp"
#include "cli/motion_flags.hpp"
#include "cli/output_folder.hpp"
#include "cli/recording_flags.hpp"
#include "cli/registry.hpp"
#include "sysid/compare_hysteresis.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"
#include "sysid/io_containers.hpp"
#include "sysid/report.hpp"

namespace sysid::cli {
namespace {

struct CompareCliOptions {
  std::string model_path;
  std::string nn_path;
  std::vector<std::string> hysteresis_paths;
  std::vector<std::string> files;
  std::string out_dir;
  bool force = false;
  std::string derivative;  // empty: the recordings' v, a columns (else central from x)
  bool json = false;
  bool plots = true;
  CompareOptions options;  // trim_samples; the derivative comes from `derivative`
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

/// A hysteresis model file for compare: read, labelled "KIND:STEM", and refused up front (exit 2
/// naming the file, nothing written) when it cannot be inverted at all.
struct HysteresisEntry {
  std::string path;
  std::unique_ptr<HysteresisModel> model;
  std::string label;
};

std::vector<HysteresisEntry> ReadHysteresisModels(const std::vector<std::string>& paths) {
  std::vector<HysteresisEntry> out;
  for (const auto& path : paths) {
    HysteresisEntry e;
    e.path = path;
    e.model = ReadHysteresisModel(path);
    e.label = e.model->kind() + ":" + std::filesystem::path(path).stem().string();
    for (const auto& other : out)
      if (other.label == e.label)
        throw OptionsError("--hysteresis: " + other.path + " and " + path +
                           " would both be labelled '" + e.label +
                           "' (KIND:FILE_STEM); give the files different names");
    if (!e.model->invertible()) {
      std::string why = "the " + e.model->kind() + " model is not invertible";
      try {
        e.model->Invert(Eigen::VectorXd::Zero(2), 1.0);  // the model's own reason
      } catch (const Error& err) {
        why = err.what();
      }
      throw InputError("--hysteresis " + path + ": cannot be used as an inverse model: " + why);
    }
    out.push_back(std::move(e));
  }
  return out;
}

void RunCompare(const CompareCliOptions& o) {
  namespace fs = std::filesystem;
  if (o.model_path.empty() && o.nn_path.empty() && o.hysteresis_paths.empty())
    throw OptionsError("--model, --nn, --hysteresis: give at least one inverse model");
  // The output folder is checked before any work (cli/output_folder.hpp).
  std::vector<std::string> inputs = o.files;
  inputs.insert(inputs.end(), {o.model_path, o.nn_path});
  inputs.insert(inputs.end(), o.hysteresis_paths.begin(), o.hysteresis_paths.end());
  const auto folder = OptionalOutputFolder(o.out_dir, o.force, inputs, "compare");
  std::optional<FrictionModel> model;
  if (!o.model_path.empty()) model = ReadModel(o.model_path);
  std::optional<NeuralNetwork> nn;
  if (!o.nn_path.empty()) nn = ReadNeuralNetwork(o.nn_path);
  const std::vector<HysteresisEntry> hysteresis = ReadHysteresisModels(o.hysteresis_paths);
  std::vector<NamedHysteresisModel> named;
  for (const auto& h : hysteresis) named.push_back({h.label, h.model.get()});
  CompareOptions co = o.options;
  co.derivative.method = ParseDerivativeMethod(o.derivative.empty() ? "central" : o.derivative);
  co.use_recorded_columns = o.derivative.empty();  // the one rule (MotionOptions)
  // Everything is computed before anything is written: a bad file leaves no partial output.
  std::vector<InverseComparison> results;
  for (size_t i = 0; i < o.files.size(); ++i) {
    Progress(fmt::format("compare: {}/{} {}", i + 1, o.files.size(), o.files[i]));
    const Recording rec = ReadRecording(o.files[i], o.recording.Apply({}));
    try {
      results.push_back(
          CompareInverseModels(rec, model ? &*model : nullptr, nn ? &*nn : nullptr, named, co));
    } catch (const NumericalError& e) {
      // A model that refuses or overflows on this recording's reference is the input's
      // problem (exit 2); the message names the model, and the recording once.
      const std::string what = e.what();
      throw InputError(what.rfind(rec.source + ":", 0) == 0 ? what : o.files[i] + ": " + what);
    }
  }
  ProgressDone();
  nlohmann::ordered_json j;
  if (model) j["model"] = o.model_path;
  if (nn) j["nn"] = o.nn_path;
  if (!hysteresis.empty()) {
    j["hysteresis"] = nlohmann::ordered_json::array();
    for (const auto& h : hysteresis)
      j["hysteresis"].push_back({{"label", h.label}, {"kind", h.model->kind()}, {"file", h.path}});
  }
  j["recordings"] = nlohmann::ordered_json::array();
  Table table({"recording", "model", "RMSE [V]", "peak [V]", "nrmse_range", "R^2"});
  for (const auto& c : results) {
    const std::string name = fs::path(c.source).stem().string();
    j["recordings"].push_back(nlohmann::ordered_json::parse(ToJson(c)));
    auto row = [&](const std::string& which, const PredictionErrors& e) {
      table.AddRow({name, which, Num(e.rmse_v, 4), Num(e.peak_error_v, 4), Num(e.nrmse_range, 4),
                    Num(e.r2, 4)});
    };
    if (c.has_analytic) row("analytic", c.analytic);
    if (c.has_nn) row("nn", c.nn);
    for (const auto& h : c.hysteresis) row(h.label, h.errors);
  }
  if (folder) {
    std::vector<std::string> notes;
    PlotColours colours;  // one colour per model across every recording's plots
    std::vector<std::pair<std::string, PlotSpec>> drawn;
    folder->Write([&](const fs::path& dir) {
      for (const auto& c : results) {
        const std::string stem = fs::path(c.source).stem().string();
        WriteRecordingByExtension((dir / (stem + "_traces." + o.traces)).string(),
                                  c.AsRecording());
        if (!o.plots) continue;
        for (auto& [file, spec] : ComparisonPlots(c, stem, colours)) {
          const auto p = WritePlot((dir / file).string(), spec);
          if (!p.written) notes.push_back(p.message);
          drawn.emplace_back(file, std::move(spec));
        }
      }
      if (!drawn.empty()) WriteFileAtomically((dir / "plots.json").string(), PlotIndexJson(drawn));
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
      "(x'' + a1 v(t-tau) + a2 sgn v)/a3, the network's prediction and hysteresis models "
      "inverted on the recorded x; RMSE, peak error, nrmse_range = RMSE / (max u - min u) (at "
      "least one of --model, --nn, "
      "--hysteresis)");
  cmd->add_option("--model", o->model_path, "friction model JSON (a1p, a1n, a2p, a2n, a3, tau)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--nn", o->nn_path,
                  "neural inverse model JSON (inputs by name: v [m/s], "
                  "a [m/s^2])")
      ->check(CLI::ExistingFile);
  cmd->add_option("--hysteresis", o->hysteresis_paths,
                  "hysteresis model file from `sysid hysteresis fit` (repeatable): its inverse "
                  "on the recording's x [m] from the model's initial state; row KIND:FILE_STEM")
      ->check(CLI::ExistingFile)
      ->allow_extra_args(false)  // one file per flag: the recordings stay positionals
      ->type_name("H.json");
  cmd->add_option("files", o->files,
                  "recordings: t [s], u [V] and x [m] (or v [m/s] and a [m/s^2] columns)")
      ->required()
      ->type_name("DATA.csv");
  // Given, --derivative sets the filter and turns use_recorded_columns off when the command runs.
  CompareOptions& co = o->options;
  CLI::Option* derivative =
      cmd->add_option("--derivative", o->derivative,
                      "derive v, a from x with this filter even when the file has v, a columns "
                      "(without it: the columns, else central): central | butterworth | savgol")
          ->check(CLI::IsMember({"central", "butterworth", "savgol"}))
          ->default_str("central");
  BindField(cmd, derivative, co, co.derivative.method);
  BindField(cmd, derivative, co, co.use_recorded_columns);
  BindField(cmd,
            cmd->add_option("--trim", co.trim_samples,
                            "samples dropped at each end before scoring [samples]")
                ->check(NonNegativeNumber()),
            co, co.trim_samples);
  AddOutputOption(cmd, o->out_dir,
                  "new folder for <name>_traces.csv, summary.csv, summary.json and the plots "
                  "(<name>.png, <name>_error.png, <name>_zoom.png, <name>_loop.png; plots.json "
                  "lists their series)")
      ->type_name("DIR");
  cmd->add_flag("--force", o->force,
                "replace a folder an earlier sysid compare wrote (one holding .sysid-output)");
  cmd->add_flag("--json", o->json, "print one JSON object with the metrics per recording");
  AddOffFlag(cmd, "--no-plots", o->plots, "skip the PNG plots in the output folder");
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
