// Private: the pieces of the Bouc–Wen models shared by the simulators, the fit and the tests.
#ifndef SYSID_SRC_HYSTERESIS_BOUC_WEN_INTERNAL_HPP_
#define SYSID_SRC_HYSTERESIS_BOUC_WEN_INTERNAL_HPP_

#include <Eigen/Core>
#include <cmath>
#include <complex>
#include <vector>

#include "sysid/hysteresis_bouc_wen.hpp"
#include "sysid/io.hpp"

namespace sysid::internal {

/// The most (spectral lines kept) x (samples) for which SampledInput sums a band-limited input's
/// lines at each of CVODE's evaluations; past it the input is tabulated (a sum would cost
/// minutes: 40960 samples keep about 1600 lines).
inline constexpr double kMaxBandLimitedWork = 2e7;

/// [1] The tabulated band-limited input's error bound, relative to the sum of its lines'
/// amplitudes: far below what CVODE's default rtol 1e-9 resolves.
inline constexpr double kBandLimitedGridTolerance = 1e-11;

/// The most grid points per sample of a tabulated band-limited input (a line at the Nyquist
/// frequency needs 64).
inline constexpr int kMaxGridPerSample = 1024;

/// u(t) and u'(t) between the samples u_k = u(k dt), t in [0, n dt], as InputInterpolation says.
/// Band-limited: the trigonometric interpolant of the n samples as one period (lines with
/// negligible amplitude, below 1e-15 of the largest, are dropped). While (lines x samples) is
/// within `max_line_work` every evaluation sums the lines; past it u, u' and u'' are tabulated
/// once on a grid `fine()` times finer than the samples (inverse FFTs of the lines) and
/// evaluated by quintic Hermite interpolation, whose error is at most
/// h^6 M6 / 46080 <= kBandLimitedGridTolerance A (h the grid's step, A = sum of the lines'
/// amplitudes a_j, M6 = sum a_j w_j^6 >= |u^(6)| with w_j a line's angular frequency: Hermite's
/// remainder). The table's 3 n fine() values are bounded by `max_table_values` (InputError before
/// they are allocated). A table depends on u, dt_s and `how` alone: a fit builds it once per
/// recording and hands it to every simulation (the MechanicalCvode and PiezoCvode overloads).
class SampledInput {
 public:
  SampledInput(const Eigen::VectorXd& u, double dt_s, InputInterpolation how,
               double max_line_work = kMaxBandLimitedWork,
               double max_table_values = kMaxSignalSamples);
  /// fine() of a band-limited SampledInput of u, without tabulating (one forward FFT of u): the
  /// constructor's rule, with its InputError where the constructor would refuse the table.
  static int GridPerSample(const Eigen::VectorXd& u, double dt_s,
                           double max_line_work = kMaxBandLimitedWork,
                           double max_table_values = kMaxSignalSamples);
  /// u [input unit] and its time derivative at t [s], inside the sample interval
  /// [t_k, t_k+1] (held and linear inputs use interval k's formula even at its ends, so a
  /// solver stopping at t_k+1 sees no jump).
  void Evaluate(double t_s, Eigen::Index k, double* u, double* du) const;
  InputInterpolation how() const { return how_; }
  /// The samples u_k [input unit] and their spacing [s], as given to the constructor.
  const Eigen::VectorXd& samples() const { return u_; }
  double dt_s() const { return dt_; }
  /// Grid points per sample of the tabulated band-limited input (the smallest power of two
  /// within the tolerance); 0 when the lines are summed.
  int fine() const { return fine_; }
  /// [input unit] The bound on the tabulated input's error stated above; 0 when not tabulated.
  double grid_error_bound() const { return grid_error_bound_; }

 private:
  // The interpolant's kept lines: u(t) = mean + sum 2 Re(coeff_j e^(i omega line_j t)).
  struct Lines {
    double mean = 0;
    double omega = 0;       // [rad/s] 2 pi / (n dt)
    std::vector<int> line;  // harmonic numbers kept
    std::vector<std::complex<double>> coeff;
  };
  static Lines Spectrum(const Eigen::VectorXd& u, double dt_s);
  // The grid points per sample for the lines of n samples (0: summed) and *bound, the Hermite
  // bound there; InputError past max_table_values or kMaxFftWork.
  static int Grid(const Lines& s, Eigen::Index n, double dt_s, double max_line_work,
                  double max_table_values, double* bound);
  void Tabulate();

  Eigen::VectorXd u_;
  double dt_;
  InputInterpolation how_;
  Lines s_;
  int fine_ = 0;
  double grid_error_bound_ = 0;
  std::vector<double> grid_;  // (u, u' [1/s], u'' [1/s^2]) at each grid point, one period
};

/// The most power above a quarter of the sampling rate, as a fraction of u's variance, that a
/// band-limited input may have for PeriodicBandLimited.
inline constexpr double kBandLimitedPower = 1e-6;

/// True when u looks like the band-limited interpolant's input, one or more whole periods of a
/// signal whose lines lie well below the Nyquist frequency: its wrap (u[0] after u[n-1]) is no
/// larger a step than its largest step between samples, and its lines above a quarter of the
/// sampling rate hold at most kBandLimitedPower of its variance (a record that does not wrap
/// smoothly spreads its jump over every line). *wrap_step and *high_fraction say what was
/// measured (NaN: not measured: fewer than 8 samples, or an FFT past kMaxFftWork).
bool PeriodicBandLimited(const Eigen::VectorXd& u, double* wrap_step, double* high_fraction);

/// A model's simulation options: Validate, and OptionsError for kAuto (a fit's choice).
void CheckModelSimulation(const BoucWenSimulationOptions& o);

/// Throws OptionsError unless dt_s > 0 is finite, InputError naming `what`[i] (e.g. "u[3]")
/// at the first non-finite sample; `kind` starts the message ("bouc-wen").
void CheckSamples(const Eigen::VectorXd& v, double dt_s, const char* kind, const char* what);

/// The Bouc–Wen z' (mechanical form) at velocity v and restoring force z, and its partial
/// derivatives in v and z (for Newton).
struct BoucWenRate {
  double f, df_dv, df_dz;
};
// Inline: Newton calls it at every step of the fine grid (a sixth of a fit's time as a call).
inline BoucWenRate MechanicalRate(const MechanicalBoucWenParameters& p, double v, double z) {
  const double av = std::abs(v), az = std::abs(z);
  const double sv = v > 0 ? 1.0 : v < 0 ? -1.0 : 0.0;
  const double sz = z > 0 ? 1.0 : z < 0 ? -1.0 : 0.0;
  if (p.nu == 1) {
    // |z|^0 z = z: the common case without pow.
    return {p.alpha_n_per_m * v - p.beta_per_m * (p.gamma * av * z + p.delta * v * az),
            p.alpha_n_per_m - p.beta_per_m * (p.gamma * sv * z + p.delta * az),
            -p.beta_per_m * (p.gamma * av + p.delta * v * sz)};
  }
  const double pow1 = std::pow(az, p.nu - 1);  // |z|^(nu-1), nu >= 1
  const double pownu = pow1 * az;
  return {p.alpha_n_per_m * v - p.beta_per_m * (p.gamma * av * pow1 * z + p.delta * v * pownu),
          p.alpha_n_per_m - p.beta_per_m * (p.gamma * sv * pow1 * z + p.delta * pownu),
          -p.beta_per_m * p.nu * pow1 * (p.gamma * av + p.delta * v * sz)};
}

/// One Newmark/trapezoidal step's implicit equations solved by Newton (see NewmarkBoucWen): from
/// (y0, v0, a0, z0) with f0 = z'(v0, z0), the input u1 [N] at the step's end, step h [s]; returns
/// y1 and z1 (v1 and a1 follow from y1 by the Newmark formulas). Shared by the simulation and its
/// sensitivities, so both take the same steps to the last bit.
inline void NewmarkNewton(const MechanicalBoucWenParameters& p, double u1, double h, double y0,
                          double v0, double a0, double z0, double f0, double* y1_out,
                          double* z1_out) {
  const double m = p.m_kg, c = p.c_n_s_per_m, k = p.k_n_per_m;
  // Unknowns (y1, z1); v1 = 2 (y1 - y0) / h - v0, a1 = 4 (y1 - y0 - h v0) / h^2 - a0.
  double y1 = y0 + h * v0 + 0.5 * h * h * a0;  // constant-acceleration predictor
  double z1 = z0 + h * f0;
  for (int it = 0; it < 50; ++it) {
    const double v1 = 2 * (y1 - y0) / h - v0;
    const double a1 = 4 * (y1 - y0 - h * v0) / (h * h) - a0;
    const BoucWenRate r = MechanicalRate(p, v1, z1);
    const double r1 = m * a1 + c * v1 + k * y1 + z1 - u1;
    const double r2 = z1 - z0 - 0.5 * h * (f0 + r.f);
    // d/dy1: a1' = 4/h^2, v1' = 2/h.
    const double j11 = 4 * m / (h * h) + 2 * c / h + k, j12 = 1;
    const double j21 = -0.5 * h * r.df_dv * 2 / h, j22 = 1 - 0.5 * h * r.df_dz;
    const double det = j11 * j22 - j12 * j21;
    const double dy = (r1 * j22 - j12 * r2) / det;
    const double dz = (j11 * r2 - j21 * r1) / det;
    y1 -= dy;
    z1 -= dz;
    // Converged to rounding: the correction is a few ulps of the step's own scale.
    if (std::abs(dy) <= 1e-15 * (std::abs(y1) + h * std::abs(v1)) &&
        std::abs(dz) <= 1e-15 * (std::abs(z1) + h * std::abs(r.f)))
      break;
  }
  *y1_out = y1;
  *z1_out = z1;
}

/// One whole Newmark step from (y0, v0, a0, z0) with f0 = z'(v0, z0): NewmarkNewton for y1 and
/// z1, then v1 and a1 by the Newmark formulas; NumericalError naming step `i` when it diverges.
/// Shared by the simulation and its sensitivities.
void NewmarkAdvance(const MechanicalBoucWenParameters& p, double u1, double h, double y0,
                    double v0, double a0, double z0, double f0, Eigen::Index i, double* y1,
                    double* v1, double* a1, double* z1);

/// Newmark average acceleration (gamma = 1/2, beta = 1/4) on y with the trapezoidal rule on z,
/// the implicit step solved by Newton on (y, z), at step h_s over the samples u (already at the
/// integration rate), from the state (y, v, z); the state is updated. Returns y at every sample
/// (the first: the initial y).
struct NewmarkState {
  double y = 0, v = 0, a = 0, z = 0;
  bool started = false;  // a is set from the equation of motion at the first sample
};
void NewmarkBoucWen(const MechanicalBoucWenParameters& p, const double* u, Eigen::Index n,
                    double h_s, NewmarkState* state, double* y_out);

/// The prime factors of r, ascending (MATLAB's factor()).
std::vector<int> PrimeFactors(int r);

/// Fine samples the FIR cascade (decimation by `factors` in turn) reads past a coarse sample:
/// 15 per stage at that stage's rate.
Eigen::Index FirLookahead(const std::vector<int>& factors);
/// y decimated by each of `factors` in turn (DecimateFir).
Eigen::VectorXd DecimateChain(Eigen::VectorXd y, const std::vector<int>& factors);

/// The benchmark chain in two halves. ChainInput: u [N] (one period) at `upsampling` times the
/// rate, continued periodically for the FIR cascade's lookahead — it depends on u alone, so a
/// fit computes it once instead of once per simulation. ChainOutput: y [m] at the n coarse
/// samples, dt_s apart, from ChainInput's result; the two together are Simulate's chain.
Eigen::VectorXd ChainInput(const Eigen::VectorXd& u, int upsampling);
Eigen::VectorXd ChainOutput(const MechanicalBoucWenParameters& p, const Eigen::VectorXd& ufx,
                            Eigen::Index n, double dt_s, int upsampling);

/// The mechanical parameters in the order of the sensitivities: m, c, k, alpha, beta, gamma,
/// delta, nu.
inline constexpr int kMechanicalParameters = 8;

/// One value per mechanical parameter, in kMechanicalParameters' order.
using MechanicalParameterVector = Eigen::Matrix<double, kMechanicalParameters, 1>;

/// The Bouc–Wen z' = f(v, z) differentiated in the parameters at (v, z), f = alpha v - beta
/// (gamma |v| |z|^(nu-1) z + delta v |z|^nu): entries alpha .. nu (m, c, k: 0). f is continuous
/// in z and v, so |z| and |v| need no event: the partials are those of the side z and v are on
/// (at z = 0 the nu entry is its limit 0: |z|^nu ln|z| -> 0). `with_nu` false leaves nu's at 0
/// (a logarithm per call). Shared by every sensitivity recursion (Newmark, CVODES).
inline MechanicalParameterVector MechanicalRateParameterPartials(
    const MechanicalBoucWenParameters& p, double v, double z, bool with_nu) {
  const double av = std::abs(v), az = std::abs(z);
  const double pow1 = p.nu == 1 ? 1.0 : std::pow(az, p.nu - 1);
  const double g = av * pow1 * z, d = v * pow1 * az;  // the gamma and delta terms' factors
  MechanicalParameterVector out = MechanicalParameterVector::Zero();
  out[3] = v;
  out[4] = -(p.gamma * g + p.delta * d);
  out[5] = -p.beta_per_m * g;
  out[6] = -p.beta_per_m * d;
  if (with_nu && az > 0) out[7] = out[4] * p.beta_per_m * std::log(az);
  return out;
}

/// dy/dp at the steps a recursion keeps: one column per kept step, rows in kMechanicalParameters'
/// order.
using NewmarkJacobian = Eigen::Matrix<double, kMechanicalParameters, Eigen::Dynamic>;

/// NewmarkBoucWen from rest over the fine input uf (step h_s [s]) with its forward sensitivities
/// (the implicit step differentiated at its Newton solution), keeping y and dy/dp at every
/// `stride`-th step from the first ((uf.size() - 1) / stride + 1 of them). `with_nu` false
/// leaves the nu row at 0 (it costs a logarithm per step). y is NewmarkBoucWen's to the last bit.
void NewmarkSensitivity(const MechanicalBoucWenParameters& p, const Eigen::VectorXd& uf, double h_s,
                        Eigen::Index stride, bool with_nu, Eigen::VectorXd* y,
                        NewmarkJacobian* dy_dp);

/// ChainOutput and its exact Jacobian: y [m] at the n coarse samples and dy/dp (n x 8, columns in
/// kMechanicalParameters' order, each in m per the parameter's unit), by forward sensitivities of
/// the Newmark/trapezoidal recursion (the implicit step differentiated at its Newton solution)
/// and the same (linear) FIR decimation. `with_nu` false leaves the nu column at 0 (it costs a
/// logarithm per step). y is ChainOutput's to the last bit.
void ChainOutputSensitivity(const MechanicalBoucWenParameters& p, const Eigen::VectorXd& ufx,
                            Eigen::Index n, double dt_s, int upsampling, bool with_nu,
                            Eigen::VectorXd* y, Eigen::MatrixXd* dy_dp);

/// The fixed-step integrator (BoucWenIntegrator::kFixedStep): the Newmark/trapezoidal step of
/// the chain at dt_s / substeps on u taken between samples as `how` says (linear, or
/// band-limited: the record as one period), no decimation: y is every substeps-th step's.
/// FixedStepInput: u at the (n - 1) substeps + 1 fine points (it depends on u alone, so a fit
/// computes it once per substep count). Throws OptionsError for a held input (its jumps would
/// need the acceleration restarted at every sample; CVODE takes it).
Eigen::VectorXd FixedStepInput(const Eigen::VectorXd& u, InputInterpolation how, int substeps);
/// y [m] at the n samples from FixedStepInput's result.
Eigen::VectorXd FixedStepOutput(const MechanicalBoucWenParameters& p, const Eigen::VectorXd& uf,
                                double dt_s, int substeps);
/// FixedStepOutput and its exact Jacobian (n x 8, as ChainOutputSensitivity's).
void FixedStepOutputSensitivity(const MechanicalBoucWenParameters& p, const Eigen::VectorXd& uf,
                                double dt_s, int substeps, bool with_nu, Eigen::VectorXd* y,
                                Eigen::MatrixXd* dy_dp);
/// The mechanical form by CVODE (Adams, `o.rtol`, u between samples as `o.input`; Simulate's
/// CVODE path): y [m] at the n samples u [N], dt_s apart, from rest. With `which` (indices in
/// kMechanicalParameters' order) not empty, also dy/dp of those parameters by CVODES' forward
/// sensitivities (the staggered corrector, the sensitivities outside the error test), into
/// *dy_dp (n x 8, the other columns 0); `dy_dp` may be null when `which` is empty. y is the plain
/// simulation's to the tolerance, not to the bit: the sensitivities' corrector changes the steps
/// (on the fit tests' multisine the residual RMS differs by 5e-6 relative at rtol 1e-6, 1e-9 at
/// rtol 1e-9).
void MechanicalCvode(const MechanicalBoucWenParameters& p, const Eigen::VectorXd& u, double dt_s,
                     const BoucWenSimulationOptions& o, const std::vector<int>& which,
                     Eigen::VectorXd* y, Eigen::MatrixXd* dy_dp);
/// The same on a SampledInput built beforehand (u, dt_s and the input between samples are its
/// own; `o.input` is not read): the result is the overload above's to the bit when `input` is
/// SampledInput(u, dt_s, o.input).
void MechanicalCvode(const MechanicalBoucWenParameters& p, const SampledInput& input,
                     const BoucWenSimulationOptions& o, const std::vector<int>& which,
                     Eigen::VectorXd* y, Eigen::MatrixXd* dy_dp);

/// The piezo form by CVODE (Adams, `rtol`; PiezoBoucWen::SimulateCvode's, which builds `input`
/// with a held input taken linear): y [m] at the samples [V] of `input`, from h = 0.
Eigen::VectorXd PiezoCvode(const PiezoBoucWenParameters& p, const SampledInput& input, double rtol);

/// Throws InputError, before any allocation, when the fixed step over `rows` samples would take
/// more than kMaxSignalSamples steps, or its band-limited input's FFT more than kMaxFftWork.
void CheckFixedStepWork(Eigen::Index rows, int substeps, InputInterpolation how, const char* kind);

/// The fixed step's error estimate by step doubling: the step is second order, so
/// y_m - y_exact ~ C / m^2 and y_m - y_2m ~ (3/4) C / m^2, and the error of y_m is estimated as
/// (4/3) |y_m - y_2m| (Richardson). The RMS over every sample of every recording.
double StepDoublingError(const Eigen::VectorXd& y_m, const Eigen::VectorXd& y_2m);

/// Recordings' inputs u and their sample times dt_s [s], side by side (not owned).
struct SampledRecordings {
  std::vector<const Eigen::VectorXd*> u;
  std::vector<double> dt_s;
};
/// The fixed step's y [m] of every recording at m steps per sample, stacked (CheckFixedStepWork
/// first: InputError past the work bound).
Eigen::VectorXd FixedStepStacked(const MechanicalBoucWenParameters& p, const SampledRecordings& in,
                                 InputInterpolation how, int m);
/// The fixed step's steps per sample at p: the smallest m = 2, 4, ..., 512 whose step-doubling
/// estimate (StepDoublingError of m against 2m over every sample) is within tolerance_m [m];
/// *estimate_m is that estimate. A diverging step counts as too coarse. Throws NumericalError
/// when no m reaches the tolerance, or the work bound comes first.
int ChooseFixedSteps(const MechanicalBoucWenParameters& p, const SampledRecordings& in,
                     InputInterpolation how, double tolerance_m, double* estimate_m);

/// The most operations an FFT of the benchmark chain or of a band-limited input may cost: Eigen's
/// FFT (kissfft) spends about n x (the sum of n's prime factors) on a length n, so a length with
/// a large prime factor (a recording of a prime number of rows, upsampling 997) costs up to n^2.
/// 2e9 is a few seconds: n = 2e7 = 2^8 5^7 costs 1e9.
inline constexpr double kMaxFftWork = 2e9;


/// n x (the sum of n's prime factors, with multiplicity): the work of a length-n FFT.
double FftWork(Eigen::Index n);

/// Throws InputError, before any allocation, when the benchmark chain over `periods` periods of
/// `rows` samples would integrate more than kMaxSignalSamples fine samples (rows x upsampling x
/// periods), or when its FFT upsampling would cost more than kMaxFftWork. `kind` starts the
/// message.
void CheckChainWork(Eigen::Index rows, int upsampling, double periods, const char* kind);

/// Throws InputError when the band-limited interpolant's FFT of `rows` samples would cost more
/// than kMaxFftWork.
void CheckBandLimitedWork(Eigen::Index rows, const char* kind);

/// The piezo form's exact step: h [m] after u moves in a straight line from u0 to u1 [V], from
/// h, with d [m/V], alpha, beta [1/V], gamma [1/V] of type T: double, or a ceres::Jet for the
/// fit's exact Jacobian (the same step differentiated; its branches are taken on the values).
///
/// Along the segment, with direction s = sign(u1 - u0) and progress w = |u - u0|,
/// dh/dw = A - B h with A = s alpha d and B = beta + s sign(h) gamma: exponential in w while h
/// keeps its sign, and h crosses zero at most once (after that it moves with A's sign).
template <typename T>
T PiezoStepOf(const T& d, const T& alpha, const T& beta, const T& gamma, double u0, double u1,
              T h) {
  using std::abs;
  using std::expm1;
  using std::log;
  const double s = u1 > u0 ? 1.0 : u1 < u0 ? -1.0 : 0.0;
  if (s == 0) return h;
  const T a = s * alpha * d;
  T w = T(std::abs(u1 - u0));
  for (int piece = 0; piece < 3 && w > 0; ++piece) {
    const double sigma = h > 0 ? 1.0 : h < 0 ? -1.0 : a > 0 ? 1.0 : a < 0 ? -1.0 : 0.0;
    if (sigma == 0) return T(0);  // h = 0 and no drive
    const T b = beta + s * sigma * gamma;
    // g(w) = (1 - exp(-b w)) / b, w where b w is negligible.
    auto g = [&b](const T& x) { return abs(b * x) < 1e-300 ? x : T(-expm1(-b * x) / b); };
    const T end = h + (a - b * h) * g(w);
    const double end_sign = end > 0 ? 1.0 : end < 0 ? -1.0 : 0.0;
    if (h == 0 || end_sign == sigma || end_sign == 0) return end;
    // h reaches 0 at w*: h + (a - b h) g(w*) = 0.
    T wstar;
    if (abs(b) < 1e-300) {
      wstar = -h / a;
    } else {
      const T ratio = a / (a - b * h);  // exp(-b w*)
      wstar = -log(ratio) / b;
    }
    if (wstar < 0) wstar = T(0);
    if (wstar > w) wstar = w;
    w -= wstar;
    h = T(0);
  }
  return h;
}

inline double PiezoStep(const PiezoBoucWenParameters& p, double u0, double u1, double h) {
  return PiezoStepOf<double>(p.d_m_per_v, p.alpha, p.beta_per_v, p.gamma_per_v, u0, u1, h);
}

/// The piezo form's y [m] at the samples u [V] by the exact step (Simulate's, to the last bit)
/// and its exact Jacobian dy/dp (n x 5: d, alpha, beta, gamma, offset; each in m per the
/// parameter's unit), the step differentiated by ceres::Jet.
void PiezoOutputSensitivity(const PiezoBoucWenParameters& p, const Eigen::VectorXd& u,
                            Eigen::VectorXd* y, Eigen::MatrixXd* dy_dp);

}  // namespace sysid::internal

#endif  // SYSID_SRC_HYSTERESIS_BOUC_WEN_INTERNAL_HPP_
