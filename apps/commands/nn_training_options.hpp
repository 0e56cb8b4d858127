// Options shared by `sysid train` and `sysid sweep` (one header so both read the same flags).
#ifndef SYSID_APPS_COMMANDS_NN_TRAINING_OPTIONS_HPP_
#define SYSID_APPS_COMMANDS_NN_TRAINING_OPTIONS_HPP_

#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "cli/common.hpp"
#include "cli/field_flag.hpp"
#include "cli/fit_fraction_flag.hpp"
#include "cli/recording_flags.hpp"
#include "sysid/error.hpp"
#include "sysid/nn.hpp"

namespace sysid::cli {

struct NeuralCliOptions {
  std::string train_path, test_path, validation_path, model_path;
  RecordingFlags recording;  ///< --var, --rate, --scale for the training, test, validation files
  std::string inputs = "v";
  std::string output = "u";
  std::string trainer;  // set from `training` (AddNeuralOptions)
  std::string init;     // set from `training` (AddNeuralOptions)
  std::vector<std::string> input_ranges;  ///< NAME=MIN:MAX
  std::string output_range;               ///< MIN:MAX
  bool json = false;
  NeuralTrainingOptions training;
  FitFractionFlag fit_fraction;  ///< of the training file; --test and --validation stay whole
};

inline std::vector<std::string> SplitComma(const std::string& s) {
  std::vector<std::string> out;
  size_t start = 0;
  for (size_t p; (p = s.find(',', start)) != std::string::npos; start = p + 1)
    out.push_back(s.substr(start, p - start));
  out.push_back(s.substr(start));
  return out;
}

inline std::pair<double, double> ParseRangeSpec(const std::string& spec,
                                                const std::string& option) {
  const size_t colon = spec.find(':');
  auto bad = [&] {
    return OptionsError(option + " '" + spec +
                        "': expected MIN:MAX with MIN < MAX (units of "
                        "the column)");
  };
  if (colon == std::string::npos) throw bad();
  try {
    size_t u1 = 0, u2 = 0;
    const std::string a = spec.substr(0, colon), b = spec.substr(colon + 1);
    const double lo = std::stod(a, &u1), hi = std::stod(b, &u2);
    if (u1 != a.size() || u2 != b.size() || !(lo < hi)) throw bad();
    return {lo, hi};
  } catch (const std::logic_error&) {
    throw bad();
  }
}

// The flag names of the trainers and initialisations (library enum <-> CLI text).
inline std::string TrainerFlag(NeuralTrainer t) {
  return t == NeuralTrainer::kCeres ? "ceres" : "lm";
}
inline std::string InitFlag(NeuralInit i) {
  return i == NeuralInit::kUniform ? "uniform" : "nguyen-widrow";
}

// The training set of --train NAMES -> OUTPUT: the file's first --fit-fraction (a note on stderr
// naming `command` and the part left out) or all of it.
inline NeuralDataset ReadTrainingSet(const NeuralCliOptions& o,
                                     const std::vector<std::string>& names,
                                     const std::string& command) {
  if (o.fit_fraction.fraction == 1)
    return ReadNeuralDataset(o.train_path, names, o.output, o.recording.Mapping());
  return MakeNeuralDataset(
      o.fit_fraction.FitPart({ReadRecording(o.train_path, o.recording.Apply({{"t"}, {}}))}, command)
          .front(),
      names, o.output);
}

// The data of one training run: the training set (ReadTrainingSet) and the --test and
// --validation files (whole) when given; all read before training, so a bad file fails fast.
struct NeuralDatasets {
  NeuralDataset train;
  std::unique_ptr<NeuralDataset> test, validation;  ///< null when not given
};

inline NeuralDatasets ReadNeuralDatasets(const NeuralCliOptions& o,
                                         const std::vector<std::string>& names,
                                         const std::string& command) {
  NeuralDatasets d{ReadTrainingSet(o, names, command), nullptr, nullptr};
  if (!o.test_path.empty())
    d.test = std::make_unique<NeuralDataset>(
        ReadNeuralDataset(o.test_path, names, o.output, o.recording.Mapping()));
  if (!o.validation_path.empty())
    d.validation = std::make_unique<NeuralDataset>(
        ReadNeuralDataset(o.validation_path, names, o.output, o.recording.Mapping()));
  return d;
}

// The unit of a mean squared error of the column `output` ("V^2"; "(unit)^2" when the column
// has no known unit), for progress lines.
inline std::string MseUnit(const std::string& output) {
  return DefaultUnit(output).empty() ? "(unit)^2" : DefaultUnit(output) + "^2";
}

inline void AddNeuralOptions(CLI::App* cmd, NeuralCliOptions& o) {
  o.trainer = TrainerFlag(o.training.trainer);
  o.init = InitFlag(o.training.init);
  o.recording.Add(cmd);
  o.fit_fraction.Add(cmd);
  cmd->add_option("--train", o.train_path,
                  "training CSV with the input and output columns (t [s] optional)")
      ->required()
      ->type_name("FILE.csv");
  cmd->add_option("--test", o.test_path, "test CSV (same columns); reported, never trained on")
      ->type_name("FILE.csv");
  cmd->add_option("--validation", o.validation_path,
                  "validation CSV for early stopping (6 consecutive rises, trainlm's rule)")
      ->type_name("FILE.csv");
  cmd->add_option("--inputs", o.inputs,
                  "comma-separated input columns, e.g. v or v,a [SI units: v m/s, a m/s^2]")
      ->capture_default_str();
  cmd->add_option("--output", o.output, "output (target) column [SI unit, u in V]")
      ->capture_default_str();
  // --trainer, --init, --input-range and --output-range are text, parsed into their fields by
  // ResolveNeuralOptions.
  NeuralTrainingOptions& t = o.training;
  BindField(cmd,
            cmd->add_option("--trainer", o.trainer,
                            "lm (the paper's LM with momentum, trainlm mu schedule) or ceres "
                            "(Ceres LM reference)")
                ->check(CLI::IsMember({"lm", "ceres"}))
                ->capture_default_str(),
            t, t.trainer);
  AddFieldOption(cmd, "--momentum", t, t.momentum,
                 "momentum alpha in [0, 1) [dimensionless]; 0 = plain trainlm");
  BindField(cmd, AddSeedOption(cmd, t.seed, "initialisation seed; restart r uses seed + r"), t,
            t.seed);
  AddFieldOption(cmd, "--restarts", t, t.restarts,
                 "random initialisations, best kept (by validation MSE, else training MSE)");
  AddFieldOption(cmd, "--max-epochs", t, t.max_epochs, "epoch limit");
  AddFieldOption(cmd, "--goal-mse", t, t.goal_mse,
                 "stop when training MSE <= this [output unit^2, V^2]");
  AddFieldOption(cmd, "--min-gradient", t, t.gradient_tolerance,
                 "stop when ||2 J'e/N|| < this [normalised units]");
  BindField(cmd,
            cmd->add_option("--init", o.init, "nguyen-widrow or uniform")
                ->check(CLI::IsMember({"nguyen-widrow", "uniform"}))
                ->capture_default_str(),
            t, t.init);
  AddFieldFlag(cmd, "--solve-output-layer", t, t.solve_output_layer,
               "lm only: after each trial step set the linear output layer to its least-squares "
               "optimum (much faster convergence; off = the paper's rule exactly)");
  BindField(cmd,
            cmd->add_option("--input-range", o.input_ranges,
                            "fixed mapminmax range NAME=MIN:MAX of an input [its SI unit], e.g. "
                            "v=-0.1:0.1; default: the training data's min/max")
                ->type_name("NAME=MIN:MAX"),
            t, t.input_ranges);
  BindField(cmd,
            cmd->add_option("--output-range", o.output_range,
                            "fixed mapminmax range MIN:MAX of the output [V]; -1:1 leaves it "
                            "unscaled; default: the training targets' min/max")
                ->type_name("MIN:MAX"),
            t, t.output_range);
  cmd->add_flag("--json", o.json, "print one JSON object to stdout");
}

// Per-epoch progress of `train` on stderr (a terminal or --progress): the first epoch, then at
// most five lines a second, so that fast epochs do not flood a log.
// `mse_unit` is the output's unit squared, e.g. "V^2".
inline void AttachEpochProgress(NeuralTrainingOptions& t, size_t inputs, const std::string& mse_unit) {
  if (!ProgressEnabled()) return;
  auto last = std::make_shared<std::chrono::steady_clock::time_point>();
  const int hidden = t.hidden, max_epochs = t.max_epochs, restarts = t.restarts;
  t.on_epoch = [=](const EpochRecord& e) {
    const auto now = std::chrono::steady_clock::now();
    if (e.epoch > 1 && e.epoch < max_epochs && now - *last < std::chrono::milliseconds(200))
      return;
    *last = now;
    std::string line = fmt::format("training {}-{}-1: epoch {}/{}", inputs, hidden, e.epoch,
                                   max_epochs);
    if (restarts > 1) line += fmt::format(" (restart {}/{})", e.restart + 1, restarts);
    line += fmt::format(", training MSE {:.4g} {}", e.train_mse, mse_unit);
    Progress(line);
  };
}

// Turns the flags into library options (input names, ranges, trainer).
inline void ResolveNeuralOptions(NeuralCliOptions& o) {
  auto names = SplitComma(o.inputs);
  for (const auto& n : names)
    if (n.empty()) throw OptionsError("--inputs '" + o.inputs + "': empty column name");
  NeuralTrainingOptions& t = o.training;
  t.trainer = o.trainer == "ceres" ? NeuralTrainer::kCeres : NeuralTrainer::kLevenbergMarquardt;
  t.init = o.init == "uniform" ? NeuralInit::kUniform : NeuralInit::kNguyenWidrow;
  if (!o.input_ranges.empty()) {
    t.input_ranges.assign(names.size(), {0.0, 0.0});
    std::vector<bool> given(names.size(), false);
    for (const auto& spec : o.input_ranges) {
      const size_t eq = spec.find('=');
      const std::string name = eq == std::string::npos ? "" : spec.substr(0, eq);
      size_t k = 0;
      while (k < names.size() && names[k] != name) ++k;
      if (k == names.size())
        throw OptionsError("--input-range '" + spec +
                           "': expected NAME=MIN:MAX with NAME one "
                           "of --inputs (" +
                           o.inputs + ")");
      t.input_ranges[k] = ParseRangeSpec(spec.substr(eq + 1), "--input-range");
      given[k] = true;
    }
    for (size_t k = 0; k < names.size(); ++k)
      if (!given[k])
        throw OptionsError("--input-range: no range for input '" + names[k] +
                           "' (give one for every input, or none)");
  }
  if (!o.output_range.empty()) t.output_range = ParseRangeSpec(o.output_range, "--output-range");
  t.Validate();
}

}  // namespace sysid::cli

#endif  // SYSID_APPS_COMMANDS_NN_TRAINING_OPTIONS_HPP_
