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
#include "cli/registry.hpp"
#include "sysid/error.hpp"
#include "sysid/input.hpp"
#include "sysid/io.hpp"
#include "sysid/model.hpp"

namespace sysid::cli {
namespace {

struct SimulateCliOptions {
  std::string model_path;
  bool paper_model = false;
  std::string input_path;
  std::string hold = "zoh";
  std::vector<double> pulses;
  PulseTrainSpec pulse_train;  // on, off, repeats, start: the flags' defaults are the library's
  std::string waveform;
  double t_end_s = 0;  // 0: the input's natural length
  std::string output, events_path;
  bool json = false;
  SimulationOptions sim;
  std::string method;  // set from sim.method
};

NamedWaveform ChooseInput(const SimulateCliOptions& o) {
  const int given = !o.input_path.empty() + !o.pulses.empty() + !o.waveform.empty();
  if (given != 1)
    throw OptionsError(
        "give exactly one input: --input U.csv, --pulses A[,A...] or --waveform "
        "NAME");
  if (!o.input_path.empty()) return ReadInputWaveform(o.input_path, ParseInputHold(o.hold));
  if (!o.pulses.empty()) {
    PulseTrainSpec spec = o.pulse_train;
    spec.amplitudes_v = o.pulses;
    return PulseTrainWaveform(spec);
  }
  NamedWaveform w = MakeNamedWaveform(o.waveform);
  w.description = w.name + ": " + w.description;
  return w;
}

std::string EventsCsv(const std::vector<SimulationEvent>& events) {
  std::string text = "t,kind\n";
  for (const auto& e : events) text += fmt::format("{:.17g},{}\n", e.t_s, ToString(e.kind));
  return text;
}

void RunSimulate(SimulateCliOptions o) {
  if (o.model_path.empty() == !o.paper_model)
    throw OptionsError("give exactly one model: --model M.json or --paper-model");
  const FrictionModel model = o.paper_model ? FrictionModel::Paper() : ReadModel(o.model_path);
  const NamedWaveform input = ChooseInput(o);
  SimulationOptions sim = o.sim;
  sim.method = ParseIntegratorMethod(o.method);
  sim.t0_s = 0.0;
  sim.t_end_s = o.t_end_s > 0 ? o.t_end_s : input.duration_s;
  if (!(sim.t_end_s > 0))
    throw OptionsError(
        fmt::format("--t-end = {}. Violated constraint: t_end > 0 (the input "
                    "ends at {} s; give --t-end)",
                    sim.t_end_s, input.duration_s));
  const SimulationResult r = Simulate(model, *input.signal, sim);
  const SimulationSummary& s = r.summary;
  if (!s.IsSolutionUsable())
    throw NumericalError(fmt::format("simulation failed ({}): {}", s.cvode_flag, s.message));

  Recording out;
  out.source = o.output.empty() ? "stdout" : o.output;
  const nlohmann::json model_json = nlohmann::json::parse(ModelToJson(model, -1));
  out.metadata = {{"model", model_json.dump()},
                  {"input", input.description},
                  {"simulator", fmt::format("CVODE {} rtol {} atol {}", ToString(sim.method),
                                            sim.rtol, sim.atol)}};
  out.SetColumn("t", r.trajectory.t_s);
  out.SetColumn("u", r.trajectory.u_v);
  out.SetColumn("x", r.trajectory.x_m);
  out.SetColumn("v", r.trajectory.v_mps);
  out.SetColumn("a", r.trajectory.a_mps2);
  // Everything is computed before anything is written: no partial output on error.
  if (!o.events_path.empty()) WriteFileAtomically(o.events_path, EventsCsv(r.events));
  if (!o.output.empty()) WriteRecording(o.output, out);

  if (o.json) {
    nlohmann::ordered_json j;
    j["model"] = model_json;
    j["input"] = input.description;
    j["t_end_s"] = sim.t_end_s;
    const auto run = nlohmann::ordered_json::parse(ToJson(r, sim));
    j["samples"] = run["samples"];
    j["output"] = o.output.empty() ? nullptr : nlohmann::ordered_json(o.output);
    j["events_file"] = o.events_path.empty() ? nullptr : nlohmann::ordered_json(o.events_path);
    j["events"] = run["events"];
    j["summary"] = run["summary"];
    std::cout << j.dump(2) << '\n';
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
  auto* input =
      cmd->add_option("--input", o->input_path, "input table CSV with columns t [s], u [V]")
          ->type_name("U.csv");
  cmd->add_option("--hold", o->hold,
                  "how the table holds between rows: zoh (u_k on [t_k, t_k+1)) or linear")
      ->check(CLI::IsMember({"zoh", "linear"}))
      ->capture_default_str();
  auto* pulses =
      cmd->add_option("--pulses", o->pulses, "pulse-train amplitudes [V], in order, e.g. 1.6,-2.3")
          ->delimiter(',')
          ->excludes(input);
  PulseTrainSpec& train = o->pulse_train;
  cmd->add_option("--pulse-on", train.on_s, "pulse length [s]")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--pulse-off", train.off_s, "rest after each pulse [s]")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_option("--pulse-repeats", train.repeats, "repeats of the amplitude list [count]")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--pulse-start", train.start_s, "time of the first pulse [s]")
      ->capture_default_str();
  std::string names;
  for (const auto& n : NamedWaveformNames()) names += (names.empty() ? "" : ", ") + n;
  cmd->add_option("--waveform", o->waveform, "a named test waveform of the paper: " + names)
      ->excludes(input)
      ->excludes(pulses);
  cmd->add_option("--t-end", o->t_end_s,
                  "end time [s] (default: the input's end: last table row, end of the pulse "
                  "train or of the waveform)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--dt", o->sim.dt_out_s, "output sample interval [s]")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  AddOutputOption(cmd, o->output, "trajectory CSV t,u,x,v,a (default: stdout)");
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
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--atol", o->sim.atol, "absolute tolerance [m, m/s]")
      ->check(CLI::PositiveNumber)
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
