// Central differences: the paper's velocity and acceleration from the encoder position.
#include "signal/checks.hpp"
#include "sysid/error.hpp"
#include "sysid/signal.hpp"

namespace sysid {

Eigen::VectorXd CentralDifference(const Eigen::VectorXd& y, double dt_s) {
  Eigen::VectorXd d;
  CentralDifference(y, dt_s, &d);
  return d;
}

void CentralDifference(const Eigen::VectorXd& y, double dt_s, Eigen::VectorXd* out) {
  SYSID_CHECK(out != &y, "CentralDifference: out must not alias y");
  constexpr const char* kWhere = "CentralDifference";
  internal::CheckSampleInterval(kWhere, dt_s);
  internal::CheckLength(kWhere, y.size(), 3, "a second-order difference");
  internal::CheckFinite(kWhere, y);
  const Eigen::Index n = y.size();
  const double inv_2dt = 0.5 / dt_s;
  Eigen::VectorXd& d = *out;
  d.resize(n);
  d.segment(1, n - 2) = (y.tail(n - 2) - y.head(n - 2)) * inv_2dt;
  // One-sided second-order stencils keep the ends as accurate (in order) as the interior.
  d[0] = (-3 * y[0] + 4 * y[1] - y[2]) * inv_2dt;
  d[n - 1] = (3 * y[n - 1] - 4 * y[n - 2] + y[n - 3]) * inv_2dt;
}

}  // namespace sysid
