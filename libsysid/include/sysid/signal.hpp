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
#include <vector>

#include "sysid/io.hpp"
#include "sysid/serialize.hpp"

namespace sysid {

enum class DerivativeMethod { kCentral, kButterworthCentral, kSavitzkyGolay };

/// Highest Butterworth order accepted (the cascade of sections stays well conditioned).
constexpr int kMaxButterworthOrder = 20;
/// Widest Savitzky–Golay window [samples] (10 s at 1 kHz): the filter costs window
/// multiply-adds a sample, so this bounds the work at 10^4 per sample.
constexpr int kMaxSavitzkyGolayWindow = 10001;
/// Highest Savitzky–Golay polynomial order (a monomial basis on [-1, 1] beyond it is
/// ill-conditioned, and the fit's memory is window x (order + 1)).
constexpr int kMaxSavitzkyGolayOrder = 20;
/// Order of the Butterworth anti-alias low-pass of Decimate (run forward and backward, so the
/// attenuation in dB is twice that of one pass).
constexpr int kDecimateButterworthOrder = 8;
/// Anti-alias cut-off of Decimate as a fraction of the new Nyquist frequency 0.5 / (factor dt).
constexpr double kDecimateCutoffFraction = 0.8;

/// "central", "butterworth", "savgol" <-> DerivativeMethod. Parse throws OptionsError.
DerivativeMethod ParseDerivativeMethod(const std::string& name);
std::string ToString(DerivativeMethod method);

struct DerivativeOptions {
  DerivativeMethod method = DerivativeMethod::kCentral;
  double cutoff_hz = 50.0;    ///< [Hz] Butterworth cut-off; must be < Nyquist (0.5/dt_s)
  int butterworth_order = 4;  ///< order of the low-pass before forward-backward filtering
  int savgol_window = 21;     ///< Savitzky–Golay window length [samples], odd, > savgol_order
  int savgol_order = 3;       ///< Savitzky–Golay polynomial order, >= 2
  /// Throws OptionsError naming the field and the rule. Checks dt_s > 0 and the fields the
  /// chosen method uses: 0 < cutoff_hz < 0.5/dt_s and 1 <= butterworth_order <=
  /// kMaxButterworthOrder (kButterworthCentral); savgol_window odd and >= 3, 2 <= savgol_order
  /// < savgol_window (kSavitzkyGolay).
  /// The fields, in file order (sysid/serialize.hpp).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(method));
    a->Visit(SYSID_NVP(cutoff_hz));
    a->Visit(SYSID_NVP(butterworth_order));
    a->Visit(SYSID_NVP(savgol_window));
    a->Visit(SYSID_NVP(savgol_order));
  }
  void Validate(double dt_s) const;
};

/// Position with its first two derivatives, all of the input's length.
struct Derivatives {
  Eigen::VectorXd x_m;     ///< [m] position (low-passed for the filtering methods)
  Eigen::VectorXd v_mps;   ///< [m/s] velocity
  Eigen::VectorXd a_mps2;  ///< [m/s^2] acceleration
};

/// Velocity and acceleration of the position `x_m` sampled every `dt_s` seconds:
///  kCentral: v = D x, a = D v with D = CentralDifference;
///  kButterworthCentral: xf = ButterworthFiltFilt(x), v = D xf, a = D v;
///  kSavitzkyGolay: x, v, a = the 0th, 1st, 2nd derivative of the Savitzky–Golay fit.
/// Throws OptionsError (options.Validate), InputError (too few samples for the method, or a
/// non-finite sample).
Derivatives Differentiate(const Eigen::VectorXd& x_m, double dt_s,
                          const DerivativeOptions& options = {});

/// First derivative by central differences (second-order one-sided at both ends):
/// y'[k] = (y[k+1] - y[k-1]) / (2 dt), y'[0] = (-3 y[0] + 4 y[1] - y[2]) / (2 dt) and its mirror.
/// Error <= dt^2/6 max|y'''| inside, <= dt^2 max|y'''| at the ends. Needs >= 3 samples.
Eigen::VectorXd CentralDifference(const Eigen::VectorXd& y, double dt_s);
/// CentralDifference into `out` (resized; its storage reused when the size matches). `out`
/// must not be `y`.
void CentralDifference(const Eigen::VectorXd& y, double dt_s, Eigen::VectorXd* out);

/// Zero-phase Butterworth low-pass: the order-`order` filter run forward and backward with
/// odd-reflection padding at the ends (as MATLAB's filtfilt), so the result has no phase lag.
/// The magnitude response is |H(e^jw)|^2 = 1 / (1 + (tan(w/2) / tan(pi cutoff_hz dt_s))^(2 order)).
/// Needs more than 3 (2 ceil(order/2) + 1 - order mod 2) samples (the padding).
Eigen::VectorXd ButterworthFiltFilt(const Eigen::VectorXd& y, double dt_s, double cutoff_hz,
                                    int order);

/// `deriv`-th derivative (0, 1, 2) of the Savitzky–Golay fit of `y` with the given window and
/// polynomial order; the ends use the fit of the first/last full window. Needs window <= samples.
Eigen::VectorXd SavitzkyGolay(const Eigen::VectorXd& y, double dt_s, int window, int order,
                              int deriv);

/// Keeps every `factor`-th sample after a zero-phase anti-alias low-pass at 0.8 x the new
/// Nyquist frequency (as the EMPS reference does before decimating): the order
/// kDecimateButterworthOrder Butterworth, forward and backward. Returns y_f[0], y_f[factor], ...
/// (ceil(n / factor) samples). factor = 1 returns y unchanged. Throws OptionsError for
/// factor < 1, InputError when y is too short for the filter's padding.
Eigen::VectorXd Decimate(const Eigen::VectorXd& y, double dt_s, int factor);

/// Every column of `recording` (sampled every dt_s [s]) through Decimate, except the time
/// column t, which is subsampled (t[0], t[factor], ...) and never filtered; source and metadata
/// are kept. Throws as Decimate.
Recording DecimateRecording(const Recording& recording, double dt_s, int factor);

/// What DelaySignal gives before the record starts (t_k - tau < t_0).
enum class DelayStart {
  kHoldFirst,  ///< y[0]: the signal is taken as constant before the record (a stage at rest)
  kNaN,        ///< NaN: unknown, so a caller can drop those samples (regressions)
};

/// The most samples a DelayLine holds (tau / dt + 2): 2^22 doubles, 32 MiB. A real-time loop's
/// delay line is a few hundred samples; a longer one is a unit mistake (tau in ms, dt in s).
inline constexpr long long kMaxDelayLineSamples = 1LL << 22;

/// The causal, streaming form of DelaySignal(kHoldFirst) (the same rule, bit for bit): pushed y_k one sample at a time, it
/// returns y(t_k - tau) = (1 - f) y_{k-w} + f y_{k-w-1}, w = floor(tau / dt), f = tau / dt - w,
/// with y_j = y_0 for j < 0 (the signal constant before its first sample). The ring of w + 2
/// samples is allocated at construction; Push neither allocates nor throws.
class DelayLine {
 public:
  /// Throws OptionsError unless dt_s > 0 and 0 <= tau_s < infinity, or when the line would hold
  /// more than kMaxDelayLineSamples. `max_pushes` >= 0 promises at most that many pushes between
  /// resets (a batch over n samples): the ring is then no longer than they need, so any finite
  /// tau is accepted (samples older than the first are the first sample anyway).
  DelayLine(double dt_s, double tau_s, long long max_pushes = -1);
  /// Forgets the history: the next push is the first sample again.
  void Reset();
  /// y_k in, y(t_k - tau) out.
  double Push(double y_k);
  long long whole_samples() const { return whole_; }  ///< w = floor(tau / dt)
  double fraction() const { return frac_; }           ///< f = tau / dt - w, in [0, 1)

 private:
  long long whole_ = 0;
  double frac_ = 0;
  std::vector<double> ring_;
  long long head_ = 0;   // slot of the next sample
  long long count_ = 0;  // samples pushed since reset, saturating at whole_ + 2
  double first_ = 0;
};

/// `y` delayed by tau_s >= 0 on its uniform grid dt_s > 0: y(t_k - tau) by linear
/// interpolation between the two neighbouring samples; before the start as `start` says.
/// Throws OptionsError for dt_s <= 0 or tau_s < 0.
Eigen::VectorXd DelaySignal(const Eigen::VectorXd& y, double dt_s, double tau_s,
                            DelayStart start = DelayStart::kHoldFirst);
/// DelaySignal into `out` (resized; its storage reused when the size matches). `out` must not
/// be `y`.
void DelaySignal(const Eigen::VectorXd& y, double dt_s, double tau_s, DelayStart start,
                 Eigen::VectorXd* out);

}  // namespace sysid

#endif  // SYSID_SIGNAL_HPP_
