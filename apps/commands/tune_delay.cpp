// sysid tune-delay --model M.json [--tau-min S] [--tau-max S] [--json] [-o MODEL.json] REC.csv...
// The delay tau of the viscous term minimising the simulated-vs-measured velocity error.
#include <fmt/format.h>

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

struct TuneDelayCli {
  std::string model;
  std::vector<std::string> recordings;
  DelayTuningOptions options;  // the flags' defaults are the library's
  bool json = false;
  bool verbose = false;
  std::string output;
  MotionFlags motion;
  FitFractionFlag fit_fraction;
};

void RunTuneDelay(const TuneDelayCli& o) {
  const FrictionModel model = ReadModel(o.model);
  DelayTuningOptions d = o.options;
  o.motion.ApplyTo(d.motion);
  const std::vector<Recording> recs =
      o.fit_fraction.FitPart(o.motion.ReadRecordings(o.recordings), "tune-delay");
  const DelayTuningResult r = TuneDelay(model, recs, d);
  for (const auto& w : r.warnings) std::cerr << "sysid tune-delay: warning: " << w << '\n';
  if (!o.output.empty())
    WriteFileAtomically(o.output, WithGeneratorKey(ModelToJson(r.model) + "\n"));
  std::cout << (o.json ? ToJson(r) : o.verbose ? r.FullReport() : r.BriefReport());
}

void AddTuneDelayCommand(CLI::App& app) {
  auto o = std::make_shared<TuneDelayCli>();
  CLI::App* cmd = app.add_subcommand(
      "tune-delay",
      "Tune the delay tau of the viscous term: minimise sum (v_sim - v_meas)^2 over all samples "
      "(NLopt DIRECT-L then BOBYQA, pulses simulated in parallel); other parameters fixed");
  AddModelAndRecordings(cmd, o->model, "model file (JSON: a1p, a1n, a2p, a2n, a3, tau)",
                        o->recordings);
  DelayTuningOptions& d = o->options;
  const double tau_limit = DelayTuningOptions::kMaxTau_s;
  const CLI::Range tau_range(0.0, tau_limit);
  CLI::Option* tau_min =
      AddFieldOption(cmd, "--tau-min", d, d.tau_min_s, "lower bound of tau [s]")
          ->check(tau_range);
  CLI::Option* tau_max =
      AddFieldOption(cmd, "--tau-max", d, d.tau_max_s,
                     fmt::format("upper bound of tau [s], <= {}", tau_limit))
          ->check(tau_range);
  // The names identify and refine use; the first spellings stay for one release.
  BindField(cmd, AddDeprecatedAlias(cmd, "--min", tau_min, d.tau_min_s, tau_range), d,
            d.tau_min_s);
  BindField(cmd, AddDeprecatedAlias(cmd, "--max", tau_max, d.tau_max_s, tau_range), d,
            d.tau_max_s);
  AddFieldOption(cmd, "--xtol", d, d.x_tolerance_s, "stop when BOBYQA steps are below this [s]")
      ->check(FiniteRange(1e-12, 1.0));
  AddFieldOption(cmd, "--curve", d, d.curve_points,
                 fmt::format("also evaluate the cost on this many evenly spaced tau values "
                             "[count], <= {}; each costs one simulation of the recordings "
                             "(about 10 ms for the bundled pulse test: the maximum takes "
                             "about 15 s)",
                             DelayTuningOptions::kMaxCurvePoints))
      ->check(CLI::Range(0, DelayTuningOptions::kMaxCurvePoints));
  BindField(cmd, AddThreadsOption(cmd, d.threads, "simulation threads [count]; 0 = all cores"), d,
            d.threads);
  o->fit_fraction.Add(cmd);
  AddVerboseFlag(cmd, o->verbose);
  cmd->add_flag("--json", o->json,
                "print tau [s], cost [m^2/s^2], evaluations, curve and the model as JSON");
  AddOutputOption(cmd, o->output, "write the model with tau filled in");
  GuardOutputFiles(cmd, {{&o->output, "-o"}});
  o->motion.Add(cmd, "filter for velocity from x", ToString(d.motion.derivative.method));
  o->motion.Bind(cmd, d, d.motion);
  cmd->callback([o] { RunTuneDelay(*o); });
}

const bool kRegistered = RegisterCommand(31, &AddTuneDelayCommand);

}  // namespace
}  // namespace sysid::cli
