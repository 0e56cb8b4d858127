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
#include "cli/motion_flags.hpp"
#include "cli/registry.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"
#include "sysid/model.hpp"

namespace sysid::cli {
namespace {

struct IdentifyCli {
  std::vector<std::string> recordings;
  std::string method = "pulse";
  std::string table;
  std::string output;
  bool json = false;
  double a3 = 6.0;
  MotionFlags motion;  // derivative empty: the method's default
  // pulse
  double min_duration_s = 0.2;
  double window_fraction = 0.5;
  double settle_tolerance = 0.02;
  double pulse_min_speed = 1e-4;
  double max_speed = 0;  // 0: no limit
  // trajectory
  double tau_s = 0;
  bool tune_delay = false;
  double tau_min_s = 0, tau_max_s = 0.02;
  int decimate = 1;
  bool offset = false;
  bool symmetric_viscous = false;
  double traj_min_speed = 1e-3;
};

MotionOptions Motion(const IdentifyCli& o, MotionOptions m) {
  o.motion.ApplyTo(m);
  return m;
}

std::vector<Recording> ReadAll(const IdentifyCli& o) {
  return o.motion.ReadRecordings(o.recordings);
}

void RunIdentify(const IdentifyCli& o) {
  std::string rendered, text;
  if (o.method == "pulse") {
    PulseIdentificationResult r;
    if (!o.table.empty()) {
      if (!o.recordings.empty())
        throw OptionsError("--table: give either a pulse table or recordings, not both");
      r = FitPulseTable(ReadPulseTable(o.table), {o.a3});
    } else {
      if (o.recordings.empty())
        throw OptionsError("identify: give recordings (REC.csv...) or --table T.csv");
      PulseIdentificationOptions po;
      po.motion = Motion(o, po.motion);
      po.detection.min_duration_s = o.min_duration_s;
      po.plateau.window_fraction = o.window_fraction;
      po.plateau.settle_tolerance = o.settle_tolerance;
      po.plateau.min_speed_mps = o.pulse_min_speed;
      if (o.max_speed > 0) po.plateau.max_speed_mps = o.max_speed;
      po.fit.a3 = o.a3;
      r = IdentifyFromPulses(ReadAll(o), po);
    }
    rendered = ToJson(r);
    Table table(
        {"source", "t_start [s]", "duration [s]", "u [V]", "v [m/s]", "+- [m/s]", "status"});
    for (const auto& e : r.pulses)
      table.AddRow({e.pulse.source, Num(e.pulse.t_start_s), Num(e.pulse.duration_s),
                    Num(e.pulse.amplitude_v), Num(e.v_mps), Num(e.v_stderr_mps, 2),
                    e.usable() ? "ok" : ToString(e.status) + ": " + e.reason});
    text = r.BriefReport() + (r.pulses.empty() ? "" : "\n" + table.Render());
  } else {
    if (o.recordings.empty()) throw OptionsError("identify --method trajectory: no recordings");
    if (!o.table.empty()) throw OptionsError("--table applies to --method pulse only");
    TrajectoryOptions to;
    to.motion = Motion(o, to.motion);
    to.tau_s = o.tau_s;
    to.tune_delay = o.tune_delay;
    to.tau_min_s = o.tau_min_s;
    to.tau_max_s = o.tau_max_s;
    to.decimation = o.decimate;
    to.offset = o.offset;
    to.symmetric_viscous = o.symmetric_viscous;
    to.min_speed_mps = o.traj_min_speed;
    const auto r = IdentifyFromTrajectory(ReadAll(o), to);
    rendered = ToJson(r);
    text = r.BriefReport();
  }
  if (!o.output.empty()) WriteFileAtomically(o.output, rendered);
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
  cmd->add_option("recordings", o->recordings,
                  "recording CSVs: t [s], u [V] and x [m] or a velocity column [m/s]")
      ->type_name("REC.csv");
  cmd->add_option("--method", o->method, "pulse (default) or trajectory")
      ->check(CLI::IsMember({"pulse", "trajectory"}));
  cmd->add_option("--a3", o->a3, "actuator gain for --method pulse [m/(s^2 V)], default 6");
  cmd->add_option("--table", o->table,
                  "pulse table CSV with columns u [V] and v [m/s] instead of recordings")
      ->type_name("T.csv");
  cmd->add_flag("--json", o->json,
                "print the model (a1p, a1n, a2p, a2n, a3, tau) plus a diagnostics object as JSON");
  AddOutputOption(cmd, o->output, "write the model file (same JSON as --json)");
  o->motion.Add(cmd,
                "velocity filter: central (pulse default), butterworth (trajectory default), "
                "savgol");
  cmd->add_option("--min-duration", o->min_duration_s, "pulse: shortest pulse [s], default 0.2")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--window-fraction", o->window_fraction,
                  "pulse: plateau = this last fraction of each pulse [dimensionless], default "
                  "0.5");
  cmd->add_option("--settle-tolerance", o->settle_tolerance,
                  "pulse: allowed drift across the plateau relative to |v| [dimensionless], "
                  "default 0.02");
  cmd->add_option("--pulse-min-speed", o->pulse_min_speed,
                  "pulse: |v| below this is stuck [m/s], default 1e-4");
  cmd->add_option("--max-speed", o->max_speed,
                  "pulse: stage velocity limit [m/s]; pulses reaching it are excluded (default "
                  "none)");
  cmd->add_option("--tau", o->tau_s, "trajectory: delay of the viscous term [s], default 0");
  cmd->add_flag("--tune-delay", o->tune_delay,
                "trajectory: choose tau in [--tau-min, --tau-max] minimising the residual");
  cmd->add_option("--tau-min", o->tau_min_s, "trajectory: lower tau bound [s], default 0");
  cmd->add_option("--tau-max", o->tau_max_s, "trajectory: upper tau bound [s], default 0.02");
  cmd->add_option("--decimate", o->decimate,
                  "trajectory: keep every n-th sample after anti-alias filtering [samples], "
                  "default 1")
      ->check(CLI::PositiveNumber);
  cmd->add_flag("--offset", o->offset,
                "trajectory: add a constant offset c0 [m/s^2]; Coulomb becomes symmetric a2");
  cmd->add_flag("--symmetric-viscous", o->symmetric_viscous,
                "trajectory: one viscous coefficient a1 [1/s] for both directions");
  cmd->add_option("--min-speed", o->traj_min_speed,
                  "trajectory: samples with |v| below this are excluded [m/s], default 1e-3");
  cmd->callback([o] { RunIdentify(*o); });
}

const bool kRegistered = RegisterCommand(30, &AddIdentifyCommand);

}  // namespace
}  // namespace sysid::cli
