// The default periodic steady state of a hysteresis model: simulate more and more periods from
// the initial state until two successive last periods agree.
#include "sysid/hysteresis_model.hpp"

#include <fmt/format.h>

#include <cmath>

#include "sysid/error.hpp"

namespace sysid {

Eigen::VectorXd HysteresisModel::SimulatePeriodic(const Eigen::VectorXd& u_period, double dt_s,
                                                  double tolerance, int max_periods) const {
  const Eigen::Index n = u_period.size();
  if (n < 1) throw InputError("SimulatePeriodic: the period has no samples");
  if (!(tolerance >= 0) || max_periods < 2)
    throw OptionsError("SimulatePeriodic: tolerance >= 0 and max_periods >= 2 are required",
                       "tolerance");
  Eigen::VectorXd previous;  // the last period of the previous, shorter run
  double change = NAN;
  for (int periods = 2; periods <= max_periods; periods *= 2) {
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
      "{}: no periodic steady state within {} periods: the last two periods still differ by "
      "{:.3g} (tolerance {:.3g})",
      kind(), max_periods, change, tolerance));
}

}  // namespace sysid
