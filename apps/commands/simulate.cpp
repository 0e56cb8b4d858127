// sysid simulate: drive the delayed friction model with an input and write t,u,x,v,a.
//   sysid simulate --model M.json --input U.csv [--hold zoh|linear] --t-end T --dt D -o OUT.csv
//                  [--events E.csv] [--json]
//   input shortcuts: --pulses 1.6,-2.3 [--pulse-on 0.4 --pulse-off 0.6 --pulse-repeats 5]
//                    --waveform paper-pulses|paper-ladder|paper-triangle|paper-sine
#include "sysid/simulate.hpp"

#include <fmt/format.h>

#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "cli/common.hpp"
#include "cli/output_file.hpp"
#include "cli/input_flags.hpp"
#include "cli/registry.hpp"
#include "sysid/error.hpp"
#include "sysid/input.hpp"
#include "sysid/io.hpp"
#include "sysid/io_containers.hpp"
#include "sysid/model.hpp"
#include "sysid/io_output.hpp"

namespace sysid::cli {
namespace {

struct SimulateCliOptions {
  std::string model_path;
  bool paper_model = false;
  InputFlags input;
  double t_end_s = 0;  // 0: the input's natural length
  std::string output, events_path;
  bool json = false;
  SimulationOptions sim;
  std::string method;  // set from sim.method
};

void RunSimulate(SimulateCliOptions o) {
  if (o.model_path.empty() == !o.paper_model)
    throw OptionsError("give exactly one model: --model M.json or --paper-model");
  const FrictionModel model = o.paper_model ? FrictionModel::Paper() : ReadModel(o.model_path);
  const NamedWaveform input = o.input.Choose();
  SimulationOptions sim = o.sim;
  sim.method = ParseIntegratorMethod(o.method);
  sim.t0_s = 0.0;
  sim.t_end_s = o.t_end_s > 0 ? o.t_end_s : input.duration_s;
  if (!(sim.t_end_s > 0))
    throw OptionsError(
        "", "--t-end", fmt::format("{}", sim.t_end_s),
        fmt::format("t_end > 0 (the input ends at {} s; give --t-end)", input.duration_s));
  const SimulationResult r = Simulate(model, *input.signal, sim);
  const SimulationSummary& s = r.summary;
  if (!s.IsSolutionUsable())
    throw NumericalError(fmt::format("simulation failed ({}): {}", s.cvode_flag, s.message));

  Recording out = TrajectoryRecording(r, model, input.description, sim);
  out.source = o.output.empty() ? "stdout" : o.output;
  // Everything is computed before anything is written: no partial output on error.
  if (!o.events_path.empty())
    WriteFileAtomically(o.events_path, GeneratorLine() + EventsToCsv(r.events));
  if (!o.output.empty()) WriteRecordingByExtension(o.output, out);

  if (o.json) {
    std::cout << SimulationReportJson(r, model, input.description, sim, o.output, o.events_path);
  } else if (o.output.empty()) {
    std::cout << FormatRecording(out);
  } else {
    std::cout << fmt::format("wrote {} ({} samples, {} events); {}\n", o.output,
                             r.trajectory.t_s.size(), r.events.size(), s.BriefReport());
  }
}

void AddSimulateCommand(CLI::App& app) {
  auto o = std::make_shared<SimulateCliOptions>();
  o->method = ToString(o->sim.method);
  CLI::App* cmd = app.add_subcommand(
      "simulate",
      "Simulate the delayed friction model x'' = -a1 v(t-tau) - a2 sgn(v) + a3 u with "
      "stick-slip (CVODE); writes t [s], u [V], x [m], v [m/s], a [m/s^2]");
  auto* model = cmd->add_option("--model", o->model_path,
                                "model JSON {a1p [1/s], a1n [1/s], a2p [m/s^2], a2n [m/s^2], "
                                "a3 [m/(s^2 V)], tau [s]}")
                    ->type_name("M.json");
  cmd->add_flag("--paper-model", o->paper_model,
                "use the paper's identified model instead of --model")
      ->excludes(model);
  o->input.Add(cmd);
  cmd->add_option("--t-end", o->t_end_s,
                  "end time [s] (default: the input's end: last table row, end of the pulse "
                  "train or of the waveform)")
      ->check(PositiveNumber());
  cmd->add_option("--dt", o->sim.dt_out_s, "output sample interval [s]")
      ->check(PositiveNumber())
      ->capture_default_str();
  AddOutputOption(cmd, o->output,
                  "trajectory CSV t,u,x,v,a, or MAT v5 when FILE ends in .mat (default: stdout)");
  GuardOutputFiles(cmd, {{&o->output, "-o"}, {&o->events_path, "--events"}});
  cmd->add_option("--events", o->events_path,
                  "event log CSV t [s], kind (stick, slip+, slip-, reverse, a1-switch)")
      ->type_name("E.csv");
  cmd->add_flag("--json", o->json,
                "print a JSON summary (events, steps, rhs evaluations, wall time) instead of "
                "the trajectory");
  cmd->add_option("--method", o->method, "CVODE method: adams (nonstiff) or bdf")
      ->check(CLI::IsMember({"adams", "bdf"}))
      ->capture_default_str();
  cmd->add_option("--rtol", o->sim.rtol, "relative tolerance [dimensionless]")
      ->check(PositiveNumber())
      ->capture_default_str();
  cmd->add_option("--atol", o->sim.atol, "absolute tolerance [m, m/s]")
      ->check(PositiveNumber())
      ->capture_default_str();
  cmd->add_option("--x0", o->sim.x0_m, "initial position [m]")->capture_default_str();
  cmd->add_option("--v0", o->sim.v0_mps, "initial velocity [m/s]")->capture_default_str();
  cmd->add_option("--history-v", o->sim.history_v_mps, "constant velocity before t = 0 [m/s]")
      ->capture_default_str();
  cmd->callback([o] { RunSimulate(*o); });
}

const bool kRegistered = RegisterCommand(20, &AddSimulateCommand);

}  // namespace
}  // namespace sysid::cli
