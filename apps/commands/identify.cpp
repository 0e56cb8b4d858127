// sysid identify [--method pulse|trajectory] [--a3 A] [--table T.csv] [--json] [-o MODEL.json]
//                REC.csv...
// Pulse-test least squares (the paper) or trajectory (inverse-model) least squares. With --json
// the printed object is itself a valid model file plus a "diagnostics" object.
#include "sysid/identify.hpp"

#include <fmt/format.h>

#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "cli/common.hpp"
#include "cli/field_flag.hpp"
#include "cli/output_file.hpp"
#include "cli/fit_fraction_flag.hpp"
#include "cli/motion_flags.hpp"
#include "cli/registry.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"
#include "sysid/model.hpp"
#include "sysid/io_output.hpp"

namespace sysid::cli {
namespace {

struct IdentifyCli {
  std::vector<std::string> recordings;
  std::string method = "pulse";
  std::string table;
  std::string output;
  bool json = false;
  bool verbose = false;
  MotionFlags motion;  // derivative empty: the method's default
  FitFractionFlag fit_fraction;
  // The flags' defaults are the library's.
  PulseIdentificationOptions pulse;
  double max_speed = 0;  // [m/s] 0: no limit (the library's default, infinity)
  TrajectoryOptions trajectory;
};

void RunIdentify(const IdentifyCli& o) {
  std::string rendered, text;
  if (o.method == "pulse") {
    PulseIdentificationResult r;
    if (!o.table.empty()) {
      if (!o.recordings.empty())
        throw OptionsError("--table: give either a pulse table or recordings, not both");
      r = FitPulseTable(ReadPulseTable(o.table, o.motion.recording.Mapping()), o.pulse.fit);
    } else {
      if (o.recordings.empty())
        throw OptionsError("identify: give recordings (REC.csv...) or --table T.csv");
      PulseIdentificationOptions po = o.pulse;
      o.motion.ApplyTo(po.motion);
      if (o.max_speed > 0) po.plateau.max_speed_mps = o.max_speed;
      r = IdentifyFromPulses(
          o.fit_fraction.FitPart(o.motion.ReadRecordings(o.recordings), "identify"), po);
    }
    if (!r.a3_given)
      std::cerr << "sysid identify: warning: " << DescribeA3(r.model.a3, false)
                << "; a1 and a2 scale with it\n";
    rendered = ToJson(r);
    Table table(
        {"source", "t_start [s]", "duration [s]", "u [V]", "v [m/s]", "+- [m/s]", "status"});
    for (const auto& e : r.pulses)
      table.AddRow({e.pulse.source, Num(e.pulse.t_start_s), Num(e.pulse.duration_s),
                    Num(e.pulse.amplitude_v), Num(e.v_mps), Num(e.v_stderr_mps, 2),
                    e.usable() ? "ok" : ToString(e.status) + ": " + e.reason});
    text = o.verbose ? r.FullReport() : r.BriefReport() + (r.pulses.empty() ? "" : "\n" + table.Render());
  } else {
    if (o.recordings.empty()) throw OptionsError("identify --method trajectory: no recordings");
    if (!o.table.empty()) throw OptionsError("--table applies to --method pulse only");
    TrajectoryOptions to = o.trajectory;
    o.motion.ApplyTo(to.motion);
    const auto r = IdentifyFromTrajectory(
        o.fit_fraction.FitPart(o.motion.ReadRecordings(o.recordings), "identify"), to);
    rendered = ToJson(r);
    text = o.verbose ? r.FullReport() : r.BriefReport();
  }
  if (!o.output.empty()) WriteFileAtomically(o.output, WithGeneratorKey(rendered));
  if (o.json)
    std::cout << rendered;
  else
    std::cout << text;
}

void AddIdentifyCommand(CLI::App& app) {
  auto o = std::make_shared<IdentifyCli>();
  CLI::App* cmd = app.add_subcommand(
      "identify",
      "Identify the friction model x'' = -a1 v(t-tau) - a2 sgn(v) + a3 u from pulse recordings "
      "(the paper's steady-state least squares) or any excited recording (trajectory least "
      "squares, identifies a3 too). Exit 3 when parameters are not identifiable.");
  AddMotionRecordings(cmd, o->recordings);
  cmd->add_option("--method", o->method, "pulse or trajectory")
      ->check(CLI::IsMember({"pulse", "trajectory"}))
      ->capture_default_str();
  CLI::Option* a3 =
      AddFieldOption(cmd, "--a3", o->pulse, o->pulse.fit.a3,
                     "actuator gain for --method pulse [m/(s^2 V)]; the default is the "
                     "paper's HR-8 data-sheet value, not your stage's");
  a3->each([o](const std::string&) { o->pulse.fit.a3_given = true; });
  cmd->add_option("--table", o->table,
                  "pulse table CSV with columns u [V] and v [m/s] instead of recordings")
      ->type_name("T.csv");
  AddVerboseFlag(cmd, o->verbose);
  cmd->add_flag("--json", o->json,
                "print the model (a1p, a1n, a2p, a2n, a3, tau) plus a diagnostics object as JSON");
  AddOutputOption(cmd, o->output, "write the model file (same JSON as --json)");
  GuardOutputFiles(cmd, {{&o->output, "-o"}});
  o->motion.Add(cmd, "velocity filter",
                ToString(PulseIdentificationOptions{}.motion.derivative.method) + " (pulse), " +
                    ToString(TrajectoryOptions{}.motion.derivative.method) + " (trajectory)");
  o->motion.Bind(cmd, o->pulse, o->pulse.motion);
  o->motion.Bind(cmd, o->trajectory, o->trajectory.motion);
  o->fit_fraction.Add(cmd);
  auto& pulse = o->pulse;
  AddFieldOption(cmd, "--min-duration", pulse, pulse.detection.min_duration_s,
                 "pulse: shortest pulse [s]")
      ->check(PositiveNumber());
  AddFieldOption(cmd, "--window-fraction", pulse, pulse.plateau.window_fraction,
                 "pulse: plateau = this last fraction of each pulse [dimensionless]");
  AddFieldOption(cmd, "--settle-tolerance", pulse, pulse.plateau.settle_tolerance,
                 "pulse: allowed drift across the plateau relative to |v| [dimensionless]");
  AddFieldOption(cmd, "--pulse-min-speed", pulse, pulse.plateau.min_speed_mps,
                 "pulse: |v| below this is stuck [m/s]");
  BindField(cmd,
            cmd->add_option("--max-speed", o->max_speed,
                            "pulse: stage velocity limit [m/s]; pulses reaching it are "
                            "excluded; 0 = no limit")
                ->capture_default_str(),
            pulse, pulse.plateau.max_speed_mps);
  auto& traj = o->trajectory;
  AddFieldOption(cmd, "--tau", traj, traj.tau_s, "trajectory: delay of the viscous term [s]");
  AddFieldFlag(cmd, "--tune-delay", traj, traj.tune_delay,
               "trajectory: choose tau in [--tau-min, --tau-max] minimising the residual");
  AddFieldOption(cmd, "--tau-min", traj, traj.tau_min_s, "trajectory: lower tau bound [s]");
  AddFieldOption(cmd, "--tau-max", traj, traj.tau_max_s, "trajectory: upper tau bound [s]");
  AddFieldOption(cmd, "--decimate", traj, traj.decimation,
                 "trajectory: keep every n-th sample after anti-alias filtering [samples]")
      ->check(PositiveNumber());
  AddFieldFlag(cmd, "--offset", traj, traj.offset,
               "trajectory: add a constant offset c0 [m/s^2]; Coulomb becomes symmetric a2");
  AddFieldFlag(cmd, "--symmetric-viscous", traj, traj.symmetric_viscous,
               "trajectory: one viscous coefficient a1 [1/s] for both directions");
  AddFieldOption(cmd, "--min-speed", traj, traj.min_speed_mps,
                 "trajectory: samples with |v| below this are excluded [m/s]");
  cmd->callback([o] { RunIdentify(*o); });
}

const bool kRegistered = RegisterCommand(30, &AddIdentifyCommand);

}  // namespace
}  // namespace sysid::cli
