// Analytic test signals and error-bound helpers for the signal tests.
#ifndef SYSID_TESTS_SIGNAL_SIGNAL_TEST_UTIL_HPP_
#define SYSID_TESTS_SIGNAL_SIGNAL_TEST_UTIL_HPP_

#include <Eigen/Core>
#include <cmath>
#include <functional>
#include <vector>

namespace sysid::test {

inline const double kPi = std::acos(-1.0);

/// f(t_k) at t_k = k dt, k = 0..n-1.
inline Eigen::VectorXd Sample(const std::function<double(double)>& f, Eigen::Index n, double dt) {
  Eigen::VectorXd y(n);
  for (Eigen::Index k = 0; k < n; ++k) y[k] = f(static_cast<double>(k) * dt);
  return y;
}

/// Rounds to the nearest multiple of q (an encoder of resolution q): |error| <= q/2.
inline Eigen::VectorXd Quantize(const Eigen::VectorXd& y, double q) {
  return y.unaryExpr([q](double v) { return q * std::round(v / q); });
}

/// Lagrange-remainder bound of a linear stencil sum_i c_i y(t + s_i h) / h^d that is exact for
/// polynomials of degree <= p:
///   |error| <= max|y^(p+1)| h^(p+1-d) / (p+1)! sum_i |c_i| |s_i|^(p+1).
inline double StencilBound(const std::vector<double>& c, const std::vector<double>& s, int p, int d,
                           double h, double max_derivative) {
  double sum = 0, factorial = 1;
  for (int i = 2; i <= p + 1; ++i) factorial *= i;
  for (size_t i = 0; i < c.size(); ++i) sum += std::abs(c[i]) * std::pow(std::abs(s[i]), p + 1);
  return max_derivative * std::pow(h, p + 1 - d) / factorial * sum;
}

/// Closed-form squared magnitude of the bilinear-transform Butterworth low-pass of order n and
/// cut-off fc/fs, at w [rad/sample]: 1 / (1 + (tan(w/2) / tan(pi fc/fs))^(2n)).
inline double ButterworthGain2(double omega, double normalized_cutoff, int order) {
  const double r = std::tan(omega / 2) / std::tan(kPi * normalized_cutoff);
  return 1.0 / (1.0 + std::pow(r, 2 * order));
}

/// max |y[k] - ref[k]| for k in [begin, end).
inline double MaxError(const Eigen::VectorXd& y, const Eigen::VectorXd& ref, Eigen::Index begin,
                       Eigen::Index end) {
  return (y.segment(begin, end - begin) - ref.segment(begin, end - begin)).cwiseAbs().maxCoeff();
}

}  // namespace sysid::test

#endif  // SYSID_TESTS_SIGNAL_SIGNAL_TEST_UTIL_HPP_
