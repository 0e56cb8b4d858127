// Private: a uniformly sampled signal delayed by a fraction of samples.
#ifndef SYSID_SRC_NUMERICS_DELAY_SHIFT_HPP_
#define SYSID_SRC_NUMERICS_DELAY_SHIFT_HPP_

#include <Eigen/Core>
#include <cmath>
#include <limits>

namespace sysid::detail {

/// y(t - tau) on the same grid by linear interpolation; NaN where t - tau precedes the record.
inline Eigen::VectorXd DelayedSignal(const Eigen::VectorXd& y, double dt_s, double tau_s) {
  const Eigen::Index n = y.size();
  Eigen::VectorXd out(n);
  const double shift = tau_s / dt_s;
  for (Eigen::Index k = 0; k < n; ++k) {
    const double pos = static_cast<double>(k) - shift;
    if (pos < 0) {
      out[k] = std::numeric_limits<double>::quiet_NaN();
      continue;
    }
    const auto i = static_cast<Eigen::Index>(std::floor(pos));
    const double w = pos - static_cast<double>(i);
    out[k] = i + 1 < n ? (1 - w) * y[i] + w * y[i + 1] : y[n - 1];
  }
  return out;
}

}  // namespace sysid::detail

#endif  // SYSID_SRC_NUMERICS_DELAY_SHIFT_HPP_
