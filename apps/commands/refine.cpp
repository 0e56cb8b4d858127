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
  RefineOptions options;  // the flags' defaults are the library's
  MotionFlags motion;
};

// A refined parameter is "far from its prior" (the value in --model) when it moved by more
// than kPriorRelativeShift of the prior AND by more than kPriorSigmaShift of its reported
// standard error (or the error is unknown): a large move that the fit also calls significant,
// which usually means the given value (a data-sheet a3, a tau at its search bound) and the
// recordings disagree. A zero prior has no scale and is not tested.
constexpr double kPriorRelativeShift = 0.5;  // [1]
constexpr double kPriorSigmaShift = 3.0;      // [standard errors]

double ParameterValue(const FrictionModel& m, const std::string& name) {
  if (name == "a1p") return m.a1p;
  if (name == "a1n") return m.a1n;
  if (name == "a2p") return m.a2p;
  if (name == "a2n") return m.a2n;
  if (name == "a3") return m.a3;
  return m.tau_s;
}

std::vector<std::string> FarFromPriorWarnings(const FrictionModel& prior,
                                              const RefineResult& res) {
  std::vector<std::string> warnings;
  for (size_t i = 0; i < res.names.size(); ++i) {
    const std::string& name = res.names[i];
    const double p0 = ParameterValue(prior, name), p = ParameterValue(res.model, name);
    const double se = res.std_error[static_cast<Eigen::Index>(i)];
    const double shift = std::abs(p - p0);
    if (p0 == 0 || shift <= kPriorRelativeShift * std::abs(p0)) continue;
    if (std::isfinite(se) && shift <= kPriorSigmaShift * se) continue;
    const std::string unit = name == "tau" ? " s" : "";
    std::string w = fmt::format("{} moved from its given value {:.6g}{} to {:.6g}{} ({:+.0f} %", name,
                                p0, unit, p, unit, 100 * (p - p0) / p0);
    w += std::isfinite(se) ? fmt::format(", {:.0f} standard errors of {:.2g}{})", shift / se, se, unit)
                           : std::string(", standard error unknown)");
    w += ": the recordings disagree with the starting model";
    if (name == "a3") w += "; check a3 against the data sheet, or keep it with --fix-a3";
    else if (name == "tau") w += "; check the delay (tune-delay), or keep it with --fix-tau";
    warnings.push_back(w);
  }
  return warnings;
}

void RunRefine(const RefineCli& o) {
  const FrictionModel initial = ReadModel(o.model);
  RefineOptions r = o.options;
  r.refine_a3 = !o.fix_a3;
  r.refine_tau = !o.fix_tau;
  o.motion.ApplyTo(r.motion);
  const std::vector<Recording> recs = o.motion.ReadRecordings(o.recordings);
  const RefineResult res = RefineOutputError(initial, recs, r);
  const FrictionModel& m = res.model;
  nlohmann::ordered_json j = {{"a1p", m.a1p}, {"a1n", m.a1n}, {"a2p", m.a2p},
                              {"a2n", m.a2n}, {"a3", m.a3},   {"tau", m.tau_s}};
  nlohmann::ordered_json se = nlohmann::ordered_json::object();
  for (size_t i = 0; i < res.names.size(); ++i) {
    const double v = res.std_error[static_cast<Eigen::Index>(i)];
    se[res.names[i]] = std::isfinite(v) ? nlohmann::ordered_json(v) : nullptr;
  }
  j["diagnostics"] = {{"method", "output-error"},
                      {"std_error", se},
                      {"initial_cost", res.initial_cost},
                      {"final_cost", res.final_cost},
                      {"rms_error_mps", res.rms_error_mps},
                      {"iterations", res.iterations},
                      {"simulations", res.simulations},
                      {"termination", ToString(res.termination)},
                      {"message", res.message},
                      {"wall_time_s", res.wall_time_s}};
  // Warnings go to stderr and into the diagnostics (so `--json` and the -o file, which stay
  // valid model files, both carry them).
  const std::vector<std::string> warnings = FarFromPriorWarnings(initial, res);
  for (const auto& w : warnings) std::cerr << "sysid refine: warning: " << w << '\n';
  j["diagnostics"]["warnings"] = warnings;
  const std::string rendered = j.dump(2) + "\n";
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
  RefineOptions& r = o->options;
  cmd->add_option("--tau-max", r.tau_max_s, "upper bound of tau [s]")->capture_default_str();
  cmd->add_option("--max-iterations", r.max_iterations,
                  "Levenberg-Marquardt iterations [count]")
      ->capture_default_str();
  cmd->add_option("--threads", r.threads, "simulation threads [count]; 0 = all cores")
      ->capture_default_str();
  cmd->add_option("--min-duration", r.detection.min_duration_s,
                  "pulses (cut points) last at least this long [s]")
      ->capture_default_str();
  o->motion.Add(cmd, "filter for velocity from x", ToString(r.motion.derivative.method));
  cmd->callback([o] { RunRefine(*o); });
}

const bool kRegistered = RegisterCommand(32, &AddRefineCommand);

}  // namespace
}  // namespace sysid::cli
