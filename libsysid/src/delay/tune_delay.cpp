// Delay tuning: NLopt over tau with parallel simulations of the recording's segments inside.
#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>

#include "core/option_rule.hpp"
#include "delay/segments.hpp"
#include "numerics/bounded_search.hpp"
#include "sysid/delay.hpp"
#include "sysid/error.hpp"

namespace sysid {

void DelayTuningOptions::Validate() const {
  auto rule = [](const char* field, double value, const char* what) {
    internal::FailOption("DelayTuningOptions", field, value, what);
  };
  if (!(tau_min_s >= 0) || !std::isfinite(tau_min_s))
    rule("tau_min_s", tau_min_s, "tau_min_s >= 0 [s]");
  if (!(tau_max_s > tau_min_s) || !std::isfinite(tau_max_s))
    rule("tau_max_s", tau_max_s, "tau_max_s > tau_min_s [s]");
  if (tau_max_s > kMaxTau_s) rule("tau_max_s", tau_max_s, fmt::format("tau_max_s <= {} [s]", kMaxTau_s).c_str());
  if (!(x_tolerance_s > 0)) rule("x_tolerance_s", x_tolerance_s, "x_tolerance_s > 0 [s]");
  if (coarse_evaluations < 3)
    rule("coarse_evaluations", coarse_evaluations, "coarse_evaluations >= 3");
  if (max_evaluations < coarse_evaluations)
    rule("max_evaluations", max_evaluations, "max_evaluations >= coarse_evaluations");
  if (curve_points < 0 || curve_points == 1)
    rule("curve_points", curve_points, "curve_points = 0 or >= 2");
  if (curve_points > kMaxCurvePoints)
    rule("curve_points", curve_points,
         fmt::format("curve_points <= {}", kMaxCurvePoints).c_str());
  if (!(sim_rtol > 0 && sim_rtol < 1)) rule("sim_rtol", sim_rtol, "0 < sim_rtol < 1");
  if (!(sim_atol > 0)) rule("sim_atol", sim_atol, "sim_atol > 0");
  if (threads < 0) rule("threads", threads, "threads >= 0");
  motion.Validate();
  segments.Validate();
}

DelayTuningResult TuneDelay(const FrictionModel& model, const std::vector<Recording>& recordings,
                            const DelayTuningOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  options.Validate();
  model.Validate();
  if (recordings.empty()) throw OptionsError("TuneDelay: no recordings given");
  std::vector<MotionSignals> motions;
  for (const auto& r : recordings) motions.push_back(ExtractMotion(r, options.motion));
  const auto segments = internal::MakeSegments(motions, options.segments, options.motion);
  DelayTuningResult result;
  result.segments = static_cast<int>(segments.size());
  result.samples = internal::SegmentSamples(segments);
  const internal::SimulationSettings sim{options.sim_rtol, options.sim_atol, options.threads};
  std::atomic<long> simulations{0};
  std::string first_failure;
  Eigen::VectorXd residuals;
  int successes = 0;
  auto cost = [&](double tau) {
    FrictionModel m = model;
    m.tau_s = tau;
    std::string failure;
    if (!internal::SegmentResiduals(m, segments, sim, &residuals, &failure, &simulations)) {
      if (first_failure.empty()) first_failure = fmt::format("tau = {:.6g} s: {}", tau, failure);
      // The rule `simulate` applies: a model that cannot be simulated is a numerical failure,
      // found at the first evaluation instead of after the whole budget.
      if (successes == 0)
        throw NumericalError("delay tuning: the model cannot be simulated at any tau tried "
                             "(first failure: " + first_failure + ")");
      return std::numeric_limits<double>::infinity();
    }
    ++successes;
    return residuals.squaredNorm();
  };
  internal::ScalarSearchOptions so;
  so.lo = options.tau_min_s;
  so.hi = options.tau_max_s;
  so.coarse_evaluations = options.coarse_evaluations;
  so.max_evaluations = options.max_evaluations;
  so.x_tolerance = options.x_tolerance_s;
  const auto search = internal::MinimizeScalar(cost, so);
  result.tau_s = search.x;
  result.cost = search.f;
  result.evaluations = search.evaluations;
  result.curve = search.evaluated;
  for (int i = 0; i < options.curve_points; ++i) {
    const double tau = options.tau_min_s +
                       (options.tau_max_s - options.tau_min_s) * i / (options.curve_points - 1);
    result.curve.emplace_back(tau, cost(tau));
  }
  std::sort(result.curve.begin(), result.curve.end());
  result.model = model;
  result.model.tau_s = result.tau_s;
  result.simulations = simulations.load();
  if (!std::isfinite(result.cost) || result.cost == std::numeric_limits<double>::max()) {
    result.termination = Termination::kFailure;
    result.message = "every simulation failed; first failure: " + first_failure;
    throw NumericalError("delay tuning: " + result.message);
  }
  // A cost that does not change with tau (a stage at rest, a model that never slides on these
  // recordings) determines no delay: the search's "optimum" is wherever it stopped.
  double lo = HUGE_VAL, hi = -HUGE_VAL;
  for (const auto& [tau, c] : result.curve)
    if (std::isfinite(c)) lo = std::min(lo, c), hi = std::max(hi, c);
  if (!(hi - lo > 1e-12 * hi))
    throw NumericalError(fmt::format(
        "delay tuning: the cost is {:.6g} m^2/s^2 at every tau tried in [{:.6g}, {:.6g}] s: "
        "these recordings do not determine tau (does the stage move in them? does the model "
        "slide at their voltages?)",
        hi, options.tau_min_s, options.tau_max_s));
  result.rms_error_mps = std::sqrt(result.cost / static_cast<double>(result.samples));
  result.termination =
      search.converged ? Termination::kConverged : Termination::kBudgetExhausted;
  result.message = search.message;
  if (!first_failure.empty())
    result.message +=
        "; some simulations failed and were scored +inf (first: " + first_failure + ")";
  // A delay at its search bound is suspicious: the optimum may lie outside, or the data may not
  // determine tau.
  const double near =
      std::max(10 * options.x_tolerance_s, 1e-3 * (options.tau_max_s - options.tau_min_s));
  if (result.tau_s - options.tau_min_s <= near || options.tau_max_s - result.tau_s <= near)
    result.warnings.push_back(fmt::format(
        "tau = {:.6g} s is at the search bound [{:.6g}, {:.6g}] s: the optimum may lie outside "
        "it, or the recordings do not determine tau; widen --tau-min/--tau-max "
        "(tau_min_s/tau_max_s) or check the data",
        result.tau_s, options.tau_min_s, options.tau_max_s));
  result.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

std::string DelayTuningResult::BriefReport() const {
  return fmt::format(
      "delay tuning: tau = {:.6g} s, cost {:.6g} m^2/s^2 (rms {:.4g} m/s), {} evaluations, {} "
      "simulations of {} segments, {:.3g} s; {} ({})\n",
      tau_s, cost, rms_error_mps, evaluations, simulations, segments, wall_time_s,
      ToString(termination), message);
}

}  // namespace sysid
