// The default periodic steady state of a hysteresis model: simulate more and more periods from
// the initial state until two successive last periods agree.
#include "sysid/hysteresis_model.hpp"

#include <fmt/format.h>

#include <cmath>

#include "sysid/error.hpp"

namespace sysid {
namespace {

// The most samples the default periodic search simulates in all (docs/robustness.md).
constexpr double kMaxPeriodicSamples = 1e6;

}  // namespace

Eigen::VectorXd HysteresisModel::SimulatePeriodic(const Eigen::VectorXd& u_period, double dt_s,
                                                  double tolerance, int max_periods) const {
  const Eigen::Index n = u_period.size();
  if (n < 1) throw InputError("SimulatePeriodic: the period has no samples");
  if (!(tolerance >= 0) || max_periods < 2)
    throw OptionsError("SimulatePeriodic: tolerance >= 0 and max_periods >= 2 are required",
                       "tolerance");
  // The doubling simulates 2 + 4 + ... + P = 2 P - 2 periods in all, bounded up front by
  // kMaxPeriodicSamples samples: an ODE model (CVODE, about 15 us a sample for an undamped
  // Bouc-Wen oscillator) then stops within seconds where it used to run for minutes.
  const double samples = static_cast<double>(n);
  if (2 * samples > kMaxPeriodicSamples)
    throw InputError(fmt::format(
        "{}: a periodic simulation of 2 periods of {} samples exceeds the {:.0e} samples a "
        "periodic simulation may run in all; shorten the period",
        kind(), n, kMaxPeriodicSamples));
  int limit = 2;
  while (limit * 2 <= max_periods && (4.0 * limit - 2) * samples <= kMaxPeriodicSamples) limit *= 2;
  Eigen::VectorXd previous;  // the last period of the previous, shorter run
  double change = NAN;
  for (int periods = 2; periods <= limit; periods *= 2) {
    const Eigen::VectorXd u = u_period.replicate(periods, 1);
    const Eigen::VectorXd y = Simulate(u, dt_s);
    Eigen::VectorXd last = y.tail(n);
    // Within one run the last two periods must agree too: a run that has settled says so
    // without waiting for the doubling.
    change = (last - y.segment((periods - 2) * n, n)).cwiseAbs().maxCoeff();
    if (previous.size() == n) change = std::max(change, (last - previous).cwiseAbs().maxCoeff());
    if (change <= tolerance) return last;
    previous = std::move(last);
  }
  throw NumericalError(fmt::format(
      "{}: no periodic steady state within {} periods ({:.4g} samples simulated in all, at "
      "most {:.0e}): the last two periods still differ by {:.3g} (tolerance {:.3g})",
      kind(), limit, (2.0 * limit - 2) * samples, kMaxPeriodicSamples, change, tolerance));
}

}  // namespace sysid
