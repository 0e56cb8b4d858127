// sysid track --plant STAGE.json|virtual --ff none|analytic|nn[,...] [--model M.json]
//             [--nn NN.json] (--freq F | --reference REF.csv) [--json] [-o DIR]
// PI position control on the virtual stage with optional feedforward; tracking-error table.
#include <fmt/format.h>

#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "cli/common.hpp"
#include "cli/output_folder.hpp"
#include "cli/pi_flags.hpp"
#include "cli/registry.hpp"
#include "sysid/compare.hpp"
#include "sysid/control.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"
#include "sysid/nn.hpp"
#include "sysid/report.hpp"
#include "sysid/stage.hpp"

namespace sysid::cli {
namespace {

struct TrackCliOptions {
  std::string plant = "virtual";
  std::string ff = "none";
  std::string model_path, nn_path, reference_path, out_dir;
  SmoothProfileOptions profile;  // the flags' defaults are the library's
  PiOptions pi;
  std::uint64_t seed = 1;
  bool json = false;
  bool plots = true;
  bool force = false;
};

std::vector<FeedforwardScheme> ParseSchemes(const std::string& s) {
  std::vector<FeedforwardScheme> out;
  std::stringstream ss(s);
  std::string item;
  try {
    while (std::getline(ss, item, ',')) out.push_back(ParseFeedforwardScheme(item));
  } catch (const OptionsError& e) {
    throw OptionsError(std::string("--ff: ") + e.what());
  }
  if (out.empty()) throw OptionsError("--ff: expected none, analytic or nn");
  return out;
}

void RunTrack(const TrackCliOptions& o) {
  namespace fs = std::filesystem;
  // The output folder is checked before any work (cli/output_folder.hpp).
  std::optional<OutputFolder> folder;
  if (!o.out_dir.empty()) {
    std::vector<std::string> inputs;  // files only (--plant may name a preset)
    for (const auto* path : {&o.plant, &o.model_path, &o.nn_path, &o.reference_path})
      if (!path->empty() && fs::exists(*path)) inputs.push_back(*path);
    folder.emplace(o.out_dir, o.force, inputs, "track");
  }
  const StageParameters stage = LoadStage(o.plant);
  const std::vector<FeedforwardScheme> schemes = ParseSchemes(o.ff);
  std::optional<FrictionModel> model;
  std::optional<NeuralNetwork> nn;
  for (const auto s : schemes) {
    if (s == FeedforwardScheme::kAnalytic && !model) {
      if (o.model_path.empty()) throw OptionsError("--ff analytic needs --model M.json");
      model = ReadModel(o.model_path);
    }
    if (s == FeedforwardScheme::kNetwork && !nn) {
      if (o.nn_path.empty()) throw OptionsError("--ff nn needs --nn NN.json");
      nn = ReadNeuralNetwork(o.nn_path);
    }
  }
  PositionReference ref;
  if (!o.reference_path.empty()) {
    ref = ReadPositionReference(o.reference_path);
  } else {
    SmoothProfileOptions p = o.profile;
    p.sample_rate_hz = stage.sample_rate_hz;
    // The stroke must fit the stage's travel from where it starts.
    const double end = stage.initial_position_m + p.amplitude_m;
    if (!(end >= stage.travel_min_m && end <= stage.travel_max_m))
      throw OptionsError(fmt::format(
          "--amplitude = {} m. Violated constraint: the stroke from the start position {} m "
          "stays within the stage's travel [{}, {}] m",
          p.amplitude_m, stage.initial_position_m, stage.travel_min_m, stage.travel_max_m));
    ref = MakeSmoothProfile(p);
  }
  const std::vector<SchemeTracking> runs = TrackSchemes(
      stage, o.seed, ref, o.pi, schemes, {model ? &*model : nullptr, nn ? &*nn : nullptr},
      [&](FeedforwardScheme s, size_t i) {
        Progress(fmt::format("track: {} ({}/{})", ToString(s), i + 1, schemes.size()));
      });
  ProgressDone();

  nlohmann::ordered_json j;
  j["plant"] = StageParameters::IsPresetName(o.plant) ? stage.name : o.plant;
  j["reference"] = ref.description;
  j["kp_v_per_m"] = o.pi.kp_v_per_m;
  j["ki_v_per_m_s"] = o.pi.ki_v_per_m_s;
  j["schemes"] = nlohmann::ordered_json::array();
  Table table({"feedforward", "max |e| [mm]", "RMS e [mm]", "RMS u [V]", "max |u| [V]", "saturated",
               "limits"});
  for (const auto& run : runs) {
    const auto& r = run.result;
    const std::string scheme = ToString(run.scheme);
    nlohmann::ordered_json entry = {{"ff", scheme}};
    entry.update(nlohmann::ordered_json::parse(ToJson(r)));
    entry["stage_limits"] = run.stage_limits;
    j["schemes"].push_back(entry);
    table.AddRow({scheme, Num(1e3 * r.max_error_m, 5), Num(1e3 * r.rms_error_m, 5),
                  Num(r.rms_u_v, 4), Num(r.max_abs_u_v, 4), std::to_string(r.saturated_samples),
                  run.stage_limits});
  }
  if (runs.size() == 1) {
    j["max_error_m"] = runs[0].result.max_error_m;
    j["rms_error_m"] = runs[0].result.rms_error_m;
  }
  if (folder) {
    folder->Write([&](const fs::path& dir) {
      PlotSpec err{"tracking error", "t [s]", "e [mm]", {}, false, 900, 500};
      PlotSpec u{"control signal", "t [s]", "u [V]", {}, false, 900, 500};
      for (const auto& run : runs) {
        const auto& r = run.result;
        const std::string scheme = ToString(run.scheme);
        Recording rec;
        rec.metadata = {{"ff", scheme},
                        {"units", "t [s], x_ref [m], x [m], e [m], u [V], u_ff [V]"}};
        rec.SetColumn("t", r.t_s);
        rec.SetColumn("x_ref", r.x_ref_m);
        rec.SetColumn("x", r.x_m);
        rec.SetColumn("e", r.e_m);
        rec.SetColumn("u", r.u_v);
        rec.SetColumn("u_ff", r.u_ff_v);
        WriteRecording((dir / ("track_" + scheme + ".csv")).string(), rec);
        err.series.push_back({scheme, r.t_s, 1e3 * r.e_m, "lines"});
        u.series.push_back({scheme, r.t_s, r.u_v, "lines"});
      }
      if (o.plots) {
        for (const auto& [name, spec] :
             {std::pair{"tracking_error.png", err}, std::pair{"control_signal.png", u}}) {
          const auto p = WritePlot((dir / name).string(), spec);
          if (!p.written) std::cerr << "sysid track: " << p.message << '\n';
        }
      }
      WriteFileAtomically((dir / "summary.json").string(), j.dump(2) + "\n");
    });
  }
  if (o.json)
    std::cout << j.dump(2) << '\n';
  else
    std::cout << table.Render();
}

void AddTrackCommand(CLI::App& app) {
  auto o = std::make_shared<TrackCliOptions>();
  CLI::App* cmd = app.add_subcommand(
      "track",
      "PI position control of the virtual stage with feedforward (none, the analytic "
      "inverse, or the NN inverse): maximum and RMS tracking error and control effort");
  cmd->add_option("--plant", o->plant,
                  "stage parameter file STAGE.json, or a preset: 'virtual' (the bundled "
                  "calibrated velocity-source stage) or 'actuator-delay' (the former stage, on "
                  "which the paper's gains limit-cycle and feedforward does not help)");
  cmd->add_option("--ff", o->ff, "feedforward scheme(s), comma separated: none, analytic, nn")
      ->capture_default_str();
  cmd->add_option("--model", o->model_path, "friction model JSON (for --ff analytic)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--nn", o->nn_path,
                  "neural inverse model JSON on v [m/s] (and a [m/s^2]) "
                  "(for --ff nn)")
      ->check(CLI::ExistingFile);
  auto* freq =
      cmd->add_option("--freq", o->profile.frequency_hz,
                      "frequency of the smooth back-and-forth profile [Hz]")
          ->check(CLI::PositiveNumber)
          ->capture_default_str();
  cmd->add_option("--reference", o->reference_path,
                  "position reference CSV with t [s] and x_ref [m] (or x) columns")
      ->check(CLI::ExistingFile)
      ->excludes(freq);
  cmd->add_option("--amplitude", o->profile.amplitude_m, "stroke of the profile [m]")
      ->capture_default_str();
  cmd->add_option("--cycles", o->profile.cycles, "profile periods to run")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  const auto [kp, ki] = AddPiGainOptions(cmd, o->pi, "");
  kp->check(CLI::Range(0.0, 1e9));
  ki->check(CLI::Range(0.0, 1e12));
  cmd->add_option("--u-max", o->pi.u_max_v, "output saturation [V]")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--seed", o->seed, "seed of the stage's encoder noise")
      ->check(CLI::Range(std::uint64_t{0}, std::uint64_t{1} << 62))  // CLI11 would wrap -1
      ->capture_default_str();
  AddOutputOption(cmd, o->out_dir,
                  "new folder for track_<ff>.csv traces, plots and summary.json")
      ->type_name("DIR");
  cmd->add_flag("--force",
                o->force, "replace a folder an earlier sysid track wrote (one holding .sysid-output)");
  cmd->add_flag("--json", o->json, "print one JSON object (max_error_m, rms_error_m, schemes)");
  cmd->add_flag("!--no-plots", o->plots, "skip the PNG plots");
  cmd->callback([o] { RunTrack(*o); });
}

const bool kRegistered = RegisterCommand(80, &AddTrackCommand);

}  // namespace
}  // namespace sysid::cli
