// Every command's flags against the options structs they set (apps/cli/field_flag.hpp). The
// reference is each struct's own Serialize list (sysid/serialize.hpp), read field by field:
// for every command of the real CLI app and every described struct it exposes, the fields its
// flags set plus the exclusions written here (each with its reason) are the whole list, and
// every flag of every command either sets a field or is listed here as a flag that sets none.
// A field added to a struct without a flag or an exclusion fails here, as does a flag added
// without a decision.
#include <catch2/catch.hpp>
#include <algorithm>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli/field_flag.hpp"
#include "cli/registry.hpp"

namespace {

using sysid::cli::ExposedOptions;

struct Excluded {
  std::string field;   ///< a field, or a nested struct's whole subtree ("segments")
  std::string reason;  ///< why no flag sets it
};
struct StructSpec {
  std::string type;
  std::vector<Excluded> excluded;
};
struct CommandSpec {
  std::string command;              ///< "tune-delay", "stage facts"
  std::vector<StructSpec> structs;  ///< the described structs its flags set
  std::vector<std::string> other_flags;  ///< flags that set no described field (--help aside)
};

std::vector<Excluded> Same(const std::string& reason, const std::string& prefix,
                           const std::vector<std::string>& fields) {
  std::vector<Excluded> out;
  for (const auto& f : fields) out.push_back({prefix + f, reason});
  return out;
}

std::vector<Excluded> Join(std::vector<std::vector<Excluded>> parts) {
  std::vector<Excluded> out;
  for (auto& p : parts) out.insert(out.end(), p.begin(), p.end());
  return out;
}

std::vector<std::string> Flags(std::vector<std::string> a, const std::vector<std::string>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

// The MotionOptions fields cli/motion_flags.hpp (--derivative, --cutoff, --velocity-column)
// leaves at the algorithm's defaults.
std::vector<Excluded> MotionUnflagged(const std::string& prefix) {
  return {{prefix + "derivative.butterworth_order", "the filter's order: the algorithm's"},
          {prefix + "derivative.savgol_window", "Savitzky-Golay window: the algorithm's"},
          {prefix + "derivative.savgol_order", "Savitzky-Golay order: the algorithm's"},
          {prefix + "max_relative_jitter", "the sampling check: the library's tolerance"}};
}

// The MotionOptions fields besides the sampling check (--jitter-tolerance) of a command that
// takes no --derivative: `why` it sets none.
std::vector<Excluded> SamplingOnly(const std::string& why) {
  return Same(why, "", {"derivative", "velocity_column", "prefer_velocity_column"});
}

// The NeuralTrainingOptions fields cli's training flags (commands/nn_training_options.hpp)
// leave at the library's defaults.
std::vector<Excluded> TrainingUnflagged(const std::string& prefix) {
  return Join(
      {Same("trainlm's mu schedule, as the paper", prefix,
            {"mu_initial", "mu_decrease", "mu_increase", "mu_max", "max_validation_failures"}),
       {{prefix + "initial_parameters", "a warm start: the library's API only"},
        {prefix + "ceres_block_size", "the Ceres trainer's internal blocking"}}});
}

const std::vector<std::string> kRecording = {"--var", "--rate", "--scale", "--t-start",
                                             "--t-end"};

const std::vector<CommandSpec>& Specs() {
  static const std::vector<CommandSpec> specs = {
      {"info",
       {{"MotionOptions", SamplingOnly("info derives no v or a")}},
       Flags({"file", "--json"}, kRecording)},
      {"import", {}, {"--column", "--rate", "--scale", "--unit", "--output", "--force"}},
      {"derive",
       {{"DerivativeOptions", {}},
        {"MotionOptions", SamplingOnly("its filter flags set the DerivativeOptions above")}},
       Flags({"file", "--output", "--force", "--decimate", "--resample", "--json"}, kRecording)},
      {"loop",
       {{"MotionOptions", MotionUnflagged("")}},
       Flags({"file", "--levels", "--half-window", "--cycles", "--moving-speed", "--json"},
             kRecording)},
      {"simulate",
       {},
       Flags({"--model", "--paper-model", "--input", "--hold", "--pulses", "--pulse-on",
              "--pulse-off", "--pulse-repeats", "--pulse-start", "--waveform", "--t-end", "--dt",
              "--output", "--force", "--events", "--json", "--method", "--rtol", "--atol", "--x0",
              "--v0", "--history-v"},
             {"--var", "--rate", "--scale"})},
      {"identify",
       {{"PulseIdentificationOptions",
         Join({MotionUnflagged("motion."),
               Same("the pulse edges: the library's tolerances", "detection.",
                    {"u_tolerance_v", "zero_tolerance_v"}),
               Same("the stage's travel: no limit from the command line", "plateau.",
                    {"travel_min_m", "travel_max_m"}),
               {{"plateau.min_window_samples", "the plateau's least samples: the library's"}}})},
        {"TrajectoryOptions",
         Join({MotionUnflagged("motion."),
               {{"trim_samples", "the derivative's start-up: the library's"}}})}},
       Flags({"recordings", "--method", "--table", "--verbose", "--json", "--output", "--force",
              "--fit-fraction"},
             kRecording)},
      {"tune-delay",
       {{"DelayTuningOptions",
         Join({MotionUnflagged("motion."),
               Same("the search's budget: the library's", "",
                    {"coarse_evaluations", "max_evaluations"}),
               Same("the simulator's tolerances: the library's", "", {"sim_rtol", "sim_atol"}),
               {{"segments", "how recordings are cut into pulses: the library's rule"}}})}},
       Flags({"--model", "recordings", "--fit-fraction", "--verbose", "--json", "--output",
              "--force"},
             kRecording)},
      {"refine",
       {{"RefineOptions",
         Join({MotionUnflagged("motion."),
               Same("the pulse edges: the library's tolerances", "detection.",
                    {"u_tolerance_v", "zero_tolerance_v"}),
               {{"sim_rtol", "the simulator's tolerance: the library's"}}})}},
       Flags({"--model", "recordings", "--json", "--verbose", "--output", "--force",
              "--fit-fraction"},
             kRecording)},
      {"generate",
       {{"DerivativeOptions",
         Same("the tracking procedure's filter settings: the library's", "",
              {"cutoff_hz", "butterworth_order", "savgol_window", "savgol_order"})}},
       {"what", "--stage", "--seed", "--output", "--format", "--force", "--json"}},
      {"excite",
       {{"PulseProcedure", {}}},
       {"what", "--output", "--force", "--rate", "--set", "--cycles", "--json"}},
      {"stage", {}, {}},
      {"stage facts",
       {{"FactsOptions",
         Same("the paper's experiment, as docs/virtual_stage.md states it (--reduced swaps the "
              "whole struct for FactsOptions::Reduced())",
              "",
              {"pulse",
               "delay",
               "pi",
               "track_frequencies_hz",
               "track_amplitude_m",
               "track_cycles",
               "ripple_tolerance_m",
               "motion_ripple_tolerance_m",
               "motion_ripple_window_s",
               "training",
               "typical_hidden",
               "typical_max_epochs",
               "typical_stride",
               "dominance_amplitude_v",
               "dominance_omega_rad_s",
               "dominance_offset_v",
               "dominance_duration_s",
               "dominance_min_speed_mps",
               "loop_period_s",
               "loop_peak_forward_v",
               "loop_peak_backward_v",
               "loop_levels_v",
               "loop_min_relative_width",
               "loop_min_start_ratio",
               "loop_sine_offset_v",
               "loop_sine_amplitude_v",
               "loop_sine_frequencies_hz",
               "loop_sine_frequency_hz",
               "loop_sine_amplitudes_v",
               "loop_min_rate_ratio",
               "loop_min_amplitude_change"})}},
       {"--stage", "--seeds", "--reduced", "--json", "--markdown"}},
      {"dominance",
       {{"DominanceOptions",
         Join({MotionUnflagged("motion."),
               {{"bound_quantile", "the bound's quantile: the library's"}}})}},
       Flags({"--model", "recordings", "--verbose", "--json", "--output", "--force"},
             kRecording)},
      {"hysteresis", {}, {}},
      {"hysteresis fit",
       {},
       Flags({"--model", "--operators", "--thresholds", "--no-offset", "--degree", "--hidden",
              "--epochs", "--seed", "--integrator", "--step-tolerance", "--input", "--starts",
              "--start-rtol", "--jacobian", "--max-time", "--threads", "--fit-fraction",
              "recordings", "--json", "--output", "--force"},
             kRecording)},
      {"hysteresis simulate",
       {},
       Flags({"--model", "recording", "--periodic", "--output", "--force"}, kRecording)},
      {"hysteresis invert",
       {},
       Flags({"--model", "reference", "--output", "--force"}, kRecording)},
      {"hysteresis dominance", {}, Flags({"recordings", "--operators", "--json"}, kRecording)},
      {"train",
       {{"NeuralTrainingOptions", TrainingUnflagged("")}},
       Flags({"--fit-fraction", "--train", "--test", "--validation", "--inputs", "--output",
              "--json", "-o", "--force", "--history"},
             kRecording)},
      {"sweep",
       {{"NeuralTrainingOptions",
         Join({TrainingUnflagged(""),
               {{"hidden", "each row's, from HiddenSweepOptions::hidden_sizes (--hidden)"},
                {"threads", "the sweep's --threads (HiddenSweepOptions) share the work"}}})},
        {"HiddenSweepOptions",
         {{"training", "the command's NeuralTrainingOptions (its own entry here)"}}}},
       Flags({"--fit-fraction", "--train", "--test", "--validation", "--inputs", "--output",
              "--json", "-o", "--force"},
             kRecording)},
      {"predict", {}, Flags({"--nn", "data", "-o", "--force", "--column", "--json"}, kRecording)},
      {"irreducible",
       {},
       Flags({"data", "--inputs", "--output", "--neighbours", "--jackknife-groups", "--seed",
              "--json"},
             kRecording)},
      {"compare",
       {{"CompareOptions",
         Same("the filter's settings: the method's defaults", "derivative.",
              {"cutoff_hz", "butterworth_order", "savgol_window", "savgol_order"})}},
       Flags({"--model", "--nn", "--hysteresis", "files", "--output", "--force", "--json",
              "--no-plots", "--traces"},
             kRecording)},
      {"validate",
       {{"ValidationOptions",
         Join({Same("the residual tests' band and levels: the library's (99 %)", "residual.",
                    {"z", "lag_probability", "test_level"}),
               MotionUnflagged("motion."),
               Same("the simulator's tolerances: the library's", "", {"sim_rtol", "sim_atol"})})}},
       Flags({"--model", "--hysteresis", "files", "--output", "--force", "--json", "--no-plots"},
             kRecording)},
      {"track",
       {{"SmoothProfileOptions",
         {{"dwell_fraction", "the profile's shape: the library's"},
          {"sample_rate_hz", "the plant's control rate (the stage file, or --loop-rate)"}}},
        {"PiOptions",
         {{"sample_time_s", "the plant's control period (the stage file, or --loop-rate)"},
          {"anti_windup", "always on: the library's default"}}}},
       Flags({"--plant", "--loop-rate", "--ff", "--hysteresis", "--waveform", "--model", "--nn",
              "--reference", "--seed", "--output", "--force", "--json", "--no-plots"},
             kRecording)},
      {"margins",
       {{"PiOptions",
         {{"u_max_v", "saturation is outside the linear loop the margins are of"},
          {"anti_windup", "saturation is outside the linear loop the margins are of"}}}},
       {"--model", "--extra-delay", "--json"}},
      {"tune-pi",
       {},
       {"--model", "--loop-rate", "--phase-margin", "--gain-margin", "--corner-ratio",
        "--extra-delay", "--u-max", "--step", "--sine-amplitude", "--sine-freq", "--json"}},
      {"pipeline",
       {{"PipelineOptions",
         Join({{{"delay", "delay tuning's settings: the library's (--threads is the pipeline's)"},
                {"typical_hidden", "the typical network's size: the paper's"},
                {"track_frequencies_hz", "the tracking experiment: the paper's"},
                {"track_amplitude_m", "the tracking experiment: the paper's"},
                {"pi.sample_time_s", "the stage file's control period"},
                {"pi.u_max_v", "the stage file's amplifier"},
                {"pi.anti_windup", "always on: the library's default"},
                {"facts_options", "the facts' own settings: sysid stage facts' defaults"}},
               TrainingUnflagged("training."),
               Same("the networks train with the library's settings (sysid train has the "
                    "flags)",
                    "training.",
                    {"hidden", "trainer", "init", "momentum", "solve_output_layer",
                     "gradient_tolerance", "goal_mse", "restarts", "input_ranges",
                     "output_range", "threads"})})}},
       Flags({"input", "--output", "--force", "--json"}, kRecording)},
      {"export",
       {},
       {"--model", "--nn", "--hysteresis", "--dt", "--precision", "--prefix", "--vectors", "-o",
        "--force"}},
  };
  return specs;
}

// Whether `path` is `field` or lies in its subtree.
bool Covers(const std::string& field, const std::string& path) {
  return path == field || path.rfind(field + ".", 0) == 0;
}

void Commands(CLI::App* app, const std::string& prefix,
              std::vector<std::pair<std::string, CLI::App*>>* out) {
  for (CLI::App* sub : app->get_subcommands({})) {
    const std::string name = prefix + sub->get_name();
    out->emplace_back(name, sub);
    Commands(sub, name + " ", out);
  }
}

void CheckStruct(const ExposedOptions& exposed, const StructSpec& spec) {
  INFO(exposed.type);
  std::vector<std::string> unaccounted, twice, stale;
  for (const auto& field : exposed.fields) {
    const bool bound = std::any_of(exposed.bound.begin(), exposed.bound.end(),
                                   [&](const auto& b) { return Covers(b.second, field); });
    const bool excluded = std::any_of(spec.excluded.begin(), spec.excluded.end(),
                                      [&](const Excluded& e) { return Covers(e.field, field); });
    if (!bound && !excluded) unaccounted.push_back(field);
    if (bound && excluded) twice.push_back(field);
  }
  for (const auto& e : spec.excluded) {
    CHECK_FALSE(e.reason.empty());
    if (std::none_of(exposed.fields.begin(), exposed.fields.end(),
                     [&](const std::string& f) { return Covers(e.field, f); }))
      stale.push_back(e.field);
  }
  CAPTURE(unaccounted, twice, stale);
  CHECK(unaccounted.empty());  // a field with neither a flag nor a written reason
  CHECK(twice.empty());        // a field both set by a flag and excluded
  CHECK(stale.empty());        // an exclusion naming no field of the struct
}

}  // namespace

TEST_CASE("every command's flags and every field of the options structs it exposes match") {
  static CLI::App app;  // never freed: the records are keyed by the commands' addresses
  sysid::cli::AddRegisteredCommands(app);
  std::vector<std::pair<std::string, CLI::App*>> commands;
  Commands(&app, "", &commands);

  std::set<std::string> listed, built;
  for (const auto& s : Specs()) listed.insert(s.command);
  for (const auto& [name, cmd] : commands) built.insert(name);
  CHECK(built == listed);  // a new command needs its entry here

  for (const auto& [command_name, cmd] : commands) {
    // A lambda cannot capture a structured binding in C++17 (clang refuses): a plain copy.
    const std::string name = command_name;
    INFO("sysid " << name);
    const auto spec = std::find_if(Specs().begin(), Specs().end(),
                                   [&](const CommandSpec& s) { return s.command == name; });
    if (spec == Specs().end()) continue;
    const std::vector<ExposedOptions> exposed = sysid::cli::ExposedOptionsOf(cmd);

    std::vector<std::string> exposed_types, listed_types;
    for (const auto& e : exposed) exposed_types.push_back(e.type);
    for (const auto& s : spec->structs) listed_types.push_back(s.type);
    CHECK(exposed_types == listed_types);
    for (const auto& e : exposed)
      for (const auto& s : spec->structs)
        if (s.type == e.type) CheckStruct(e, s);

    std::set<std::string> bound_flags, flags;
    for (const auto& e : exposed)
      for (const auto& b : e.bound) bound_flags.insert(b.first);
    std::vector<std::string> undecided, twice, stale;
    for (const CLI::Option* option : cmd->get_options()) {
      const std::string flag = sysid::cli::FlagName(option);
      flags.insert(flag);
      if (flag == "--help") continue;
      const bool other = std::count(spec->other_flags.begin(), spec->other_flags.end(), flag) > 0;
      if (!bound_flags.count(flag) && !other) undecided.push_back(flag);
      if (bound_flags.count(flag) && other) twice.push_back(flag);
    }
    for (const auto& f : spec->other_flags)
      if (!flags.count(f)) stale.push_back(f);
    CAPTURE(undecided, twice, stale);
    CHECK(undecided.empty());  // a flag neither setting a field nor listed as setting none
    CHECK(twice.empty());
    CHECK(stale.empty());
  }
}

namespace {

struct Inner {
  double x_m = 1.5;
  int n = 2;
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(x_m));
    a->Visit(SYSID_NVP(n));
  }
};

struct Outer {
  Inner inner;  // shares its address with Outer and with inner.x_m: the types tell them apart
  double y_s = 0.25;
  double not_listed = 0;
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(inner));
    a->Visit(SYSID_NVP(y_s));
  }
};

}  // namespace

TEST_CASE("a field flag is named by its struct's field list, and a member off the list fails") {
  static CLI::App app;  // as above
  CLI::App* cmd = app.add_subcommand("demo");
  Outer o;
  using sysid::cli::AddFieldOption;
  AddFieldOption(cmd, "--x", o, o.inner.x_m, "x [m]");
  AddFieldOption(cmd, "--y", o, o.y_s, "y [s]");
  sysid::cli::BindField(cmd, cmd->add_option("--inner-n", o.inner.n), o, o.inner.n);
  CHECK(cmd->get_option("--y")->get_default_str() == "0.25");  // the struct's default

  const auto exposed = sysid::cli::ExposedOptionsOf(cmd);
  REQUIRE(exposed.size() == 1);
  CHECK(exposed[0].type == "Outer");
  CHECK(exposed[0].fields == std::vector<std::string>{"inner.x_m", "inner.n", "y_s"});
  std::vector<std::string> bound;
  for (const auto& [flag, field] : exposed[0].bound) bound.push_back(flag + " " + field);
  CHECK(bound == std::vector<std::string>{"--x inner.x_m", "--y y_s", "--inner-n inner.n"});

  CHECK_THROWS_WITH(AddFieldOption(cmd, "--z", o, o.not_listed, "z"),
                    Catch::Contains("--z") && Catch::Contains("no field in Outer::Serialize"));
  double elsewhere = 0;
  CHECK_THROWS_AS(AddFieldOption(cmd, "--w", o, elsewhere, "w"), std::logic_error);
}
