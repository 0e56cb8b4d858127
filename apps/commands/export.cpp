// sysid export --model M.json --dt S | --nn NN.json | --hysteresis H.json --dt S
//              [--precision double|float] [--prefix NAME] [--vectors REC.csv] -o DIR [--force]:
// an inverse model as allocation-free C99 with test vectors and a check program
// (libsysid: sysid/deploy.hpp; docs/deploy.md).
#include <fmt/format.h>

#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

#include "cli/common.hpp"
#include "cli/output_folder.hpp"
#include "cli/registry.hpp"
#include "sysid/compare_hysteresis.hpp"
#include "sysid/deploy.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"

namespace sysid::cli {
namespace {

namespace fs = std::filesystem;

struct ExportCli {
  std::string model_path, nn_path, hysteresis_path, vectors_path, out_dir;
  double dt_s = 0;
  std::string precision = "double";
  ExportOptions options;
  bool force = false;
};

// The vectors' columns by the step's input names (pi also takes a recording's "x").
ExportVectors ReadVectors(const std::string& path, const std::vector<std::string>& names) {
  ReadOptions read;
  read.required_columns = names;  // the reader names the first one missing
  if (read.required_columns.front() == "x_ref") read.required_columns.clear();
  read.any_of_columns = names.front() == "x_ref" ? std::vector<std::string>{"x_ref", "x"}
                                                 : std::vector<std::string>{};
  const Recording rec = ReadRecording(path, read);
  ExportVectors v;
  v.source = path;
  v.inputs.resize(rec.rows(), static_cast<Eigen::Index>(names.size()));
  for (size_t i = 0; i < names.size(); ++i) {
    const std::string& name = names[i] == "x_ref" && !rec.has("x_ref") ? "x" : names[i];
    v.inputs.col(static_cast<Eigen::Index>(i)) = rec.column(name);  // InputError names it
  }
  return v;
}

void RunExport(const ExportCli& o) {
  const int given = !o.model_path.empty() + !o.nn_path.empty() + !o.hysteresis_path.empty();
  if (given != 1)
    throw OptionsError("exactly one of --model, --nn, --hysteresis is needed", "model");
  ExportOptions options = o.options;
  options.precision = ExportPrecisionFromString(o.precision);
  options.Validate();
  const std::string& path = !o.model_path.empty() ? o.model_path
                            : !o.nn_path.empty()  ? o.nn_path
                                                  : o.hysteresis_path;
  if (o.nn_path.empty() && !(o.dt_s > 0))
    throw OptionsError("--dt: the sample time [s] is needed for this model", "dt_s");
  std::vector<std::string> inputs{path};
  if (!o.vectors_path.empty()) inputs.push_back(o.vectors_path);
  const OutputFolder folder(o.out_dir, o.force, inputs, "export");
  const ExportProvenance provenance{path, Sha256Hex(ReadFile(path))};
  ExportResult r;
  if (!o.model_path.empty()) {
    const FrictionModel m = ReadModel(path);
    const ExportVectors v = o.vectors_path.empty() ? DefaultFrictionVectors(o.dt_s)
                                                   : ReadVectors(o.vectors_path, {"v", "a"});
    r = ExportFrictionInverse(m, o.dt_s, v, options, provenance);
  } else if (!o.nn_path.empty()) {
    const NeuralNetwork net = ReadNeuralNetwork(path);
    const ExportVectors v = o.vectors_path.empty() ? DefaultNetworkVectors(net)
                                                   : ReadVectors(o.vectors_path, net.input_names());
    r = ExportNetworkInverse(net, v, options, provenance);
  } else {
    const auto h = ReadHysteresisModel(path);
    const auto* pi = dynamic_cast<const PrandtlIshlinskiiModel*>(h.get());
    const auto* ops = dynamic_cast<const OperatorNetworkModel*>(h.get());
    const auto* bw = dynamic_cast<const PiezoBoucWen*>(h.get());
    if (bw != nullptr) {
      const ExportVectors v = o.vectors_path.empty() ? DefaultBoucWenVectors(*bw)
                                                     : ReadVectors(o.vectors_path, {"x_ref"});
      r = ExportBoucWenInverse(*bw, v, options, provenance);
    } else if (ops != nullptr) {
      const ExportVectors v = o.vectors_path.empty() ? DefaultOperatorNetworkVectors(*ops)
                                                     : ReadVectors(o.vectors_path, {"x_ref"});
      r = ExportOperatorNetworkInverse(*ops, v, options, provenance);
    } else if (pi == nullptr) {
      throw OptionsError(path + ": a " + h->kind() + " model; this version exports the "
                         "PI family's (pi, gpi, rdpi), the operator-input network's and the "
                         "piezo Bouc-Wen's inverses of the hysteresis models only",
                         "hysteresis");
    } else {
      const ExportVectors v = o.vectors_path.empty() ? DefaultPiVectors(*pi, o.dt_s)
                                                     : ReadVectors(o.vectors_path, {"x_ref"});
      r = ExportPiInverse(*pi, o.dt_s, v, options, provenance);
    }
  }
  const std::string& p = options.prefix;
  folder.Write([&](const fs::path& dir) { WriteExportFiles(r, p, dir.string()); });
  std::cout << fmt::format("{}: {} inverse, {} in {}, {} vectors, bound {:.3g} V\n",
                           folder.path().string(), r.kind, options.precision ==
                           ExportPrecision::kDouble ? "double" : "float", p + ".c",
                           r.u_expected_v.size(), r.bound_v);
}

void AddExportCommand(CLI::App& app) {
  auto o = std::make_shared<ExportCli>();
  CLI::App* cmd = app.add_subcommand(
      "export",
      "An inverse model as allocation-free C99 for a real-time target: NAME.h, NAME.c "
      "(NAME_init, NAME_step), NAME_vectors.csv (the library stepper's outputs), NAME_check.c "
      "and NAME_README.md (docs/deploy.md)");
  cmd->add_option("--model", o->model_path, "friction model JSON: the analytic inverse")
      ->check(CLI::ExistingFile)
      ->type_name("M.json");
  cmd->add_option("--nn", o->nn_path, "tanh network JSON")
      ->check(CLI::ExistingFile)
      ->type_name("NN.json");
  cmd->add_option("--hysteresis", o->hysteresis_path, "hysteresis model JSON (kind pi, gpi, rdpi, nn-operators, bouc-wen-piezo)")
      ->check(CLI::ExistingFile)
      ->type_name("H.json");
  cmd->add_option("--dt", o->dt_s, "sample time of the exported step [s] (--model, --hysteresis)")
      ->check(FiniteRange(1e-9, 1e3));
  cmd->add_option("--precision", o->precision, "arithmetic of the generated C")
      ->check(CLI::IsMember({"double", "float"}))
      ->capture_default_str();
  cmd->add_option("--prefix", o->options.prefix, "C identifier naming the files and symbols")
      ->capture_default_str();
  cmd->add_option("--vectors", o->vectors_path,
                  "recording whose input columns (v, a; the network's inputs; x_ref or x) "
                  "replace the default test waveform")
      ->check(CLI::ExistingFile)
      ->type_name("REC.csv");
  cmd->add_option("-o", o->out_dir, "output folder (written whole, docs/robustness.md)")
      ->required()
      ->type_name("DIR");
  cmd->add_flag("--force", o->force, "replace a folder sysid wrote before");
  cmd->callback([o] { RunExport(*o); });
}

const bool kRegistered = RegisterCommand(95, &AddExportCommand);

}  // namespace
}  // namespace sysid::cli
