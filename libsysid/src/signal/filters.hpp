// Private helpers of the signal module: Butterworth design as second-order sections, the
// sections' filter with steady-state initial conditions, and Savitzky–Golay weights.
// Tests include this file to check the design against closed forms.
#ifndef SYSID_SRC_SIGNAL_FILTERS_HPP_
#define SYSID_SRC_SIGNAL_FILTERS_HPP_

#include <Eigen/Core>
#include <Eigen/QR>
#include <complex>
#include <vector>

namespace sysid::internal {

/// One biquad H(z) = (b0 + b1 z^-1 + b2 z^-2) / (1 + a1 z^-1 + a2 z^-2) (a0 = 1).
struct Biquad {
  double b0 = 1, b1 = 0, b2 = 0;
  double a1 = 0, a2 = 0;
  bool first_order() const { return b2 == 0.0 && a2 == 0.0; }
};

/// Digital Butterworth low-pass of order `order` with cut-off `normalized_cutoff` = f_c / f_s
/// (0 < . < 0.5), by the bilinear transform of the analog prototype with pre-warping, as
/// ceil(order/2) sections of unit DC gain, in increasing pole quality factor (the first-order
/// section first when the order is odd) so the resonant sections see an already smoothed input.
std::vector<Biquad> DesignButterworthLowPass(int order, double normalized_cutoff);

/// H(e^{j omega}) of the cascade, omega in [rad/sample].
std::complex<double> FrequencyResponse(const std::vector<Biquad>& sections, double omega);

/// Number of padding samples filtfilt uses at each end (SciPy's sosfiltfilt rule:
/// 3 x (2 x sections + 1 - number of first-order sections)).
int FiltFiltPadLength(const std::vector<Biquad>& sections);

/// Zero-phase forward-backward filtering with odd-reflection padding and steady-state initial
/// conditions scaled by the first sample of each pass (SciPy sosfiltfilt, MATLAB filtfilt).
/// Requires y.size() > FiltFiltPadLength(sections); the caller checks.
Eigen::VectorXd FiltFilt(const std::vector<Biquad>& sections, const Eigen::VectorXd& y);

/// Savitzky–Golay weights: row r (r = 0..window-1) holds the weights w such that
/// sum_i w_i y[i] over one window is the `deriv`-th derivative, at offset r - (window-1)/2
/// samples from the window centre, of the least-squares polynomial of degree `order`, for unit
/// sample spacing (divide by dt^deriv).
/// Builds the full window x window matrix: for tests and small windows only.
Eigen::MatrixXd SavitzkyGolayWeights(int window, int order, int deriv);

/// The least-squares polynomial fit of one Savitzky–Golay window in O(window x order) memory:
/// the QR factorisation of the window x (order + 1) Vandermonde matrix on x = (i - half)/half.
class SavitzkyGolayFit {
 public:
  SavitzkyGolayFit(int window, int order, int deriv);
  /// Row `row` of SavitzkyGolayWeights (window values), without forming the matrix.
  Eigen::VectorXd Weights(int row) const;
  /// The `deriv`-th derivative of the fit to `samples` (one window) at rows first..first+count-1
  /// (unit sample spacing).
  Eigen::VectorXd Evaluate(const Eigen::VectorXd& samples, int first, int count) const;

 private:
  int half_;
  Eigen::MatrixXd basis_;       ///< x_i^j
  Eigen::MatrixXd derivative_;  ///< d^deriv/ds^deriv of x_i^j, s in samples
  Eigen::HouseholderQR<Eigen::MatrixXd> qr_;
};

}  // namespace sysid::internal

#endif  // SYSID_SRC_SIGNAL_FILTERS_HPP_
