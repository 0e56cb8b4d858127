// Signal conditioning: velocity and acceleration from a sampled encoder position.
//
// Methods (all for uniformly sampled signals, sample interval dt_s):
//  - kCentral: central differences y'[k] = (y[k+1] - y[k-1]) / (2 dt), one-sided at the ends
//    (what the paper does);
//  - kButterworthCentral: zero-phase Butterworth low-pass (forward-backward, order doubled,
//    no phase lag) then central differences (the robotics IDIM practice);
//  - kSavitzkyGolay: local least-squares polynomial fit over a sliding window and its
//    derivative (noise-robust smoothing derivative).
#ifndef SYSID_SIGNAL_HPP_
#define SYSID_SIGNAL_HPP_

#include <Eigen/Core>
#include <string>

namespace sysid {

enum class DerivativeMethod { kCentral, kButterworthCentral, kSavitzkyGolay };

/// "central", "butterworth", "savgol" <-> DerivativeMethod. Parse throws OptionsError.
DerivativeMethod ParseDerivativeMethod(const std::string& name);
std::string ToString(DerivativeMethod method);

struct DerivativeOptions {
  DerivativeMethod method = DerivativeMethod::kCentral;
  double cutoff_hz = 50.0;      ///< [Hz] Butterworth cut-off; must be < Nyquist (0.5/dt_s)
  int butterworth_order = 4;    ///< order of the low-pass before forward-backward filtering
  int savgol_window = 21;       ///< Savitzky–Golay window length [samples], odd, > savgol_order
  int savgol_order = 3;         ///< Savitzky–Golay polynomial order, >= 2
  void Validate(double dt_s) const;  ///< throws OptionsError naming the field and the rule
};

/// Position with its first two derivatives, all of the input's length.
struct Derivatives {
  Eigen::VectorXd x_m;       ///< [m] position (low-passed for the filtering methods)
  Eigen::VectorXd v_mps;     ///< [m/s] velocity
  Eigen::VectorXd a_mps2;    ///< [m/s^2] acceleration
};

/// Velocity and acceleration of the position `x_m` sampled every `dt_s` seconds.
Derivatives Differentiate(const Eigen::VectorXd& x_m, double dt_s,
                          const DerivativeOptions& options = {});

/// First derivative by central differences (second-order one-sided at both ends).
Eigen::VectorXd CentralDifference(const Eigen::VectorXd& y, double dt_s);

/// Zero-phase Butterworth low-pass: the order-`order` filter run forward and backward with
/// odd-reflection padding at the ends (as MATLAB's filtfilt), so the result has no phase lag.
Eigen::VectorXd ButterworthFiltFilt(const Eigen::VectorXd& y, double dt_s, double cutoff_hz,
                                    int order);

/// `deriv`-th derivative (0, 1, 2) of the Savitzky–Golay fit of `y` with the given window and
/// polynomial order; the ends use the fit of the first/last full window.
Eigen::VectorXd SavitzkyGolay(const Eigen::VectorXd& y, double dt_s, int window, int order,
                              int deriv);

/// Keeps every `factor`-th sample after a zero-phase anti-alias low-pass at 0.8 x the new
/// Nyquist frequency (as the EMPS reference does before decimating).
Eigen::VectorXd Decimate(const Eigen::VectorXd& y, double dt_s, int factor);

}  // namespace sysid

#endif  // SYSID_SIGNAL_HPP_
