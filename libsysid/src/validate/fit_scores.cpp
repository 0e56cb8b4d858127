// MATLAB compare's fit % and the RMSE with both normalisers, named (validate.hpp).
#include <fmt/format.h>

#include <cmath>
#include <limits>

#include "sysid/error.hpp"
#include "sysid/validate.hpp"

namespace sysid {

FitScores ScoreFit(const Eigen::VectorXd& measured, const Eigen::VectorXd& simulated) {
  if (measured.size() != simulated.size())
    throw InputError(
        fmt::format("fit: measured has {} samples, simulated {}: expected equal "
                    "lengths",
                    measured.size(), simulated.size()));
  if (measured.size() < 2)
    throw InputError(fmt::format("fit: {} samples: expected at least 2", measured.size()));
  if (!measured.allFinite() || !simulated.allFinite())
    throw InputError("fit: expected finite measured and simulated outputs, found NaN or inf");
  const double n = static_cast<double>(measured.size());
  const double error_norm = (measured - simulated).norm();
  const double spread_norm = (measured.array() - measured.mean()).matrix().norm();
  const double range = measured.maxCoeff() - measured.minCoeff();
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  FitScores s;
  s.rmse = error_norm / std::sqrt(n);
  s.fit_percent = spread_norm > 0 ? 100.0 * (1.0 - error_norm / spread_norm) : kNaN;
  // Population std: sqrt(mean (y - mean y)^2) = spread_norm / sqrt(n).
  s.nrmse_std = spread_norm > 0 ? s.rmse / (spread_norm / std::sqrt(n)) : kNaN;
  s.nrmse_range = range > 0 ? s.rmse / range : kNaN;
  return s;
}

}  // namespace sysid
