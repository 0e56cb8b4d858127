// sysid irreducible DATA.csv... [--inputs v] [--inputs v,a] [--output u] [--neighbours K]
// [--json]: the least MSE any model of the output on each input set can reach on each recording,
// estimated from the data alone (libsysid: EstimateIrreducibleError in sysid/nn_irreducible.hpp).
#include <fmt/format.h>
#include <fmt/ranges.h>

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
  // The true floor of a set cannot exceed a subset's (a function of fewer inputs is a function
  // of more); an estimate can, through its upward bias. Such an estimate is not printed as the
  // set's floor: the subset's (lower) estimate bounds it better.
  std::vector<std::string> exceeds(rows.size());
  for (size_t i = 0; i < rows.size(); ++i)
    for (size_t j = 0; j < rows.size(); ++j) {
      if (i == j || files[i] != files[j] || rows[j].mse >= rows[i].mse) continue;
      const auto& sub = rows[j].input_names;
      const auto& set = rows[i].input_names;
      const bool subset =
          sub.size() < set.size() && std::all_of(sub.begin(), sub.end(), [&](const std::string& n) {
            return std::find(set.begin(), set.end(), n) != set.end();
          });
      if (subset && (exceeds[i].empty() || rows[j].mse < rows[i].mse))
        exceeds[i] = fmt::format("{}", fmt::join(sub, ","));
    }
  if (o.json) {
    nlohmann::json j = nlohmann::json::array();
    for (size_t i = 0; i < rows.size(); ++i) {
      nlohmann::json row = nlohmann::json::parse(ToJson(rows[i], -1));
      row["file"] = files[i];
      row["estimate_above_subset"] =
          exceeds[i].empty() ? nlohmann::json(nullptr) : nlohmann::json(exceeds[i]);
      j.push_back(row);
    }
    PrintJson({{"unit", "output unit squared (V^2 for u)"},
               {"bias",
                "upward: the estimate may exceed the floor, never the reverse in "
                "expectation"},
               {"rows", j}});
    return;
  }
  Table table({"file", "inputs", "rows", "Var(output)", "MSE floor estimate", "95% interval",
               "unexplained [%]", "note"});
  bool any_exceeds = false;
  for (size_t i = 0; i < rows.size(); ++i) {
    any_exceeds = any_exceeds || !exceeds[i].empty();
    table.AddRow({files[i], fmt::format("{}", fmt::join(rows[i].input_names, ",")),
                  std::to_string(rows[i].rows), Num(rows[i].output_variance, 4),
                  Num(rows[i].mse, 4), Num(rows[i].mse_low, 4) + " .. " + Num(rows[i].mse_high, 4),
                  Num(100 * rows[i].unexplained_share(), 3),
                  exceeds[i].empty() ? "" : "above " + exceeds[i] + "'s: bias"});
  }
  std::cout
      << table.Render()
      << fmt::format(
             "\nAn estimate, in the output's unit squared (V^2 for u), of the least MSE a "
             "model of '{}' on those inputs can reach on that data: the mean over rows of "
             "the output's variance among each row's {} nearest neighbours in the "
             "standardised inputs. It is biased upward (the function's spread within a "
             "neighbourhood adds to it, more so with more inputs); the 95 % interval is its spread "
             "(delete-a-group jackknife), not its bias.\n",
             o.output, o.options.neighbours);
  if (any_exceeds)
    std::cout << "A set whose estimate is above a subset's ('above ...: bias') has a floor no "
                 "higher than the subset's: the true floor cannot grow with an input, so the "
                 "difference is the estimate's bias, not information lost.\n";
}

void AddIrreducibleCommand(CLI::App& app) {
  auto o = std::make_shared<IrreducibleCli>();
  o->options.jackknife_groups = 20;
  CLI::App* cmd = app.add_subcommand(
      "irreducible",
      "An estimate of the least MSE any inverse model on the given inputs can reach on each "
      "recording (e.g. u from v, or from v and a), from the data alone: the output's variance "
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
  cmd->add_option("--jackknife-groups", o->options.jackknife_groups,
                  "contiguous row groups of the delete-a-group jackknife behind the 95 % "
                  "interval (0: no interval; 5..100)")
      ->check(CLI::Range(0, 100))
      ->capture_default_str();
  AddSeedOption(cmd, o->options.seed, "seed of the tie-breaking perturbation");
  cmd->add_flag(
      "--json", o->json,
      "print {\"unit\", \"rows\": [{\"file\", \"inputs\", \"output\", \"rows\", "
      "\"neighbours\", \"output_variance\", \"irreducible_mse_estimate\", \"interval95\", "
      "\"unexplained_share\", \"estimate_above_subset\"}]}");
  o->recording.Add(cmd);
  cmd->callback([o] { RunIrreducible(*o); });
}

const bool kRegistered = RegisterCommand(63, &AddIrreducibleCommand);

}  // namespace
}  // namespace sysid::cli
