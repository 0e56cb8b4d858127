// sysid track --plant STAGE.json|virtual --ff none|analytic|nn[,...] [--model M.json]
//             [--nn NN.json] (--freq F | --reference REF.csv) [--json] [-o DIR]
// sysid track --plant STACK.json|piezo-stack --ff none,hysteresis --hysteresis H.json
//             [--waveform sine|triangle] (--freq F | --reference REF.csv) [--json] [-o DIR]
// sysid track --plant M.json [--loop-rate HZ] --ff none|analytic|nn[,...] [--model FF.json] ...
// sysid track --plant H.json --ff none,hysteresis --hysteresis H2.json ... (the stack's form)
// PI position control on the virtual stage, the virtual piezo stack (a file naming
// "plant": "piezo-stack") or an identified friction model simulated as the plant (a model
// file), with optional feedforward; tracking-error table naming its plant.
#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <functional>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cli/common.hpp"
#include "cli/field_flag.hpp"
#include "cli/output_folder.hpp"
#include "cli/pi_flags.hpp"
#include "cli/recording_flags.hpp"
#include "cli/registry.hpp"
#include "sysid/compare_hysteresis.hpp"
#include "sysid/control.hpp"
#include "sysid/error.hpp"
#include "sysid/hysteresis.hpp"
#include "sysid/io.hpp"
#include "sysid/model.hpp"
#include "sysid/nn.hpp"
#include "sysid/report.hpp"
#include "sysid/stack.hpp"
#include "sysid/stage.hpp"

namespace sysid::cli {
namespace {

struct TrackCliOptions {
  std::string plant = "virtual", ff = "none";
  std::string model_path, nn_path, hysteresis_path, reference_path, out_dir;
  std::string waveform = "sine";  // the stack's reference
  // The flags whose default differs between stage and stack (set when given).
  const CLI::Option *freq = nullptr, *amplitude = nullptr, *kp = nullptr, *ki = nullptr,
                    *u_max = nullptr, *waveform_flag = nullptr;
  SmoothProfileOptions profile;  // the flags' defaults are the library's
  PiOptions pi;
  std::uint64_t seed = 1;
  bool json = false, plots = true, force = false;
  RecordingFlags recording;  // --var, --rate, --scale for --reference
  double loop_rate_hz = StageParameters::Default().rig.sample_rate_hz;  // a model plant's loop
  const CLI::Option* loop_rate = nullptr;
};

bool Given(const CLI::Option* option) { return option != nullptr && option->count() > 0; }

// A hysteresis model file ({"kind": ...}, sysid hysteresis fit -o): the model ahead of the
// stack's mechanics.
bool IsHysteresisPlant(const std::string& plant) {
  if (IsStackPresetName(plant) || StageParameters::IsPresetName(plant)) return false;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(plant, ec)) return false;
  const std::string text = ReadFile(plant);
  return !IsStackFileText(text) && text.find("\"kind\"") != std::string::npos &&
         text.find("\"a1p\"") == std::string::npos;
}

// A stack preset, a file that names "plant": "piezo-stack", or a hysteresis model (anything
// else is a stage or a friction model).
bool IsStackPlant(const std::string& plant) {
  if (IsStackPresetName(plant)) return true;
  if (StageParameters::IsPresetName(plant)) return false;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(plant, ec)) return false;
  return IsStackFileText(ReadFile(plant)) || IsHysteresisPlant(plant);
}

// The stack of --plant: a preset or stack file, or the bundled stack with H.json's hysteresis.
StackParameters LoadStackPlant(const std::string& plant) {
  if (!IsHysteresisPlant(plant)) return LoadStack(plant);
  const std::unique_ptr<HysteresisModel> model = ReadHysteresisModel(plant);
  const auto* pi = dynamic_cast<const PrandtlIshlinskiiModel*>(model.get());
  if (pi == nullptr)
    throw OptionsError(plant + ": a " + model->kind() +
                       " model has no form in the stack's hysteresis (rate-dependent PI); give "
                       "a pi or rdpi model as --plant (sysid hysteresis fit --model pi|rdpi)");
  return StackWithHysteresis(StackParameters::Default(), pi->pi(), plant);
}

// A friction model file (sysid identify -o: the key "a1p") rather than a stage or stack file.
bool IsModelPlant(const std::string& plant) {
  if (IsStackPresetName(plant) || StageParameters::IsPresetName(plant)) return false;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(plant, ec)) return false;
  const std::string text = ReadFile(plant);
  return !IsStackFileText(text) && text.find("\"a1p\"") != std::string::npos;
}

// --ff and the reference for every plant: the smooth profile `profile` makes (--freq,
// --amplitude, --cycles, --waveform) or --reference, which a plant at control_rate_hz [Hz] takes
// at its rate or at one dividing it (ReferenceAtControlRate: linear interpolation) inside its
// travel [x_min_m, x_max_m] [m]. A library refusal names the flag.
struct SchemesAndReference {
  std::vector<FeedforwardScheme> schemes;
  PositionReference reference;
};
SchemesAndReference ParseSchemesAndReference(const TrackCliOptions& o, double control_rate_hz,
                                             double x_min_m, double x_max_m,
                                             const std::function<PositionReference()>& profile) {
  SchemesAndReference out;
  try {
    out.schemes = ParseFeedforwardSchemes(o.ff);
    if (o.reference_path.empty()) {
      out.reference = profile();
    } else {
      out.reference = ReferenceAtControlRate(
          ReadPositionReference(o.reference_path, o.recording.Mapping()), control_rate_hz);
      CheckReferenceForPlant(out.reference, control_rate_hz, x_min_m, x_max_m);
    }
  } catch (const OptionsError& e) {
    std::map<std::string, std::string> flags{
        {"schemes", "--ff"},         {"waveform", "--waveform"},
        {"frequency_hz", "--freq"},  {"amplitude_m", "--amplitude"},
        {"stroke_m", "--amplitude"}, {"cycles", "--cycles"}};
    if (Given(o.loop_rate)) flags["sample_rate_hz"] = "--loop-rate";
    RethrowWithFlag(e, flags);
  }
  return out;
}

// -o DIR for stage and stack alike: a trace per scheme, the plots, the summary.
template <typename Folder, typename Runs>
void WriteTrackFolder(Folder& folder, const Runs& runs, bool plots, const std::string& summary) {
  namespace fs = std::filesystem;
  folder.Write([&](const fs::path& dir) {
    for (const auto& run : runs)
      WriteRecording((dir / ("track_" + ToString(run.scheme) + ".csv")).string(),
                     TrackingRecording(run.result, ToString(run.scheme)));
    if (plots) {
      const auto specs = TrackingPlots(runs);
      for (const auto& [name, spec] : specs) {
        const auto p = WritePlot((dir / name).string(), spec);
        if (!p.written) std::cerr << "sysid track: " << p.message << '\n';
      }
      WriteFileAtomically((dir / "plots.json").string(), PlotIndexJson(specs));
    }
    WriteFileAtomically((dir / "summary.json").string(), summary);
  });
}

// Progress per scheme on stderr, as every plant's loop reports it.
std::function<void(FeedforwardScheme, size_t)> SchemeProgress(size_t schemes) {
  return [schemes](FeedforwardScheme s, size_t i) {
    Progress(fmt::format("track: {} ({}/{})", ToString(s), i + 1, schemes));
  };
}

// The network --ff nn needs (read from --nn), else none.
std::optional<NeuralNetwork> NetworkIfUsed(const std::vector<FeedforwardScheme>& schemes,
                                           const TrackCliOptions& o) {
  if (!Uses(schemes, FeedforwardScheme::kNetwork)) return std::nullopt;
  if (o.nn_path.empty()) throw OptionsError("--ff nn needs --nn NN.json");
  return ReadNeuralNetwork(o.nn_path);
}

// The friction plants' table (the stage, an identified model): errors in mm, then the column
// `last` holding each run's stage limits.
Table FrictionRunsTable(const std::vector<SchemeTracking>& runs, const std::string& last) {
  Table table({"feedforward", "max |e| [mm]", "RMS e [mm]", "RMS u [V]", "max |u| [V]", "saturated",
               last});
  for (const auto& run : runs) {
    const auto& r = run.result;
    table.AddRow({ToString(run.scheme), Num(1e3 * r.max_error_m, 5), Num(1e3 * r.rms_error_m, 5),
                  Num(r.rms_u_v, 4), Num(r.max_abs_u_v, 4), std::to_string(r.saturated_samples),
                  run.stage_limits});
  }
  return table;
}

void RunStackTrack(const TrackCliOptions& o) {
  namespace fs = std::filesystem;
  const auto folder = OptionalOutputFolder(o.out_dir, o.force,
                                           {o.plant, o.hysteresis_path, o.reference_path}, "track");
  if (!o.model_path.empty() || !o.nn_path.empty())
    throw OptionsError(
        "--model and --nn are the stage's inverse models; the piezo stack takes --hysteresis "
        "H.json (--ff hysteresis)");
  const StackParameters stack = LoadStackPlant(o.plant);
  PiOptions pi = StackPiOptions(stack);
  if (Given(o.kp)) pi.kp_v_per_m = o.pi.kp_v_per_m;
  if (Given(o.ki)) pi.ki_v_per_m_s = o.pi.ki_v_per_m_s;
  if (Given(o.u_max)) pi.u_max_v = o.pi.u_max_v;
  // The stack reaches at most its steepest static slope times the amplifier's range: a
  // generous envelope that still refuses a 1 m stroke on a 30 um stack.
  const double reach_min = stack.MaxStaticGain() * std::min(stack.rig.voltage_min_v, 0.0),
               reach_max = stack.MaxStaticGain() * stack.rig.voltage_max_v;
  const SchemesAndReference parsed =
      ParseSchemesAndReference(o, stack.rig.control_rate_hz, reach_min, reach_max, [&] {
        StackReferenceOptions ro;
        ro.waveform = ParseStackWaveform(o.waveform);
        if (Given(o.freq)) ro.frequency_hz = o.profile.frequency_hz;
        if (Given(o.amplitude)) ro.stroke_m = o.profile.amplitude_m;
        ro.cycles = o.profile.cycles;
        ro.sample_rate_hz = stack.rig.control_rate_hz;
        if (!(ro.stroke_m <= reach_max))
          throw OptionsError("StackReferenceOptions", "stroke_m", fmt::format("{:g} m", ro.stroke_m),
                             fmt::format("at most the stack's reach, {:g} m (its steepest slope "
                                         "{:g} m/V at {:g} V)",
                                         reach_max, stack.MaxStaticGain(), stack.rig.voltage_max_v));
        return MakeStackReference(ro);
      });
  const std::vector<FeedforwardScheme>& schemes = parsed.schemes;
  const PositionReference& ref = parsed.reference;
  std::unique_ptr<HysteresisModel> hysteresis;
  if (Uses(schemes, FeedforwardScheme::kHysteresis)) {
    if (o.hysteresis_path.empty())
      throw OptionsError("--ff hysteresis needs --hysteresis H.json (sysid hysteresis fit -o)");
    hysteresis = ReadHysteresisModel(o.hysteresis_path);
  }
  std::vector<SchemeTracking> runs;
  try {
    runs = TrackStackSchemes(stack, o.seed, ref, pi, schemes, {nullptr, nullptr, hysteresis.get()},
                             SchemeProgress(schemes.size()));
  } catch (const OptionsError& e) {
    RethrowWithFlag(e, {{"schemes", "--ff"}});
  }
  ProgressDone();
  const LoopMargins margins = StackPiMargins(stack, pi);

  const std::string summary = TrackingSummaryToJson(
      IsStackPresetName(o.plant) ? stack.name : o.plant, ref, pi, runs);
  Table table({"feedforward", "max |e| [um]", "RMS e [um]", "RMS e / stroke", "RMS u [V]",
               "max |u| [V]", "saturated", "limits"});
  const double stroke = ref.x_m.maxCoeff() - ref.x_m.minCoeff();
  for (const auto& run : runs) {
    const auto& r = run.result;
    table.AddRow({ToString(run.scheme), Num(1e6 * r.max_error_m, 5), Num(1e6 * r.rms_error_m, 5),
                  stroke > 0 ? fmt::format("{:.3g} %", 100 * r.rms_error_m / stroke) : "-",
                  Num(r.rms_u_v, 4), Num(r.max_abs_u_v, 4), std::to_string(r.saturated_samples),
                  run.stage_limits});
  }
  if (folder) WriteTrackFolder(*folder, runs, o.plots, summary);
  if (o.json) {
    std::cout << summary;
    return;
  }
  std::cout << fmt::format("{}: {}\n", stack.name, ref.description)
            << fmt::format(
                   "PI Kp = {:.4g} V/m, Ki = {:.4g} V/(m s); linear margins at the steepest slope: "
                   "gain {:.3g}, phase {:.3g} deg, crossover {:.3g} Hz\n",
                   pi.kp_v_per_m, pi.ki_v_per_m_s, margins.gain_margin, margins.phase_margin_deg,
                   margins.CrossoverHz())
            << table.Render();
}

// The identified model as the plant (FrictionModelPlant); --ff analytic defaults to the same
// model, --model names another (the model error a user wants to see).
void RunModelTrack(const TrackCliOptions& o) {
  if (!o.hysteresis_path.empty() || Given(o.waveform_flag))
    throw OptionsError("--hysteresis and --waveform are the piezo stack's; a friction model "
                       "plant tracks the smooth profile (--freq, --amplitude) or --reference");
  const auto folder = OptionalOutputFolder(
      o.out_dir, o.force, {o.plant, o.model_path, o.nn_path, o.reference_path}, "track");
  const FrictionModel plant = ReadModel(o.plant);
  // An identified model has no travel limits.
  const SchemesAndReference parsed =
      ParseSchemesAndReference(o, o.loop_rate_hz, -std::numeric_limits<double>::max(),
                               std::numeric_limits<double>::max(), [&] {
                                 SmoothProfileOptions profile = o.profile;
                                 profile.sample_rate_hz = o.loop_rate_hz;
                                 return MakeSmoothProfile(profile);
                               });
  const std::vector<FeedforwardScheme>& schemes = parsed.schemes;
  const PositionReference& ref = parsed.reference;
  const FrictionModel ff_model = o.model_path.empty() ? plant : ReadModel(o.model_path);
  const std::optional<NeuralNetwork> nn = NetworkIfUsed(schemes, o);
  const std::vector<SchemeTracking> runs = TrackModelSchemes(
      plant, 1 / o.loop_rate_hz, ref, o.pi, schemes, {&ff_model, nn ? &*nn : nullptr},
      SchemeProgress(schemes.size()));
  ProgressDone();
  const std::string summary = TrackingSummaryToJson(o.plant, ref, o.pi, runs);
  const Table table = FrictionRunsTable(runs, "plant");
  if (folder) WriteTrackFolder(*folder, runs, o.plots, summary);
  if (o.json) {
    std::cout << summary;
    return;
  }
  std::cout << fmt::format("plant: {} (identified friction model, simulated at {:g} Hz); "
                           "feedforward model: {}\n",
                           o.plant, o.loop_rate_hz,
                           o.model_path.empty() ? "the plant's" : o.model_path)
            << table.Render();
}

void RunTrack(const TrackCliOptions& o) {
  namespace fs = std::filesystem;
  if (IsStackPlant(o.plant)) return RunStackTrack(o);
  if (IsModelPlant(o.plant)) return RunModelTrack(o);
  if (Given(o.loop_rate))
    throw OptionsError("--loop-rate is a friction model plant's; a stage runs at its own control "
                       "rate (rig.control_rate_hz)");
  if (!o.hysteresis_path.empty())
    throw OptionsError("--hysteresis is the piezo stack's feedforward model (--plant piezo-stack)");
  if (Given(o.waveform_flag))
    throw OptionsError("--waveform is the piezo stack's reference; the stage tracks its smooth "
                       "profile (--freq, --amplitude) or --reference");
  // The output folder is checked before any work; --plant may name a preset.
  const auto folder = OptionalOutputFolder(
      o.out_dir, o.force, {o.plant, o.model_path, o.nn_path, o.reference_path}, "track");
  const StageParameters stage = LoadStage(o.plant);
  const SchemesAndReference parsed = ParseSchemesAndReference(
      o, stage.rig.sample_rate_hz, stage.rig.travel_min_m, stage.rig.travel_max_m,
      [&] { return MakeStageProfile(stage, o.profile); });
  const std::vector<FeedforwardScheme>& schemes = parsed.schemes;
  const PositionReference& ref = parsed.reference;
  std::optional<FrictionModel> model;
  if (Uses(schemes, FeedforwardScheme::kAnalytic)) {
    if (o.model_path.empty()) throw OptionsError("--ff analytic needs --model M.json");
    model = ReadModel(o.model_path);
  }
  const std::optional<NeuralNetwork> nn = NetworkIfUsed(schemes, o);
  const std::vector<SchemeTracking> runs = TrackSchemes(
      stage, o.seed, ref, o.pi, schemes, {model ? &*model : nullptr, nn ? &*nn : nullptr},
      SchemeProgress(schemes.size()));
  ProgressDone();

  const std::string summary = TrackingSummaryToJson(
      StageParameters::IsPresetName(o.plant) ? stage.name : o.plant, ref, o.pi, runs);
  const Table table = FrictionRunsTable(runs, "limits");
  if (folder) WriteTrackFolder(*folder, runs, o.plots, summary);
  std::cout << (o.json ? summary : "plant: " + stage.name + "\n" + table.Render());
}

void AddTrackCommand(CLI::App& app) {
  auto o = std::make_shared<TrackCliOptions>();
  CLI::App* cmd = app.add_subcommand(
      "track",
      "PI position control of the virtual stage with feedforward (none, the analytic "
      "inverse, or the NN inverse), or of the virtual piezo stack with a hysteresis model's "
      "inverse as feedforward: maximum and RMS tracking error and control effort");
  cmd->add_option("--plant", o->plant,
                  std::string("stage parameter file STAGE.json, or a stage preset: ") +
                      cli::kStagePresets +
                      "; or a piezo stack: a file naming \"plant\": \"piezo-stack\", or the "
                  "preset 'piezo-stack' (docs/piezo_stack.md); or an identified friction model "
                  "M.json (sysid identify -o), simulated with stick-slip as the plant; or a pi or "
                  "rdpi hysteresis model H.json (sysid hysteresis fit -o) ahead of the bundled "
                  "stack's creep and mechanics");
  o->loop_rate = cmd->add_option("--loop-rate", o->loop_rate_hz,
                                 "control rate of a friction model plant [Hz] (the bundled "
                                 "stage's)")
                     ->check(FiniteRange(1, 1e6))
                     ->capture_default_str();
  cmd->add_option("--ff", o->ff,
                  "feedforward scheme(s), comma separated: none, analytic, nn (stage); none, "
                  "hysteresis (stack)")
      ->capture_default_str();
  cmd->add_option("--hysteresis", o->hysteresis_path,
                  "hysteresis model JSON (sysid hysteresis fit -o) whose inverse of the position "
                  "reference is the feedforward (for --ff hysteresis; piezo stack)")
      ->check(CLI::ExistingFile);
  o->waveform_flag =
      cmd->add_option("--waveform", o->waveform,
                      "the piezo stack's reference: sine or triangle, from 0 up to the stroke and "
                      "back")
          ->check(CLI::IsMember({"sine", "triangle"}))
          ->capture_default_str();
  cmd->add_option("--model", o->model_path,
                  "friction model JSON (for --ff analytic; with a model plant, default the plant)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--nn", o->nn_path,
                  "neural inverse model JSON on v [m/s] (and a [m/s^2]) "
                  "(for --ff nn)")
      ->check(CLI::ExistingFile);
  SmoothProfileOptions& profile = o->profile;
  auto* freq =
      AddFieldOption(cmd, "--freq", profile, profile.frequency_hz,
                     fmt::format("frequency of the smooth back-and-forth profile [Hz] (piezo "
                                 "stack: of its waveform, {:g} when not given)",
                                 StackReferenceOptions{}.frequency_hz))
          ->check(PositiveNumber());
  o->freq = freq;
  cmd->add_option("--reference", o->reference_path,
                  "position reference CSV with t [s] and x_ref [m] (or x) columns, sampled "
                  "uniformly at the control rate or at a rate that divides it (1 kHz on a 10 kHz "
                  "loop: x_ref, v_ref, a_ref interpolated linearly between its samples)")
      ->check(CLI::ExistingFile)
      ->excludes(freq);
  o->amplitude =
      AddFieldOption(cmd, "--amplitude", profile, profile.amplitude_m,
                     fmt::format("stroke of the profile [m] (piezo stack: {:g} when not given)",
                                 StackReferenceOptions{}.stroke_m));
  AddFieldOption(cmd, "--cycles", profile, profile.cycles, "profile periods to run")
      ->check(PositiveNumber());
  PiOptions& pi = o->pi;
  const auto [kp, ki] = AddPiGainOptions(cmd, pi, "");
  kp->check(FiniteRange(0.0, 1e9));
  ki->check(FiniteRange(0.0, 1e12));
  o->kp = kp;
  o->ki = ki;
  o->u_max = AddFieldOption(cmd, "--u-max", pi, pi.u_max_v,
                            "output saturation [V] (piezo stack: default its amplifier's upper "
                            "end; its gains default to StackPiOptions, docs/piezo_stack.md)")
                 ->check(PositiveNumber());
  AddSeedOption(cmd, o->seed, "seed of the stage's encoder noise");
  AddOutputOption(cmd, o->out_dir,
                  "new folder for track_<ff>.csv traces, plots and summary.json")
      ->type_name("DIR");
  cmd->add_flag("--force",
                o->force, "replace a folder an earlier sysid track wrote (one holding .sysid-output)");
  cmd->add_flag("--json", o->json, "print one JSON object (max_error_m, rms_error_m, schemes)");
  AddOffFlag(cmd, "--no-plots", o->plots, "skip the PNG plots");
  o->recording.Add(cmd);
  cmd->callback([o] { RunTrack(*o); });
}

const bool kRegistered = RegisterCommand(80, &AddTrackCommand);

}  // namespace
}  // namespace sysid::cli
