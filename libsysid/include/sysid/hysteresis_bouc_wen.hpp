// Bouc–Wen hysteresis models (docs/hysteresis.md, "Bouc–Wen"), in two forms:
//
//  - mechanical (the Bouc–Wen benchmark's oscillator, Noël & Schoukens 2016):
//      m y'' + c y' + k y + z = u,
//      z' = alpha y' - beta (gamma |y'| |z|^(nu-1) z + delta y' |z|^nu),
//    u [N] the force, y [m] the displacement, z [N] the hysteretic restoring force;
//  - piezo (Low & Guo 1995; Rakotondrabe 2011):
//      y = d u - h + y0,   h' = alpha d u' - beta |u'| h - gamma u' |h|,
//    u [V] the voltage, y [m] the displacement, h [m] the hysteresis, y0 [m] a sensor offset.
//
// Simulation: CVODE with the input between samples held, linear, or band-limited (the
// trigonometric interpolant of the record taken as one period: exact for a periodic input whose
// lines lie below the Nyquist frequency), or, for the mechanical form, the benchmark's own chain
// (band-limited upsampling, Newmark average acceleration with the trapezoidal rule on z, MATLAB's
// decimate(..., 'fir') by the prime factors of the upsampling), which reproduces the benchmark's
// published outputs.
#ifndef SYSID_HYSTERESIS_BOUC_WEN_HPP_
#define SYSID_HYSTERESIS_BOUC_WEN_HPP_

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "sysid/hysteresis_model.hpp"
#include "sysid/serialize.hpp"

namespace sysid {

struct Recording;

enum class BoucWenForm { kMechanical, kPiezo };

/// How u is taken between its samples.
enum class InputInterpolation {
  kHold,         ///< zero-order hold: u(t) = u_k on [t_k, t_k+1)
  kLinear,       ///< straight lines between samples
  kBandLimited,  ///< the trigonometric interpolant of the record as one period (FFT)
  /// A fit's choice (BoucWenFitOptions' default; see there); a model refuses it.
  kAuto,
};

enum class BoucWenIntegrator {
  kCvode,           ///< CVODE (Adams) with `input` between samples, tolerances rtol/atol
  kBenchmarkChain,  ///< mechanical form only: the Bouc–Wen benchmark's generator (see top)
  /// Mechanical form only: the chain's Newmark/trapezoidal step at `upsampling` steps per sample
  /// on `input` (linear or band-limited) without decimation; second order. A fit chooses the
  /// steps per sample by step doubling (BoucWenFitOptions::fixed_step_tolerance).
  kFixedStep,
  /// A fit's choice (BoucWenFitOptions' default; see there); a model refuses it.
  kAuto,
};

struct BoucWenSimulationOptions {
  BoucWenIntegrator integrator = BoucWenIntegrator::kCvode;
  InputInterpolation input = InputInterpolation::kLinear;  ///< CVODE and the fixed step
  double rtol = 1e-9;  ///< [1] CVODE relative tolerance, in (0, 1e-2]
  /// Benchmark chain and fixed step: integration steps per input sample (the benchmark: 20); the
  /// chain's decimation runs MATLAB's decimate(..., 'fir') once per prime factor, largest last.
  /// In [1, 1000].
  int upsampling = 20;
  /// A model file's "simulation" object, in file order (sysid/serialize.hpp): every key
  /// optional; a model file takes no kAuto (its reader refuses "auto").
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(integrator));
    a->Visit(SYSID_NVP(input));
    a->Visit(SYSID_NVP(rtol).ExclusiveMinimum(0));
    a->Visit(SYSID_NVP(upsampling).Minimum(1).Maximum(1000));
  }
  void Validate() const;  ///< throws OptionsError naming the field and the rule
};

/// BoucWenFitOptions' default simulation: integrator and input kAuto (the CLI's `--integrator
/// auto --input auto`), the rest BoucWenSimulationOptions' defaults.
BoucWenSimulationOptions AutoBoucWenSimulation();

/// The mechanical form's parameters (defaults: the benchmark's true system).
struct MechanicalBoucWenParameters {
  double m_kg = 2;             ///< [kg] mass, > 0
  double c_n_s_per_m = 10;     ///< [N s/m] viscous damping, >= 0
  double k_n_per_m = 5e4;      ///< [N/m] linear stiffness, >= 0
  double alpha_n_per_m = 5e4;  ///< [N/m] hysteretic stiffness, > 0
  double beta_per_m = 1e3;     ///< [1/m^nu] (with z in N: [N^(1-nu)/m]) loop scale, > 0
  double gamma = 0.8;          ///< [1] loop shape, finite
  double delta = -1.1;         ///< [1] loop shape, finite
  double nu = 1;               ///< [1] sharpness, in [1, 10]
  /// A "bouc-wen" model file's "parameters" object, in file order (sysid/serialize.hpp): the
  /// keys are the equation's symbols (units in the file's "units", parameters()); nu may be
  /// left out (1), the ranges are Validate()'s, checked as read.
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(m_kg).Renamed("m").Required().ExclusiveMinimum(0));
    a->Visit(SYSID_NVP(c_n_s_per_m).Renamed("c").Required().Minimum(0));
    a->Visit(SYSID_NVP(k_n_per_m).Renamed("k").Required().Minimum(0));
    a->Visit(SYSID_NVP(alpha_n_per_m).Renamed("alpha").Required().ExclusiveMinimum(0));
    a->Visit(SYSID_NVP(beta_per_m).Renamed("beta").Required().ExclusiveMinimum(0));
    a->Visit(SYSID_NVP(gamma).Required());
    a->Visit(SYSID_NVP(delta).Required());
    a->Visit(SYSID_NVP(nu).Minimum(1).Maximum(10));
  }
  void Validate() const;       ///< throws OptionsError naming the field and the rule
};

/// The piezo form's parameters.
struct PiezoBoucWenParameters {
  double d_m_per_v = 1e-6;    ///< [m/V] piezoelectric coefficient, > 0
  double alpha = 0.2;         ///< [1] hysteresis gain, finite
  double beta_per_v = 0.05;   ///< [1/V] loop shape, finite
  double gamma_per_v = 0.01;  ///< [1/V] loop shape, finite
  double offset_m = 0;        ///< [m] sensor offset y0, finite
  /// A "bouc-wen-piezo" model file's "parameters" object, in file order (sysid/serialize.hpp):
  /// the keys are the equation's symbols (units in the file's "units"); offset may be left out
  /// (0).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(d_m_per_v).Renamed("d").Required().ExclusiveMinimum(0));
    a->Visit(SYSID_NVP(alpha).Required());
    a->Visit(SYSID_NVP(beta_per_v).Renamed("beta").Required());
    a->Visit(SYSID_NVP(gamma_per_v).Renamed("gamma").Required());
    a->Visit(SYSID_NVP(offset_m).Renamed("offset"));
  }
  void Validate() const;      ///< throws OptionsError naming the field and the rule
};

/// The mechanical Bouc–Wen oscillator (kind "bouc-wen"), from rest (y = y' = z = 0). Not
/// invertible (Invert throws NumericalError).
class MechanicalBoucWen : public HysteresisModel {
 public:
  explicit MechanicalBoucWen(const MechanicalBoucWenParameters& p,
                             const BoucWenSimulationOptions& options = {},
                             std::vector<double> std_errors = {});
  std::string kind() const override { return "bouc-wen"; }
  /// y [m] at the samples u [N], dt_s apart. The benchmark chain treats u as periodic for the
  /// upsampling and continues it periodically past its end for the FIR filter's lookahead (as
  /// the benchmark simulated one period more and dropped it).
  Eigen::VectorXd Simulate(const Eigen::VectorXd& u, double dt_s) const override;
  /// The benchmark chain: periods are integrated on the fine grid until two successive periods
  /// agree to `tolerance` [m]; the decimated middle of three steady periods is returned. CVODE:
  /// the interface's default (period doubling).
  Eigen::VectorXd SimulatePeriodic(const Eigen::VectorXd& u_period, double dt_s,
                                   double tolerance = 1e-12, int max_periods = 256) const override;
  bool invertible() const override { return false; }
  Eigen::VectorXd Invert(const Eigen::VectorXd& y_desired, double dt_s) const override;
  /// Throws NumericalError, as Invert.
  std::unique_ptr<HysteresisInverseStepper> InverseStepper(double dt_s) const override;
  /// m, c, k, alpha, beta, gamma, delta, nu.
  std::vector<HysteresisParameter> parameters() const override;
  std::string ToJson(int indent = 2) const override;

  const MechanicalBoucWenParameters& values() const { return p_; }
  const BoucWenSimulationOptions& options() const { return options_; }

 private:
  MechanicalBoucWenParameters p_;
  BoucWenSimulationOptions options_;
  std::vector<double> std_errors_;  // per parameters() entry; empty: unknown
};

/// The piezo Bouc–Wen model (kind "bouc-wen-piezo"), from h = 0. It is rate-independent: for a
/// held or linear input the path of u between samples is a straight segment and h follows it in
/// closed form (exponentials in u, exact); CVODE integrates the band-limited input. Invertible
/// when the loop is monotone (see invertible()): per sample the exact step is solved for u.
class PiezoBoucWen : public HysteresisModel {
 public:
  explicit PiezoBoucWen(const PiezoBoucWenParameters& p,
                        const BoucWenSimulationOptions& options = {},
                        std::vector<double> std_errors = {});
  std::string kind() const override { return "bouc-wen-piezo"; }
  Eigen::VectorXd Simulate(const Eigen::VectorXd& u, double dt_s) const override;
  /// Same, always by CVODE (for the closed form's test); band-limited, held or linear input.
  Eigen::VectorXd SimulateCvode(const Eigen::VectorXd& u, double dt_s) const;
  /// True when d > 0, beta + gamma > 0, beta - gamma >= 0 ... precisely: when y' has the sign of
  /// u' for every h the model can reach, d (1 - alpha) - |beta - gamma| alpha d / (beta + gamma)
  /// > 0 (the reachable |h| is at most alpha d / (beta + gamma)).
  bool invertible() const override;
  /// u [V] with Simulate(u) = y_desired at every sample (to 1e-12 relative), u_0 from h = 0.
  Eigen::VectorXd Invert(const Eigen::VectorXd& y_desired, double dt_s) const override;
  /// A BoucWenInverseStepper (sysid/hysteresis_stepper.hpp; rate-independent: dt_s unused).
  std::unique_ptr<HysteresisInverseStepper> InverseStepper(double dt_s) const override;
  /// d, alpha, beta, gamma, offset.
  std::vector<HysteresisParameter> parameters() const override;
  std::string ToJson(int indent = 2) const override;

  const PiezoBoucWenParameters& values() const { return p_; }
  const BoucWenSimulationOptions& options() const { return options_; }

 private:
  PiezoBoucWenParameters p_;
  BoucWenSimulationOptions options_;
  std::vector<double> std_errors_;
};

/// How the fit gets the Jacobian of the residuals in the parameters.
enum class BoucWenJacobian {
  /// Forward sensitivities, one pass per recording. The benchmark chain and the fixed step: the
  /// Newmark/trapezoidal step differentiated (then the chain's linear FIR decimation), exact to
  /// rounding; the mechanical form by CVODE: CVODES' forward sensitivities (the staggered
  /// corrector, to the simulation's tolerance); the piezo form's closed-form step (held or linear
  /// input): differentiated by ceres::Jet. The piezo form by CVODE (band-limited input): central
  /// differences.
  kSensitivities,
  /// Central differences, 2 p + 1 simulations per Jacobian (p free parameters), in parallel.
  kCentralDifferences,
};

/// One Ceres iteration of a Bouc–Wen fit, for progress reports.
struct BoucWenFitProgress {
  int start = 0;         ///< 1..starts: the perturbed starts; 0: the final fit from the best
  int starts = 0;        ///< BoucWenFitOptions::starts
  int iteration = 0;     ///< Ceres' iteration number within this start (0: the initial point)
  double rms_m = 0;      ///< [m] sqrt(sum (y_model - x)^2 / samples) at the iteration's point
  double elapsed_s = 0;  ///< [s] wall time since the fit began
};

struct BoucWenFitOptions {
  /// How the fit simulates (the benchmark's data: the benchmark chain). With the fixed step its
  /// `upsampling` is chosen by the fit (fixed_step_tolerance). kAuto (the default here, the
  /// CLI's and the Python binding's; one rule for all three, in FitBoucWen):
  ///  - input: the mechanical form's (the chain takes its input band-limited anyway, and
  ///    records linear): band-limited when every recording's u is whole periods of a
  ///    band-limited signal (it wraps from its last sample to its first by no more than its
  ///    largest step, and at most 1e-6 of its variance lies above a quarter of the sampling
  ///    rate) and, with CVODE, CVODE takes it (its band-limited work bound), else linear; the
  ///    piezo form's: linear. The summary's message says which and why;
  ///  - integrator: the mechanical form's fixed step, or CVODE for a held input; the piezo
  ///    form's CVODE setting (its exact closed-form step, CVODE for a band-limited input).
  BoucWenSimulationOptions simulation = AutoBoucWenSimulation();
  /// [1] The fixed step's tolerance, relative to the recordings' output RMS about its mean
  /// (rms(x - mean x)), in (0, 0.1]. The steps per sample m: the smallest power of two (2 to 512)
  /// whose step-doubling estimate (internal::StepDoublingError, m against 2m, at the starting
  /// parameters) is within it. After the fit the model is simulated by CVODE (rtol 1e-9, the same
  /// input; where CVODE refuses the input, step doubling again): past the tolerance m doubles and
  /// the fit continues from its parameters; the summary's message gives m and both errors.
  double fixed_step_tolerance = 1e-4;
  /// Starting values; the mechanical form's default is the linear fit described in
  /// docs/hysteresis.md when `mechanical_initial_given` is false.
  MechanicalBoucWenParameters mechanical_initial;
  bool mechanical_initial_given = false;
  PiezoBoucWenParameters piezo_initial;
  bool piezo_initial_given = false;
  /// Mechanical form: nu is fixed at its initial value unless fit_nu. With nu fixed at 1, beta
  /// only appears as beta*gamma and beta*delta: beta is then fixed too (the products are fit).
  bool fit_nu = false;
  bool fit_beta = false;  ///< only allowed with fit_nu (else beta is unidentifiable)
  int starts = 4;  ///< starting points: the initial values and starts-1 perturbed, in [1, 64]
  double start_spread = 0.3;  ///< [1] perturbation of the extra starts, factor exp(+-spread)
  int start_iterations = 3;   ///< Ceres iterations per start before the best continues
  /// [1] CVODE's relative tolerance while the starts screen, in [simulation.rtol, 1e-2]: when the
  /// mechanical form is fitted by CVODE with CVODES' sensitivities, the starts' iterations run at
  /// it and the best start then continues at simulation.rtol (tolerance continuation: a CVODES
  /// pass on the benchmark costs half at 1e-6 what it costs at 1e-9, and ranking the starts
  /// does not need the last digits). Equal to simulation.rtol: the starts run at the final
  /// tolerance. Unused by the other integrators (exact to rounding), by central differences
  /// (their step would drown in the looser simulation's error) and with one start.
  double start_rtol = 1e-6;
  int max_iterations = 100;   ///< Ceres iterations of the final fit, in [1, 10000]
  std::uint64_t seed = 1;     ///< for the perturbed starts
  /// Threads (0: all cores): the central-difference Jacobian's simulations, or the recordings'
  /// sensitivity passes, in parallel; threads those leave idle run starts side by side (the
  /// same result).
  int threads = 0;
  BoucWenJacobian jacobian = BoucWenJacobian::kSensitivities;
  /// [s] wall-time bound of the whole fit (starts included), >= 0; 0: none. Past it the fit
  /// stops with the best parameters so far (the summary: not converged, the message says the
  /// bound stopped it). Ceres checks it between iterations, so the iteration under way still
  /// runs after it; a start begins only while one iteration's time (the mean so far) is left;
  /// the fixed step's final check against CVODE runs only while the bound has not passed (the
  /// message says when it was skipped).
  double max_time_s = 0;
  /// Called after every Ceres iteration of every start, on the calling thread, start by start
  /// (starts run side by side report once the earlier starts' reports are out; progress
  /// reports; it must not throw). Does not change the result.
  std::function<void(const BoucWenFitProgress&)> on_iteration;
  void Validate() const;      ///< throws OptionsError naming the field and the rule
};

/// Output-error least squares: minimises sum over recordings (columns t [s], u, x [m]; uniform
/// t) of (y_model - x)^2, each recording simulated from the model's initial state, over the
/// form's free parameters (bounded: positives stay positive), from several starting points.
/// Standard errors from s^2 (J^T J)^-1 (s^2 = cost / (samples - free parameters)), NaN for fixed
/// parameters and when J^T J is singular. Throws InputError for unusable recordings.
std::unique_ptr<HysteresisModel> FitBoucWen(BoucWenForm form,
                                            const std::vector<Recording>& recordings,
                                            const BoucWenFitOptions& options,
                                            HysteresisFitSummary* summary = nullptr);

/// A model file written by ToJson (kind "bouc-wen" or "bouc-wen-piezo"); bad values throw
/// InputError "SOURCE:LINE:COL: key: expected ..., found ...".
std::unique_ptr<HysteresisModel> BoucWenModelFromJson(const std::string& text,
                                                      const std::string& source);

/// The benchmark's decimation: MATLAB decimate(x, r, 'fir') — a 31-tap Hamming-window low-pass
/// (fir1(30, 1/r)), zero initial state, its 15-sample delay compensated, then x_f[0], x_f[r], ...
Eigen::VectorXd DecimateFir(const Eigen::VectorXd& x, int r);

/// u, of n samples taken as one period, at `factor` times the rate by its trigonometric
/// interpolant (zero-padding of the FFT; the Nyquist line split in two halves).
Eigen::VectorXd UpsampleBandLimited(const Eigen::VectorXd& u, int factor);

}  // namespace sysid

#endif  // SYSID_HYSTERESIS_BOUC_WEN_HPP_
