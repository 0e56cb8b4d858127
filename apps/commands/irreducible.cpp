// sysid irreducible DATA.csv... [--inputs v] [--inputs v,a] [--output u] [--neighbours K]
// [--json]: the least MSE any model of the output on each input set can reach on each recording,
// estimated from the data alone (libsysid: EstimateIrreducibleError in sysid/nn_irreducible.hpp).
#include <fmt/format.h>

#include <algorithm>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "cli/common.hpp"
#include "cli/recording_flags.hpp"
#include "cli/registry.hpp"
#include "commands/nn_training_options.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"
#include "sysid/nn.hpp"
#include "sysid/nn_irreducible.hpp"

namespace sysid::cli {
namespace {

constexpr size_t kMaxInputSets = 16;

struct IrreducibleCli {
  std::vector<std::string> paths;
  std::vector<std::string> input_sets;  // "v", "v,a", ...
  std::string output = "u";
  IrreducibleErrorOptions options;
  bool json = false;
  RecordingFlags recording;
};

// "v,a" -> {"v", "a"}, as train's --inputs (SplitComma), with the same empty-name rule.
std::vector<std::string> SplitInputs(const std::string& text) {
  std::vector<std::string> names = SplitComma(text);
  for (const auto& n : names)
    if (n.empty()) throw OptionsError("--inputs '" + text + "': empty column name", "--inputs");
  return names;
}

void RunIrreducible(const IrreducibleCli& o) {
  std::vector<std::string> sets = o.input_sets;
  if (sets.empty()) sets = {"v", "v,a"};
  if (sets.size() > kMaxInputSets)
    throw OptionsError(fmt::format("--inputs given {} times; at most {}", sets.size(),
                                   kMaxInputSets),
                       "--inputs");
  // Every set's columns, checked before any file is read; each file is then read once.
  std::vector<std::vector<std::string>> inputs;
  ReadOptions ro = o.recording.Apply({});
  ro.required_columns = {o.output};
  ro.any_of_columns = {};
  for (const auto& set : sets) {
    inputs.push_back(SplitInputs(set));
    for (const auto& name : inputs.back())
      if (std::find(ro.required_columns.begin(), ro.required_columns.end(), name) ==
          ro.required_columns.end())
        ro.required_columns.push_back(name);
  }
  std::vector<IrreducibleError> rows;
  std::vector<std::string> files;
  for (const auto& path : o.paths) {
    const Recording rec = ReadRecording(path, ro);
    for (size_t i = 0; i < sets.size(); ++i) {
      Progress(fmt::format("irreducible error: {} given {}", path, sets[i]));
      rows.push_back(
          EstimateIrreducibleError(MakeNeuralDataset(rec, inputs[i], o.output), o.options));
      files.push_back(path);
    }
  }
  if (o.json) {
    nlohmann::json j = nlohmann::json::array();
    for (size_t i = 0; i < rows.size(); ++i)
      j.push_back({{"file", files[i]},
                   {"inputs", rows[i].input_names},
                   {"output", rows[i].output_name},
                   {"rows", rows[i].rows},
                   {"neighbours", rows[i].neighbours},
                   {"output_variance", rows[i].output_variance},
                   {"irreducible_mse", rows[i].mse},
                   {"unexplained_share", rows[i].unexplained_share()}});
    PrintJson({{"unit", "output unit squared (V^2 for u)"}, {"rows", j}});
    return;
  }
  Table table({"file", "inputs", "rows", "Var(output)", "irreducible MSE", "unexplained [%]"});
  for (size_t i = 0; i < rows.size(); ++i) {
    std::string inputs;
    for (const auto& n : rows[i].input_names) inputs += (inputs.empty() ? "" : ",") + n;
    table.AddRow({files[i], inputs, std::to_string(rows[i].rows), Num(rows[i].output_variance, 4),
                  Num(rows[i].mse, 4), Num(100 * rows[i].unexplained_share(), 3)});
  }
  std::cout << table.Render()
            << fmt::format(
                   "\nMSE in the output's unit squared (V^2 for u): the mean over rows of the "
                   "output's variance among each row's {} nearest neighbours in the standardised "
                   "inputs. No model of '{}' on those inputs can do better on that data.\n",
                   o.options.neighbours, o.output);
}

void AddIrreducibleCommand(CLI::App& app) {
  auto o = std::make_shared<IrreducibleCli>();
  CLI::App* cmd = app.add_subcommand(
      "irreducible",
      "The least MSE any inverse model on the given inputs can reach on each recording "
      "(e.g. u from v, or from v and a), estimated from the data alone: the output's variance "
      "among each row's k nearest neighbours in the inputs, averaged. Tells 'the network did "
      "not learn it' from 'these inputs do not determine it' [output unit^2, V^2 for u]");
  cmd->add_option("data", o->paths, "recordings with the input and output columns (SI units)")
      ->required()
      ->type_name("DATA.csv ...");
  cmd->add_option("--inputs", o->input_sets,
                  "an input set, comma-separated columns (repeatable); default: v and v,a")
      ->type_name("COLS");
  cmd->add_option("--output", o->output, "output column [SI unit]")->capture_default_str();
  cmd->add_option("--neighbours", o->options.neighbours,
                  "rows per neighbourhood k, the row itself included (small k: less bias where "
                  "the output varies fast, more variance)")
      ->check(CLI::Range(2, 1000))
      ->capture_default_str();
  AddSeedOption(cmd, o->options.seed, "seed of the tie-breaking perturbation");
  cmd->add_flag("--json", o->json,
                "print {\"unit\", \"rows\": [{\"file\", \"inputs\", \"output\", \"rows\", "
                "\"neighbours\", \"output_variance\", \"irreducible_mse\", "
                "\"unexplained_share\"}]}");
  o->recording.Add(cmd);
  cmd->callback([o] { RunIrreducible(*o); });
}

const bool kRegistered = RegisterCommand(63, &AddIrreducibleCommand);

}  // namespace
}  // namespace sysid::cli
