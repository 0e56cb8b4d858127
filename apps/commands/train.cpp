// sysid train --train A.csv [--test B.csv] --inputs v[,a] --output u --hidden H
//             [--trainer lm|ceres] [--momentum a] [--seed N] -o NN.json [--json]
#include <fmt/format.h>

#include <cmath>
#include <iostream>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "cli/common.hpp"
#include "cli/field_flag.hpp"
#include "cli/output_file.hpp"
#include "cli/registry.hpp"
#include "commands/nn_training_options.hpp"
#include "sysid/io.hpp"
#include "sysid/nn.hpp"

namespace sysid::cli {
namespace {

struct TrainCliOptions {
  NeuralCliOptions nn;
  bool history = false;
};

void RunTrain(TrainCliOptions& o) {
  ResolveNeuralOptions(o.nn);
  const auto names = SplitComma(o.nn.inputs);
  // Read everything before training so bad files fail fast.
  const NeuralDatasets data = ReadNeuralDatasets(o.nn, names, "train");
  const NeuralDataset* test = data.test.get();
  if (ProgressEnabled())
    Progress(fmt::format("training {}-{}-1 ...", names.size(), o.nn.training.hidden));
  AttachEpochProgress(o.nn.training, names.size(), MseUnit(o.nn.output));
  const NeuralTrainingResult r =
      TrainNeuralNetwork(data.train, data.validation.get(), o.nn.training);
  ProgressDone();
  const double test_mse =
      test ? MeanSquaredError(r.network, *test) : std::numeric_limits<double>::quiet_NaN();

  // The library's report with the command's context: data, output unit, test MSE, files.
  nlohmann::ordered_json j;
  j["inputs"] = names;
  j["output"] = o.nn.output;
  j.update(nlohmann::ordered_json::parse(ToJson(r, o.nn.training)));
  j["test_mse"] = test ? nlohmann::ordered_json(test_mse) : nlohmann::ordered_json(nullptr);
  j["mse_unit"] =
      "(" + (DefaultUnit(o.nn.output).empty() ? std::string("unit") : DefaultUnit(o.nn.output)) +
      ")^2";
  j["train_file"] = o.nn.train_path;
  if (test) j["test_file"] = o.nn.test_path;
  if (!o.history) j.erase("history");
  for (const auto& w : r.warnings) std::cerr << "sysid train: warning: " << w << '\n';
  if (!o.nn.model_path.empty()) {
    nlohmann::ordered_json summary = j;
    summary.erase("history");
    summary.erase("wall_time_s");  // the model file is reproducible: same seed, same bytes
    summary.erase("warnings");
    WriteNeuralNetwork(o.nn.model_path, r.network, summary.dump());
  }
  if (!IsSolutionUsable(r.termination))
    std::cerr << "sysid: warning: training stopped on a numerical failure (" << r.message
              << "); the best finite weights were kept\n";
  if (o.nn.json) {
    PrintJson(j);
    return;
  }
  std::cout << fmt::format("network     {}-{}-1 tanh ({} parameters), inputs {}, output {}\n",
                           names.size(), o.nn.training.hidden, r.network.parameter_count(),
                           o.nn.inputs, o.nn.output);
  std::cout << fmt::format("trainer     {} (momentum {}), {} epochs, stop: {} ({})\n",
                           ToString(o.nn.training.trainer), o.nn.training.momentum, r.epochs,
                           ToString(r.stop), r.message);
  Table t({"set", "MSE"});
  t.AddRow({"training", Num(r.train_mse)});
  if (data.validation) t.AddRow({"validation", Num(r.validation_mse)});
  if (test) t.AddRow({"test", Num(test_mse)});
  std::cout << t.Render();
  if (!o.nn.model_path.empty()) std::cout << "wrote " << o.nn.model_path << '\n';
}

void AddTrainCommand(CLI::App& app) {
  auto o = std::make_shared<TrainCliOptions>();
  CLI::App* cmd =
      app.add_subcommand("train",
                         "Train a neural inverse model (inputs -> H tanh units -> output) by "
                         "Levenberg-Marquardt; MSE in the output's unit squared (V^2)");
  AddNeuralOptions(cmd, o->nn);
  NeuralTrainingOptions& t = o->nn.training;
  AddFieldOption(cmd, "--hidden", t, t.hidden, "hidden tanh units H")
      ->check(CLI::Range(1, kMaxHiddenUnits));
  BindField(cmd,
            AddThreadsOption(cmd, t.threads,
                             "threads for each epoch (lm trainer); 0 = all cores; results do "
                             "not depend on it"),
            t, t.threads);
  cmd->add_option("-o", o->nn.model_path, "network model file (JSON, written atomically)")
      ->type_name("NN.json");
  GuardOutputFiles(cmd, {{&o->nn.model_path, "-o"}});
  cmd->add_flag("--history", o->history, "with --json: include every epoch (mu, MSEs)");
  cmd->callback([o] { RunTrain(*o); });
}

const bool kRegistered = RegisterCommand(60, &AddTrainCommand);

}  // namespace
}  // namespace sysid::cli
