// Savitzky–Golay smoothing derivative: the derivative of the local least-squares polynomial.
// The weights come from a QR least-squares solve on abscissae scaled to [-1, 1] (a Vandermonde
// matrix in raw sample offsets is ill-conditioned for wide windows); only the window x
// (order + 1) factorisation and one row of weights are stored, so memory is linear in the
// window (a full window x window weight matrix would take 6.3 GB at 20001). Boost.Math's
// discrete_lanczos_derivative computes the same estimator for derivatives 1 and 2 (the tests
// cross-check against it) but not the smoothed value itself nor order 2 fits for acceleration,
// so one general path is kept here.
#include <Eigen/QR>
#include <string>

#include "core/option_rule.hpp"
#include "signal/checks.hpp"
#include "signal/filters.hpp"
#include "sysid/error.hpp"
#include "sysid/signal.hpp"

namespace sysid {
namespace internal {

SavitzkyGolayFit::SavitzkyGolayFit(int window, int order, int deriv)
    : half_((window - 1) / 2), basis_(window, order + 1), derivative_(window, order + 1) {
  SYSID_CHECK(window >= 3 && window % 2 == 1 && order >= 0 && order < window && deriv >= 0,
              "Savitzky-Golay weights need an odd window >= 3 and 0 <= order < window");
  const double scale = std::pow(1.0 / half_, deriv);
  for (int i = 0; i < window; ++i) {
    const double x = static_cast<double>(i - half_) / half_;  // x_i = (i - half) / half
    for (int j = 0; j <= order; ++j) {
      basis_(i, j) = std::pow(x, j);
      double falling = 1;  // j (j-1) ... (j-deriv+1)
      for (int r = 0; r < deriv; ++r) falling *= j - r;
      // d^deriv/ds^deriv of the basis, s in samples
      derivative_(i, j) = j >= deriv ? falling * std::pow(x, j - deriv) * scale : 0.0;
    }
  }
  qr_.compute(basis_);
}

Eigen::VectorXd SavitzkyGolayFit::Weights(int row) const {
  // w = D_row pinv(B) with B = QR: w^T = Q R^-T D_row^T (R is (order+1) square).
  const Eigen::Index p = basis_.cols();
  const Eigen::VectorXd z = qr_.matrixQR()
                                .topLeftCorner(p, p)
                                .triangularView<Eigen::Upper>()
                                .transpose()
                                .solve(derivative_.row(row).transpose());
  Eigen::VectorXd w = Eigen::VectorXd::Zero(basis_.rows());
  w.head(p) = z;
  w.applyOnTheLeft(qr_.householderQ());
  return w;
}

Eigen::VectorXd SavitzkyGolayFit::Evaluate(const Eigen::VectorXd& samples, int first,
                                           int count) const {
  const Eigen::VectorXd coefficients = qr_.solve(samples);
  return derivative_.middleRows(first, count) * coefficients;
}

Eigen::MatrixXd SavitzkyGolayWeights(int window, int order, int deriv) {
  const SavitzkyGolayFit fit(window, order, deriv);
  Eigen::MatrixXd w(window, window);
  for (int i = 0; i < window; ++i) w.row(i) = fit.Weights(i).transpose();
  return w;
}

}  // namespace internal

Eigen::VectorXd SavitzkyGolay(const Eigen::VectorXd& y, double dt_s, int window, int order,
                              int deriv) {
  constexpr const char* kWhere = "SavitzkyGolay";
  internal::CheckSampleInterval(kWhere, dt_s);
  internal::CheckSavitzkyGolay(kWhere, "window", window, "order", order, 0);
  if (deriv < 0 || deriv > 2 || deriv > order)
    internal::FailOption(kWhere, "deriv", deriv,
                         "0 <= deriv <= min(2, order = " + std::to_string(order) + ")");
  internal::CheckLength(kWhere, y.size(), window,
                      "a Savitzky-Golay window of " + std::to_string(window));
  internal::CheckFinite(kWhere, y);
  // Memory linear in the window: the window x (order + 1) fit, one row of weights.
  const internal::SavitzkyGolayFit fit(window, order, deriv);
  const double scale = 1.0 / std::pow(dt_s, deriv);
  const Eigen::Index n = y.size();
  const int half = (window - 1) / 2;
  Eigen::VectorXd out(n);
  const Eigen::RowVectorXd centre = fit.Weights(half).transpose() * scale;
  for (Eigen::Index k = half; k < n - half; ++k) out[k] = centre.dot(y.segment(k - half, window));
  // The ends take the polynomial of the first/last full window at their own offset.
  out.head(half) = fit.Evaluate(y.head(window), 0, half) * scale;
  out.tail(half) = fit.Evaluate(y.tail(window), half + 1, half) * scale;
  return out;
}

}  // namespace sysid
