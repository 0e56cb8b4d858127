// The one fractional-sample delay of the library (analytic inverse, trajectory regressors,
// dominance terms): y(t_k - tau) on the signal's own grid.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "sysid/error.hpp"
#include "sysid/signal.hpp"

namespace sysid {

Eigen::VectorXd DelaySignal(const Eigen::VectorXd& y, double dt_s, double tau_s,
                            DelayStart start) {
  Eigen::VectorXd out;
  DelaySignal(y, dt_s, tau_s, start, &out);
  return out;
}

void DelaySignal(const Eigen::VectorXd& y, double dt_s, double tau_s, DelayStart start,
                 Eigen::VectorXd* result) {
  SYSID_CHECK(result != &y, "DelaySignal: out must not alias y");
  if (!(dt_s > 0) || !(tau_s >= 0) || !std::isfinite(tau_s))
    throw OptionsError("DelaySignal: dt_s = " + std::to_string(dt_s) + ", tau_s = " +
                       std::to_string(tau_s) + ". Violated constraint: dt_s > 0, tau_s >= 0");
  const double shift = tau_s / dt_s;  // delay in samples, possibly fractional
  const auto whole = static_cast<Eigen::Index>(std::floor(shift));
  const double frac = shift - static_cast<double>(whole);
  const Eigen::Index n = y.size();
  Eigen::VectorXd& out = *result;
  out.resize(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    // y(t_k - tau) lies between samples k - whole - 1 and k - whole.
    const Eigen::Index hi = k - whole, lo = hi - 1;
    if (start == DelayStart::kNaN && (hi < 0 || (hi == 0 && frac > 0))) {
      out[k] = std::numeric_limits<double>::quiet_NaN();
      continue;
    }
    const double y_hi = y[std::clamp<Eigen::Index>(hi, 0, n - 1)];
    const double y_lo = y[std::clamp<Eigen::Index>(lo, 0, n - 1)];
    out[k] = (1 - frac) * y_hi + frac * y_lo;
  }
}

}  // namespace sysid
