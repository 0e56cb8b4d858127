// The defaults `sysid <command> --help` shows are the library's: each flag bound to an Options
// field shows that field's default-constructed value (CLI11 capture_default_str), and no help
// text carries a hand-written default number that could drift from the struct.
#include <catch2/catch.hpp>
#include <regex>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "support/test_support.hpp"
#include "sysid/control.hpp"
#include "sysid/control_tuning.hpp"
#include "sysid/delay.hpp"
#include "sysid/dominance.hpp"
#include "sysid/identify.hpp"
#include "sysid/input.hpp"
#include "sysid/motion.hpp"
#include "sysid/nn.hpp"
#include "sysid/pipeline.hpp"
#include "sysid/simulate.hpp"
#include "sysid/stage.hpp"
#include "sysid/stage_facts.hpp"

using sysid::test::RunCli;

namespace {

std::string Help(const std::vector<std::string>& command) {
  std::vector<std::string> args = command;
  args.push_back("--help");
  const auto r = RunCli(args);
  REQUIRE(r.exit_code == 0);
  return r.out;
}

// The subcommands a help text lists under "Subcommands:".
std::vector<std::string> Subcommands(const std::string& help) {
  std::vector<std::string> names;
  std::istringstream lines(help);
  bool in_list = false;
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("Subcommands:", 0) == 0) {
      in_list = true;
      continue;
    }
    std::istringstream words(line);
    std::string name;
    if (in_list && (words >> name)) names.push_back(name);
  }
  return names;
}

// Every command the help lists, with their subcommands in place of those that have some
// (`hysteresis fit`, `stage facts`, ...).
std::vector<std::vector<std::string>> AllCommands() {
  std::vector<std::vector<std::string>> commands;
  for (const auto& name : Subcommands(Help({}))) {
    const auto nested = Subcommands(Help({name}));
    if (nested.empty()) commands.push_back({name});
    for (const auto& sub : nested) commands.push_back({name, sub});
  }
  return commands;
}

// The default shown for `flag`: CLI11 writes "  --flag TYPE=VALUE  description"; the option
// column ends at the first run of two blanks. Empty when no default is shown.
std::string ShownDefault(const std::string& help, const std::string& flag) {
  std::istringstream lines(help);
  for (std::string line; std::getline(lines, line);) {
    const size_t at = line.find(flag);
    if (at == std::string::npos) continue;
    // The flag opens the option column: blanks before it, or a short form ("-o,").
    const size_t first = line.find_first_not_of(' ');
    if (first != at && !(line[at - 1] == ',' && line.find(' ', first) > at)) continue;
    const size_t end = line.find("  ", at);
    const std::string column = line.substr(at, end == std::string::npos ? end : end - at);
    if (column.compare(0, flag.size(), flag) != 0 ||
        (column.size() > flag.size() && column[flag.size()] != ' ' &&
         column[flag.size()] != '='))
      continue;  // a longer flag with this prefix
    const size_t eq = column.find('=');
    return eq == std::string::npos ? "" : column.substr(eq + 1);
  }
  FAIL("flag " << flag << " not in the help text");
  return "";
}

double ShownNumber(const std::string& help, const std::string& flag) {
  const std::string text = ShownDefault(help, flag);
  INFO(flag << " shows '" << text << "'");
  REQUIRE(!text.empty());
  return std::stod(text);
}

}  // namespace

TEST_CASE("help defaults are the Options structs' defaults", "[cli]") {
  const auto same = [](double shown, double field) {
    return shown == Approx(field).epsilon(1e-6).margin(1e-300);
  };
  {
    const std::string h = Help({"identify"});
    CHECK(same(ShownNumber(h, "--min-duration"), sysid::PulseDetectionOptions{}.min_duration_s));
    CHECK(same(ShownNumber(h, "--window-fraction"), sysid::PlateauOptions{}.window_fraction));
    CHECK(same(ShownNumber(h, "--settle-tolerance"), sysid::PlateauOptions{}.settle_tolerance));
    CHECK(same(ShownNumber(h, "--pulse-min-speed"), sysid::PlateauOptions{}.min_speed_mps));
    CHECK(same(ShownNumber(h, "--a3"), sysid::PulseFitOptions{}.a3));
    CHECK(same(ShownNumber(h, "--tau-max"), sysid::TrajectoryOptions{}.tau_max_s));
    CHECK(same(ShownNumber(h, "--min-speed"), sysid::TrajectoryOptions{}.min_speed_mps));
    CHECK(same(ShownNumber(h, "--cutoff"), sysid::MotionOptions{}.derivative.cutoff_hz));
    CHECK_THAT(ShownDefault(h, "--derivative"),
               Catch::Contains(sysid::ToString(
                   sysid::TrajectoryOptions{}.motion.derivative.method)));
  }
  {
    const std::string h = Help({"simulate"});
    const sysid::SimulationOptions sim;
    CHECK(same(ShownNumber(h, "--rtol"), sim.rtol));
    CHECK(same(ShownNumber(h, "--atol"), sim.atol));
    CHECK(same(ShownNumber(h, "--dt"), sim.dt_out_s));
    CHECK(ShownDefault(h, "--method") == sysid::ToString(sim.method));
    CHECK(same(ShownNumber(h, "--pulse-on"), sysid::PulseTrainSpec{}.on_s));
    CHECK(same(ShownNumber(h, "--pulse-off"), sysid::PulseTrainSpec{}.off_s));
    CHECK(same(ShownNumber(h, "--pulse-repeats"), sysid::PulseTrainSpec{}.repeats));
  }
  {
    const std::string h = Help({"tune-delay"});
    CHECK(same(ShownNumber(h, "--tau-max"), sysid::DelayTuningOptions{}.tau_max_s));
    CHECK(same(ShownNumber(h, "--tau-min"), sysid::DelayTuningOptions{}.tau_min_s));
    CHECK(same(ShownNumber(h, "--xtol"), sysid::DelayTuningOptions{}.x_tolerance_s));
  }
  {
    const std::string h = Help({"refine"});
    CHECK(same(ShownNumber(h, "--tau-max"), sysid::RefineOptions{}.tau_max_s));
    CHECK(same(ShownNumber(h, "--max-iterations"), sysid::RefineOptions{}.max_iterations));
  }
  CHECK(same(ShownNumber(Help({"dominance"}), "--negligible"),
             sysid::DominanceOptions{}.negligible_ratio));
  {
    const std::string h = Help({"train"});
    const sysid::NeuralTrainingOptions t;
    CHECK(same(ShownNumber(h, "--max-epochs"), t.max_epochs));
    CHECK(same(ShownNumber(h, "--min-gradient"), t.gradient_tolerance));
    CHECK(same(ShownNumber(h, "--hidden"), t.hidden));
    CHECK(ShownDefault(h, "--trainer") == "lm");
  }
  CHECK(sysid::ParseHiddenSizes(ShownDefault(Help({"sweep"}), "--hidden")) ==
        sysid::HiddenSweepOptions{}.hidden_sizes);
  {
    const std::string h = Help({"pipeline"});
    const sysid::PipelineOptions p;
    CHECK(same(ShownNumber(h, "--max-epochs"), p.training.max_epochs));
    CHECK(same(ShownNumber(h, "--typical-epochs"), p.typical_max_epochs));
    CHECK(same(ShownNumber(h, "--kp"), p.pi.kp_v_per_m));
    CHECK(same(ShownNumber(h, "--ki"), p.pi.ki_v_per_m_s));
    CHECK(sysid::ParseHiddenSizes(ShownDefault(h, "--hidden")) == p.hidden_sizes);
  }
  {
    const std::string h = Help({"track"});
    CHECK(same(ShownNumber(h, "--u-max"), sysid::PiOptions{}.u_max_v));
    CHECK(same(ShownNumber(h, "--amplitude"), sysid::SmoothProfileOptions{}.amplitude_m));
    CHECK(same(ShownNumber(h, "--freq"), sysid::SmoothProfileOptions{}.frequency_hz));
  }
  {
    const std::string h = Help({"tune-pi"});
    const sysid::PiTuningOptions t;
    const sysid::PiBehaviourOptions b;
    CHECK(same(ShownNumber(h, "--loop-rate"), t.loop_rate_hz));
    CHECK(same(ShownNumber(h, "--phase-margin"), t.phase_margin_deg));
    CHECK(same(ShownNumber(h, "--gain-margin"), t.gain_margin_db));
    CHECK(same(ShownNumber(h, "--corner-ratio"), t.crossover_per_integral_corner));
    CHECK(same(ShownNumber(h, "--u-max"), t.u_max_v));
    CHECK(same(ShownNumber(h, "--step"), b.step_m));
    CHECK(same(ShownNumber(h, "--sine-freq"), b.sine_frequency_hz));
    CHECK(same(ShownNumber(Help({"track"}), "--loop-rate"),
               sysid::StageParameters::Default().rig.sample_rate_hz));
  }
  {
    const std::string h = Help({"excite"});
    CHECK(same(ShownNumber(h, "--on"), sysid::PulseProcedure{}.on_s));
    CHECK(same(ShownNumber(h, "--rate"), sysid::StageParameters{}.rig.sample_rate_hz));
  }
  const sysid::FactsOptions facts;
  CHECK(same(ShownNumber(Help({"stage", "facts"}), "--seed"), static_cast<double>(facts.seed)));
}

TEST_CASE("no help text carries a hand-written default number", "[cli]") {
  // "default 0.2", "(default 1e-7)", "default: 16:32:2", "default the paper's 19000": a copied
  // literal. Descriptions such as "default: the training data's min/max" stay allowed.
  const std::regex literal(R"(default[s]?\s*[:=]?\s*(is\s+)?(the paper's\s+)?[-+.]?[0-9])",
                           std::regex::icase);
  const auto commands = AllCommands();
  REQUIRE(commands.size() > 10);
  for (const auto& command : commands) {
    std::istringstream lines(Help(command));
    for (std::string line; std::getline(lines, line);) {
      INFO("sysid " << command[0] << (command.size() > 1 ? " " + command[1] : "")
                    << " --help: " << line);
      CHECK_FALSE(std::regex_search(line, literal));
    }
  }
}

TEST_CASE("every option that takes a stage preset lists every preset", "[cli]") {
  for (const std::vector<std::string>& command :
       {std::vector<std::string>{"generate", "pulses"}, {"stage", "facts"}, {"track"}}) {
    const std::string help = Help(command);
    for (const std::string& name : sysid::StageParameters::PresetNames()) {
      INFO("sysid " << command[0] << " --help, preset " << name);
      // The whole name: "drive-hysteresis" inside "drive-hysteresis-static" does not count.
      const std::regex word("(^|[^a-z0-9-])" + name + "([^a-z0-9-]|$)");
      CHECK(std::regex_search(help, word));
    }
  }
}

TEST_CASE("every --seed and --threads has its range, whichever command it is on", "[cli]") {
  // Commands and subcommands from the help: CLI11 reads -1 into a uint64 seed as 2^64 - 1 and
  // takes any int as a thread count unless the option checks its range (three did not).
  const auto commands = AllCommands();
  int seeds = 0, threads = 0;
  for (const auto& command : commands) {
    const std::string help = Help(command);
    for (const auto& [flag, bad, rule] :
         {std::tuple<std::string, std::string, std::string>{"--seed", "-1", "not in range 0 to"},
          {"--threads", "1025", "not in range 0 to 1024"}}) {
      if (help.find("  " + flag + " ") == std::string::npos) continue;
      (flag == "--seed" ? seeds : threads) += 1;
      std::vector<std::string> args = command;
      args.insert(args.end(), {flag, bad});
      const auto r = RunCli(args);
      INFO("sysid " << command[0] << (command.size() > 1 ? " " + command[1] : "") << " " << flag
                    << " " << bad << ": " << r.err);
      CHECK(r.exit_code == 1);
      CHECK_THAT(r.err, Catch::Contains(flag + ": Value " + bad + " " + rule));
    }
  }
  CHECK(seeds >= 8);  // the walk found the options (generate, train, sweep, pipeline, ...)
  CHECK(threads >= 8);
}

TEST_CASE("no help text shows CLI11's internals: '{false}' after a flag, an empty 'Excludes:'",
          "[cli]") {
  for (const auto& command : AllCommands()) {
    const std::string help = Help(command);
    INFO(command[0] << (command.size() > 1 ? " " + command[1] : ""));
    CHECK(help.find("{false}") == std::string::npos);
    CHECK(help.find("{true}") == std::string::npos);
    CHECK_FALSE(std::regex_search(help, std::regex("Excludes: *(\n|$)")));
  }
}
