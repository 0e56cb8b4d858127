// sysid refine --model M.json [--json] [-o MODEL.json] REC.csv...
// Output-error refinement of all parameters (Ceres through the simulator).

#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "cli/common.hpp"
#include "cli/field_flag.hpp"
#include "cli/fit_fraction_flag.hpp"
#include "cli/motion_flags.hpp"
#include "cli/output_file.hpp"
#include "cli/registry.hpp"
#include "sysid/delay.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"
#include "sysid/io_output.hpp"
#include "sysid/model.hpp"

namespace sysid::cli {
namespace {

struct RefineCli {
  std::string model;
  std::vector<std::string> recordings;
  bool json = false;
  bool verbose = false;
  std::string output;
  bool fix_a3 = false;
  bool fix_tau = false;
  RefineOptions options;  // the flags' defaults are the library's
  MotionFlags motion;
  FitFractionFlag fit_fraction;
};

void RunRefine(const RefineCli& o) {
  const FrictionModel initial = ReadModel(o.model);
  RefineOptions r = o.options;
  r.refine_a3 = !o.fix_a3;
  r.refine_tau = !o.fix_tau;
  o.motion.ApplyTo(r.motion);
  const std::vector<Recording> recs =
      o.fit_fraction.FitPart(o.motion.ReadRecordings(o.recordings), "refine");
  const RefineResult res = RefineOutputError(initial, recs, r);
  for (const auto& w : res.warnings) std::cerr << "sysid refine: warning: " << w << '\n';
  const std::string rendered = ToJson(res);
  if (!o.output.empty()) WriteFileAtomically(o.output, WithGeneratorKey(rendered));
  if (o.json)
    std::cout << rendered;
  else
    std::cout << (o.verbose ? res.FullReport() : res.BriefReport());
}

void AddRefineCommand(CLI::App& app) {
  auto o = std::make_shared<RefineCli>();
  CLI::App* cmd = app.add_subcommand(
      "refine",
      "Refine a1p, a1n, a2p, a2n, a3 and tau by minimising sum (v_sim - v_meas)^2 with Ceres "
      "(numeric differentiation through the simulator), starting from --model");
  AddModelAndRecordings(cmd, o->model, "starting model file (JSON)", o->recordings);
  cmd->add_flag("--json", o->json, "print the refined model plus diagnostics as JSON");
  AddVerboseFlag(cmd, o->verbose);
  AddOutputOption(cmd, o->output, "write the refined model file (same JSON as --json)");
  GuardOutputFiles(cmd, {{&o->output, "-o"}});
  RefineOptions& r = o->options;
  // --fix-a3 and --fix-tau set refine_a3 and refine_tau to their negation when the command runs.
  BindField(cmd, cmd->add_flag("--fix-a3", o->fix_a3, "keep a3 at the starting value"), r,
            r.refine_a3);
  BindField(cmd, cmd->add_flag("--fix-tau", o->fix_tau, "keep tau at the starting value"), r,
            r.refine_tau);
  AddFieldOption(cmd, "--tau-max", r, r.tau_max_s, "upper bound of tau [s]");
  AddFieldOption(cmd, "--max-iterations", r, r.max_iterations,
                 "Levenberg-Marquardt iterations [count]");
  BindField(cmd, AddThreadsOption(cmd, r.threads, "simulation threads [count]; 0 = all cores"), r,
            r.threads);
  o->fit_fraction.Add(cmd);
  AddFieldOption(cmd, "--min-duration", r, r.detection.min_duration_s,
                 "pulses (cut points) last at least this long [s]");
  o->motion.Add(cmd, "filter for velocity from x", ToString(r.motion.derivative.method));
  o->motion.Bind(cmd, r, r.motion);
  cmd->callback([o] { RunRefine(*o); });
}

const bool kRegistered = RegisterCommand(32, &AddRefineCommand);

}  // namespace
}  // namespace sysid::cli
