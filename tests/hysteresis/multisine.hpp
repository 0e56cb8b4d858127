// The random-phase multisine the Bouc-Wen tests drive the oscillator with: harmonics first..last
// of the record's fundamental, each of `amplitude` [N], Schroeder-like phases 2.39996 l^2.
#ifndef SYSID_TESTS_HYSTERESIS_MULTISINE_HPP_
#define SYSID_TESTS_HYSTERESIS_MULTISINE_HPP_

#include <Eigen/Core>
#include <cmath>

namespace sysid::test {

inline Eigen::VectorXd Multisine(Eigen::Index n, double dt, int first, int last, double amplitude) {
  Eigen::VectorXd u = Eigen::VectorXd::Zero(n);
  const double w0 = 2 * M_PI / (static_cast<double>(n) * dt);
  for (int l = first; l <= last; ++l)
    for (Eigen::Index i = 0; i < n; ++i)
      u[i] += amplitude * std::cos(w0 * l * static_cast<double>(i) * dt + 2.39996 * l * l);
  return u;
}

}  // namespace sysid::test

#endif  // SYSID_TESTS_HYSTERESIS_MULTISINE_HPP_
