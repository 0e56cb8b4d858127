// Decimation behind a zero-phase anti-alias low-pass.
#include <string>

#include "signal/checks.hpp"
#include "sysid/error.hpp"
#include "sysid/signal.hpp"

namespace sysid {

Eigen::VectorXd Decimate(const Eigen::VectorXd& y, double dt_s, int factor) {
  detail::CheckSampleInterval("Decimate", dt_s);
  if (factor < 1)
    throw OptionsError("Decimate: factor = " + std::to_string(factor) +
                       ". Violated constraint: factor >= 1");
  if (factor == 1) return y;
  const double cutoff_hz = kDecimateCutoffFraction * 0.5 / (factor * dt_s);
  const Eigen::VectorXd filtered =
      ButterworthFiltFilt(y, dt_s, cutoff_hz, kDecimateButterworthOrder);
  const Eigen::Index m = (y.size() + factor - 1) / factor;
  Eigen::VectorXd out(m);
  for (Eigen::Index i = 0; i < m; ++i) out[i] = filtered[i * factor];
  return out;
}

}  // namespace sysid
