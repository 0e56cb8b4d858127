// How an iterative computation stopped: one vocabulary for every solver result (delay tuning,
// refinement, network training, simulation), after Ceres' TerminationType. The result beside
// it carries the detail in words (`message`) and, where an algorithm has several stopping
// rules (network training), the rule that fired.
#ifndef SYSID_TERMINATION_HPP_
#define SYSID_TERMINATION_HPP_

#include <string>

namespace sysid {

enum class Termination {
  /// Met its stopping rule: a tolerance, a goal, the end of the simulated interval.
  kConverged,
  /// Ran out of its budget (evaluations, iterations, epochs, steps) before converging. The
  /// result holds the best point found so far.
  kBudgetExhausted,
  /// Could not go on: NaN/Inf, a solver error, a singular system. `message` says which.
  kFailure,
};

/// "converged", "budget-exhausted", "failure" (the text the CLI's JSON uses).
std::string ToString(Termination termination);

/// True unless the computation failed: a result that ran out of budget is still the best point
/// found and may be used (as Ceres' IsSolutionUsable). A simulation is different: one that
/// stopped early has no samples after the stop (SimulationSummary::IsSolutionUsable).
inline bool IsSolutionUsable(Termination termination) {
  return termination != Termination::kFailure;
}

}  // namespace sysid

#endif  // SYSID_TERMINATION_HPP_
