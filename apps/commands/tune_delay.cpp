// sysid tune-delay --model M.json [--min S] [--max S] [--json] [-o MODEL.json] REC.csv...
// The delay tau of the viscous term minimising the simulated-vs-measured velocity error.
#include <fmt/format.h>

#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "cli/common.hpp"
#include "cli/motion_flags.hpp"
#include "cli/registry.hpp"
#include "sysid/delay.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"
#include "sysid/model.hpp"

namespace sysid::cli {
namespace {

struct TuneDelayCli {
  std::string model;
  std::vector<std::string> recordings;
  double tau_min_s = 0.0, tau_max_s = 0.02, x_tolerance_s = 1e-7;
  int curve_points = 0;
  int threads = 0;
  bool json = false;
  std::string output;
  MotionFlags motion;
};

void RunTuneDelay(const TuneDelayCli& o) {
  const FrictionModel model = ReadModel(o.model);
  DelayTuningOptions d;
  d.tau_min_s = o.tau_min_s;
  d.tau_max_s = o.tau_max_s;
  d.x_tolerance_s = o.x_tolerance_s;
  d.curve_points = o.curve_points;
  d.threads = o.threads;
  o.motion.ApplyTo(d.motion);
  const std::vector<Recording> recs = o.motion.ReadRecordings(o.recordings);
  const DelayTuningResult r = TuneDelay(model, recs, d);
  for (const auto& w : r.warnings) std::cerr << "sysid tune-delay: warning: " << w << '\n';
  if (!o.output.empty()) WriteFileAtomically(o.output, ModelToJson(r.model) + "\n");
  std::cout << (o.json ? ToJson(r) : r.BriefReport());
}

void AddTuneDelayCommand(CLI::App& app) {
  auto o = std::make_shared<TuneDelayCli>();
  CLI::App* cmd = app.add_subcommand(
      "tune-delay",
      "Tune the delay tau of the viscous term: minimise sum (v_sim - v_meas)^2 over all samples "
      "(NLopt DIRECT-L then BOBYQA, pulses simulated in parallel); other parameters fixed");
  cmd->add_option("--model", o->model, "model file (JSON: a1p, a1n, a2p, a2n, a3, tau)")
      ->required()
      ->type_name("M.json");
  cmd->add_option("recordings", o->recordings,
                  "recording CSVs: t [s], u [V] and x [m] or a velocity column [m/s]")
      ->required()
      ->type_name("REC.csv");
  cmd->add_option("--min", o->tau_min_s, "lower bound of tau [s], default 0")
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--max", o->tau_max_s, "upper bound of tau [s], default 0.02 (at most 1 s)")
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--xtol", o->x_tolerance_s,
                  "stop when BOBYQA steps are below this [s], "
                  "default 1e-7")
      ->check(CLI::Range(1e-12, 1.0));
  cmd->add_option("--curve", o->curve_points,
                  "also evaluate the cost on this many evenly spaced tau values [count], "
                  "default 0")
      ->check(CLI::Range(0, 10000));
  cmd->add_option("--threads", o->threads, "simulation threads [count], default all cores")
      ->check(CLI::Range(0, 1024));
  cmd->add_flag("--json", o->json,
                "print tau [s], cost [m^2/s^2], evaluations, curve and the model as JSON");
  AddOutputOption(cmd, o->output, "write the model with tau filled in");
  o->motion.Add(cmd, "filter for velocity from x: central (default), butterworth, savgol");
  cmd->callback([o] { RunTuneDelay(*o); });
}

const bool kRegistered = RegisterCommand(31, &AddTuneDelayCommand);

}  // namespace
}  // namespace sysid::cli
