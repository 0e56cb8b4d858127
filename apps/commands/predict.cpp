// sysid predict --nn NN.json DATA.csv [-o OUT.csv] [--column NAME] [--json]
#include <fmt/format.h>

#include <cmath>
#include <iostream>
#include <memory>
#include <string>

#include "cli/common.hpp"
#include "cli/output_file.hpp"
#include "cli/recording_flags.hpp"
#include "cli/registry.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"
#include "sysid/io_containers.hpp"
#include "sysid/nn.hpp"

namespace sysid::cli {
namespace {

struct PredictOptions {
  std::string nn_path, data_path, out_path, column;
  bool json = false;
  RecordingFlags recording;
};

void RunPredict(const PredictOptions& o) {
  const NeuralNetwork net = ReadNeuralNetwork(o.nn_path);
  ReadOptions ro = o.recording.Apply({});
  ro.required_columns = net.input_names();
  ro.any_of_columns = {};
  Recording rec = ReadRecording(o.data_path, ro);
  NetworkPrediction p;
  try {
    p = PredictColumn(net, rec, o.column);
  } catch (const OptionsError& e) {
    throw OptionsError("--column: " + std::string(e.what()) + " with --column", "--column");
  }
  rec.metadata.push_back({"predicted_by", o.nn_path});
  if (!o.out_path.empty()) WriteRecordingByExtension(o.out_path, rec);
  // The library's summary with the command's files in front.
  nlohmann::ordered_json j;
  j["nn"] = o.nn_path;
  j["data"] = o.data_path;
  j.update(nlohmann::ordered_json::parse(ToJson(p)));
  if (o.json) {
    PrintJson(j);
    return;
  }
  if (o.out_path.empty()) {
    std::cout << FormatRecording(rec);
    return;
  }
  std::cout << fmt::format("wrote {} ({} rows, column '{}')\n", o.out_path, p.rows, p.column);
  if (!std::isnan(p.mse))
    std::cout << fmt::format("MSE against '{}': {:.6g}\n", net.output().name, p.mse);
  if (p.rows_outside_input_range > 0)
    std::cout << fmt::format(
        "warning: {} rows have inputs outside the network's input range "
        "(extrapolation)\n",
        p.rows_outside_input_range);
}

void AddPredictCommand(CLI::App& app) {
  auto o = std::make_shared<PredictOptions>();
  CLI::App* cmd = app.add_subcommand(
      "predict",
      "Evaluate a neural inverse model on a CSV: adds the predicted output column "
      "(e.g. u_nn [V]) and reports the MSE when the true output column is present");
  cmd->add_option("--nn", o->nn_path, "network model file (JSON from sysid train/sweep)")
      ->required()
      ->type_name("NN.json");
  cmd->add_option("data", o->data_path,
                  "CSV with the network's input columns (SI units, e.g. v [m/s]); t optional")
      ->required()
      ->type_name("DATA.csv");
  cmd->add_option("-o", o->out_path,
                  "output CSV (MAT v5 when it ends in .mat): the input file's columns plus the "
                  "prediction (atomic); default: CSV to stdout")
      ->type_name("OUT.csv");
  GuardOutputFiles(cmd, {{&o->out_path, "-o"}});
  cmd->add_option("--column", o->column, "name of the prediction column; default <output>_nn");
  cmd->add_flag("--json", o->json, "print a JSON summary (rows, mse, column) to stdout");
  o->recording.Add(cmd);
  cmd->callback([o] { RunPredict(*o); });
}

const bool kRegistered = RegisterCommand(62, &AddPredictCommand);

}  // namespace
}  // namespace sysid::cli
