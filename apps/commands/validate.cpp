// sysid validate (--model M.json | --hysteresis H.json) [--lags L] [--json] [-o DIR] REC...
// The model simulated free-run from each recording's u and scored as MATLAB's compare and resid
// do: fit %, RMSE, nrmse_std, nrmse_range, residual autocorrelation and cross-correlation with u.
#include "sysid/validate.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "cli/common.hpp"
#include "cli/motion_flags.hpp"
#include "cli/output_folder.hpp"
#include "cli/registry.hpp"
#include "sysid/compare_hysteresis.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"
#include "sysid/report.hpp"

namespace sysid::cli {
namespace {

struct ValidateCliOptions {
  std::string model_path, hysteresis_path;
  std::vector<std::string> files;
  std::string out_dir;
  bool force = false, json = false, plots = true;
  ValidationOptions validation;
  MotionFlags motion;
};

void RunValidate(ValidateCliOptions o) {
  namespace fs = std::filesystem;
  if (o.model_path.empty() == o.hysteresis_path.empty())
    throw OptionsError("give exactly one model: --model M.json or --hysteresis H.json");
  try {
    o.validation.Validate();
  } catch (const OptionsError& e) {
    RethrowWithFlag(e, {{"max_lag", "--lags"}});
  }
  std::vector<std::string> inputs = o.files;
  inputs.insert(inputs.end(), {o.model_path, o.hysteresis_path});
  const auto folder = OptionalOutputFolder(o.out_dir, o.force, inputs, "validate");
  std::optional<FrictionModel> friction;
  std::unique_ptr<HysteresisModel> hysteresis;
  if (!o.model_path.empty())
    friction = ReadModel(o.model_path);
  else
    hysteresis = ReadHysteresisModel(o.hysteresis_path);
  o.motion.ApplyTo(o.validation.motion);
  // Only the friction model needs v (and says where it came from); a hysteresis model needs x.
  std::vector<Recording> recs;
  if (friction)
    recs = o.motion.ReadRecordings(o.files);
  else
    for (const auto& f : o.files) recs.push_back(ReadRecording(f, o.motion.recording.Apply({})));
  // Everything is computed before anything is written: a bad file leaves no partial output.
  std::vector<Validation> results;
  for (size_t i = 0; i < recs.size(); ++i) {
    Progress(fmt::format("validate: {}/{} {}", i + 1, recs.size(), o.files[i]));
    try {
      results.push_back(friction ? ValidateFrictionModel(recs[i], *friction, o.validation)
                                 : ValidateHysteresisModel(recs[i], *hysteresis, o.validation));
    } catch (const NumericalError& e) {
      throw InputError(o.files[i] + ": " + e.what());  // the model fails on this recording
    }
  }
  ProgressDone();
  nlohmann::ordered_json j;
  j["model"] = friction ? o.model_path : o.hysteresis_path;
  j["kind"] = friction ? "friction" : hysteresis->kind();
  j["max_lag"] = o.validation.residual.max_lag;
  j["recordings"] = nlohmann::ordered_json::array();
  Table table({"recording", "output", "fit [%]", "RMSE", "nrmse_std", "nrmse_range",
               "autocorrelation", "cross-correlation u"});
  auto verdict = [](const CorrelationTest& t) {
    return fmt::format("{} ({}/{} out)", t.pass ? "pass" : "FAIL", t.outside, t.lags.size());
  };
  for (const auto& v : results) {
    j["recordings"].push_back(nlohmann::ordered_json::parse(ToJson(v)));
    for (const auto& out : v.outputs)
      table.AddRow({fs::path(v.source).stem().string(), out.output, Num(out.scores.fit_percent, 4),
                    Num(out.scores.rmse, 4) + " " + out.unit, Num(out.scores.nrmse_std, 4),
                    Num(out.scores.nrmse_range, 4), verdict(out.autocorrelation),
                    verdict(out.cross_correlation)});
  }
  if (folder) {
    std::vector<std::string> notes;
    folder->Write([&](const fs::path& dir) {
      WriteFileAtomically((dir / "summary.json").string(), j.dump(2) + "\n");
      if (!o.plots) return;
      PlotColours colours;  // one colour per series label across the folder's plots
      std::vector<std::pair<std::string, PlotSpec>> drawn;
      for (const auto& v : results)
        for (auto& [name, spec] : ValidationPlots(v, fs::path(v.source).stem().string())) {
          colours.Apply(spec);
          const auto p = WritePlot((dir / name).string(), spec);
          if (!p.written) notes.push_back(p.message);
          drawn.emplace_back(name, std::move(spec));
        }
      if (!drawn.empty()) WriteFileAtomically((dir / "plots.json").string(), PlotIndexJson(drawn));
    });
    for (const auto& n : notes) std::cerr << "sysid validate: " << n << '\n';
  }
  if (o.json) {
    std::cout << j.dump(2) << '\n';
  } else {
    std::cout << table.Render()
              << fmt::format(
                     "residual tests: lags 1..{0} (autocorrelation), 0..{0} (with u), "
                     "99 % band ±2.58/sqrt(N); docs/validation.md gives the verdict rule\n",
                     o.validation.residual.max_lag);
  }
}

void AddValidateCommand(CLI::App& app) {
  auto o = std::make_shared<ValidateCliOptions>();
  CLI::App* cmd = app.add_subcommand(
      "validate",
      "Validate a model on held-out recordings as MATLAB's compare and resid do: simulate it "
      "free-run from u (friction model: v and x; hysteresis model: x), print fit % = "
      "100 (1 - |y - yhat| / |y - mean y|), RMSE, nrmse_std, nrmse_range and the residual's "
      "autocorrelation and cross-correlation with u against the 99 % band");
  auto* model = cmd->add_option("--model", o->model_path,
                                "friction model JSON (a1p, a1n, a2p, a2n, a3, tau), simulated "
                                "by the delayed stick-slip simulator")
                    ->check(CLI::ExistingFile)
                    ->type_name("M.json");
  cmd->add_option("--hysteresis", o->hysteresis_path,
                  "hysteresis model file from `sysid hysteresis fit`, simulated from u")
      ->check(CLI::ExistingFile)
      ->excludes(model)
      ->type_name("H.json");
  cmd->add_option("files", o->files, "held-out recordings: t [s], u [V], x [m] (or v [m/s])")
      ->required()
      ->type_name("REC");
  AddFieldOption(cmd, "--lags", o->validation, o->validation.residual.max_lag,
                 "largest lag L of the residual tests [samples], in [1, 1000]");
  AddOutputOption(cmd, o->out_dir,
                  "new folder for summary.json and the plots <name>_<y>.png, "
                  "<name>_<y>_residual_tests.png")
      ->type_name("DIR");
  cmd->add_flag("--force", o->force,
                "replace a folder an earlier sysid validate wrote (one holding .sysid-output)");
  cmd->add_flag("--json", o->json, "print one JSON object with the scores and tests");
  AddOffFlag(cmd, "--no-plots", o->plots, "skip the PNG plots in the output folder");
  o->motion.Add(cmd, "filter for the measured velocity from x",
                ToString(o->validation.motion.derivative.method));
  o->motion.Bind(cmd, o->validation, o->validation.motion);
  cmd->callback([o] { RunValidate(*o); });
}

const bool kRegistered = RegisterCommand(72, &AddValidateCommand);

}  // namespace
}  // namespace sysid::cli
