// sysid sweep --train A.csv --test B.csv --hidden 16:32:2 [training flags] [-o BEST.json]
#include <fmt/format.h>

#include <cmath>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "cli/common.hpp"
#include "cli/field_flag.hpp"
#include "cli/output_file.hpp"
#include "cli/registry.hpp"
#include "commands/nn_training_options.hpp"
#include "sysid/nn.hpp"

namespace sysid::cli {
namespace {

struct SweepCliOptions {
  NeuralCliOptions nn;
  HiddenSweepOptions sweep;  // the flags' defaults are the library's; training comes from nn
  std::string hidden;        // set from sweep.hidden_sizes
};

void RunSweep(SweepCliOptions& o) {
  HiddenSweepOptions so = o.sweep;
  so.hidden_sizes = ParseHiddenSizes(o.hidden);
  ResolveNeuralOptions(o.nn);
  so.training = o.nn.training;
  const auto names = SplitComma(o.nn.inputs);
  const NeuralDatasets data = ReadNeuralDatasets(o.nn, names, "sweep");
  if (ProgressEnabled()) {
    Progress(fmt::format("training {} networks ...", so.hidden_sizes.size()));
    const std::string unit = MseUnit(o.nn.output);
    so.on_network = [unit](const HiddenSweepRow& row, size_t done, size_t total) {
      Progress(fmt::format("trained {}/{} networks (last: H = {}, {} epochs, training MSE {:.4g} {})",
                           done, total, row.hidden, row.epochs, row.train_mse, unit));
    };
  }
  const HiddenSweepResult r =
      SweepHiddenSize(data.train, data.validation.get(), data.test.get(), so);
  ProgressDone();
  const auto& best = r.rows[r.chosen];

  nlohmann::ordered_json j;
  j["inputs"] = names;
  j["output"] = o.nn.output;
  j.update(nlohmann::ordered_json::parse(ToJson(r, so)));
  for (const auto& w : r.warnings) std::cerr << "sysid sweep: warning: " << w << '\n';
  if (!o.nn.model_path.empty()) {
    nlohmann::ordered_json summary = j["rows"][r.chosen];
    summary.erase("wall_time_s");  // the model file is reproducible: same seed, same bytes
    summary["rule"] = r.rule;
    summary["trainer"] = j["trainer"];
    summary["train_file"] = o.nn.train_path;
    WriteNeuralNetwork(o.nn.model_path, r.runs[r.chosen].network, summary.dump());
  }
  if (o.nn.json) {
    PrintJson(j);
    return;
  }
  Table t({"hidden", "epochs", "train MSE", "validation MSE", "test MSE", "stop"});
  for (const auto& row : r.rows)
    t.AddRow({std::to_string(row.hidden), std::to_string(row.epochs), Num(row.train_mse),
              std::isfinite(row.validation_mse) ? Num(row.validation_mse) : "-",
              std::isfinite(row.test_mse) ? Num(row.test_mse) : "-", ToString(row.stop)});
  std::cout << t.Render();
  std::cout << fmt::format("chosen H = {} ({}), {:.3g} s\n", best.hidden, r.rule, r.wall_time_s);
  if (!o.nn.model_path.empty()) std::cout << "wrote " << o.nn.model_path << '\n';
}

void AddSweepCommand(CLI::App& app) {
  auto o = std::make_shared<SweepCliOptions>();
  CLI::App* cmd = app.add_subcommand(
      "sweep",
      "Train one network per hidden size (in parallel) and tabulate epochs, training "
      "and test MSE [output unit^2], as the paper's Table; picks H by min validation "
      "MSE, else min test MSE");
  AddNeuralOptions(cmd, o->nn);
  HiddenSweepOptions& so = o->sweep;
  o->hidden = FormatHiddenSizes(so.hidden_sizes);
  // Parsed into hidden_sizes when the command runs.
  BindField(cmd,
            cmd->add_option("--hidden", o->hidden,
                            "hidden sizes FIRST:LAST:STEP or a list H1,H2,...")
                ->capture_default_str(),
            so, so.hidden_sizes);
  BindField(cmd, AddThreadsOption(cmd, so.threads, "worker threads; 0 = all cores"), so,
            so.threads);
  cmd->add_option("-o", o->nn.model_path, "the chosen network's model file (JSON, atomic)")
      ->type_name("NN.json");
  GuardOutputFiles(cmd, {{&o->nn.model_path, "-o"}});
  cmd->callback([o] { RunSweep(*o); });
}

const bool kRegistered = RegisterCommand(61, &AddSweepCommand);

}  // namespace
}  // namespace sysid::cli
