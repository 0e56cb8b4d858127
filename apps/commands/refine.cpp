// sysid refine --model M.json [--json] [-o MODEL.json] REC.csv...
// Output-error refinement of all parameters (Ceres through the simulator).
#include <fmt/format.h>

#include <cmath>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "cli/common.hpp"
#include "cli/motion_flags.hpp"
#include "cli/registry.hpp"
#include "sysid/error.hpp"
#include "sysid/delay.hpp"
#include "sysid/io.hpp"
#include "sysid/model.hpp"

namespace sysid::cli {
namespace {

struct RefineCli {
  std::string model;
  std::vector<std::string> recordings;
  bool json = false;
  std::string output;
  bool fix_a3 = false;
  bool fix_tau = false;
  double tau_max_s = 0.05;
  int max_iterations = 50;
  int threads = 0;
  double min_duration_s = 0.2;
  MotionFlags motion;
};

void RunRefine(const RefineCli& o) {
  const FrictionModel initial = ReadModel(o.model);
  RefineOptions r;
  r.refine_a3 = !o.fix_a3;
  r.refine_tau = !o.fix_tau;
  r.tau_max_s = o.tau_max_s;
  r.max_iterations = o.max_iterations;
  r.threads = o.threads;
  r.detection.min_duration_s = o.min_duration_s;
  o.motion.ApplyTo(r.motion);
  const std::vector<Recording> recs = o.motion.ReadRecordings(o.recordings);
  const RefineResult res = RefineOutputError(initial, recs, r);
  const std::string rendered = ToJson(res);
  if (!o.output.empty()) WriteFileAtomically(o.output, rendered);
  if (o.json)
    std::cout << rendered;
  else
    std::cout << res.BriefReport();
}

void AddRefineCommand(CLI::App& app) {
  auto o = std::make_shared<RefineCli>();
  CLI::App* cmd = app.add_subcommand(
      "refine",
      "Refine a1p, a1n, a2p, a2n, a3 and tau by minimising sum (v_sim - v_meas)^2 with Ceres "
      "(numeric differentiation through the simulator), starting from --model");
  cmd->add_option("--model", o->model, "starting model file (JSON)")
      ->required()
      ->type_name("M.json");
  cmd->add_option("recordings", o->recordings,
                  "recording CSVs: t [s], u [V] and x [m] or a velocity column [m/s]")
      ->required()
      ->type_name("REC.csv");
  cmd->add_flag("--json", o->json, "print the refined model plus diagnostics as JSON");
  AddOutputOption(cmd, o->output, "write the refined model file (same JSON as --json)");
  cmd->add_flag("--fix-a3", o->fix_a3, "keep a3 at the starting value");
  cmd->add_flag("--fix-tau", o->fix_tau, "keep tau at the starting value");
  cmd->add_option("--tau-max", o->tau_max_s, "upper bound of tau [s], default 0.05");
  cmd->add_option("--max-iterations", o->max_iterations,
                  "Levenberg-Marquardt iterations [count], default 50");
  cmd->add_option("--threads", o->threads, "simulation threads [count], default all cores");
  cmd->add_option("--min-duration", o->min_duration_s,
                  "pulses (cut points) last at least this long [s], default 0.2");
  o->motion.Add(cmd, "filter for velocity from x: central (default), butterworth, savgol");
  cmd->callback([o] { RunRefine(*o); });
}

const bool kRegistered = RegisterCommand(32, &AddRefineCommand);

}  // namespace
}  // namespace sysid::cli
