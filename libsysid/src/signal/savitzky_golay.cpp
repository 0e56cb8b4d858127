// Savitzky–Golay smoothing derivative: the derivative of the local least-squares polynomial.
// The weights come from a QR least-squares solve on abscissae scaled to [-1, 1] (a Vandermonde
// matrix in raw sample offsets is ill-conditioned for wide windows). Boost.Math's
// discrete_lanczos_derivative computes the same estimator for derivatives 1 and 2 (the tests
// cross-check against it) but not the smoothed value itself nor order 2 fits for acceleration,
// so one general path is kept here.
#include <Eigen/QR>
#include <string>

#include "signal/checks.hpp"
#include "signal/filters.hpp"
#include "sysid/error.hpp"
#include "sysid/signal.hpp"

namespace sysid {
namespace internal {

Eigen::MatrixXd SavitzkyGolayWeights(int window, int order, int deriv) {
  SYSID_CHECK(window >= 3 && window % 2 == 1 && order >= 0 && order < window && deriv >= 0,
              "Savitzky-Golay weights need an odd window >= 3 and 0 <= order < window");
  const int half = (window - 1) / 2;
  Eigen::MatrixXd basis(window, order + 1);       // x_i^j at x_i = (i - half) / half
  Eigen::MatrixXd derivative(window, order + 1);  // d^deriv/ds^deriv of the basis, s in samples
  const double scale = std::pow(1.0 / half, deriv);
  for (int i = 0; i < window; ++i) {
    const double x = static_cast<double>(i - half) / half;
    for (int j = 0; j <= order; ++j) {
      basis(i, j) = std::pow(x, j);
      double falling = 1;  // j (j-1) ... (j-deriv+1)
      for (int r = 0; r < deriv; ++r) falling *= j - r;
      derivative(i, j) = j >= deriv ? falling * std::pow(x, j - deriv) * scale : 0.0;
    }
  }
  // pinv(basis) maps the window's samples to the polynomial coefficients.
  const Eigen::MatrixXd pinv =
      basis.householderQr().solve(Eigen::MatrixXd::Identity(window, window));
  return derivative * pinv;
}

}  // namespace internal

Eigen::VectorXd SavitzkyGolay(const Eigen::VectorXd& y, double dt_s, int window, int order,
                              int deriv) {
  constexpr const char* kWhere = "SavitzkyGolay";
  internal::CheckSampleInterval(kWhere, dt_s);
  internal::CheckSavitzkyGolay(kWhere, "window", window, "order", order, 0);
  if (deriv < 0 || deriv > 2 || deriv > order)
    throw OptionsError(
        "SavitzkyGolay: deriv = " + std::to_string(deriv) +
        ". Violated constraint: 0 <= deriv <= min(2, order = " + std::to_string(order) + ")");
  internal::CheckLength(kWhere, y.size(), window,
                      "a Savitzky-Golay window of " + std::to_string(window));
  internal::CheckFinite(kWhere, y);
  const Eigen::MatrixXd w =
      internal::SavitzkyGolayWeights(window, order, deriv) / std::pow(dt_s, deriv);
  const Eigen::Index n = y.size();
  const int half = (window - 1) / 2;
  Eigen::VectorXd out(n);
  const Eigen::RowVectorXd centre = w.row(half);
  for (Eigen::Index k = half; k < n - half; ++k) out[k] = centre.dot(y.segment(k - half, window));
  // The ends take the polynomial of the first/last full window at their own offset.
  const Eigen::VectorXd head = w.topRows(half) * y.head(window);
  const Eigen::VectorXd tail = w.bottomRows(half) * y.tail(window);
  out.head(half) = head;
  out.tail(half) = tail;
  return out;
}

}  // namespace sysid
