// Prandtl–Ishlinskii hysteresis models (docs/hysteresis.md, "## Prandtl–Ishlinskii"): a sampled
// input u (voltage [V]) to an output y (displacement [m]) as a weighted sum of play operators.
//
// Play (backlash) operator with threshold r >= 0 [V] and state z [V]:
//   z_k = F_r[u]_k = max(u_k - r, min(u_k + r, z_{k-1})),   z_{-1} = the initial state.
// On samples this is exact for the input linear between samples (the play operator is
// rate-independent and a monotone piece's output depends on its end points only).
//
// The three forms share the operators and a fit by non-negative least squares:
//   pi   (classical, Krasnosel'skii & Pokrovskii; Kuhnen 2003)
//        y_k = p0 u_k + sum_i w_i F_ri[u]_k + c
//   gpi  (asymmetric: a polynomial input function, Gu, Zhu & Su, IEEE TIE 61(3) 2014)
//        y_k = sum_{j=1..m} a_j u_k^j + sum_i w_i F_ri[u]_k + c; the fit holds the even
//        powers at 0 (their a_1 u + a_3 u^3), a_1 >= 0, a_3, a_5 free; dP/du > 0 on the
//        input range is checked afterwards (else the model says it is not invertible)
//   rdpi (rate-dependent weights linear in a rate, after Ang, Khosla & Riviere, IEEE/ASME
//        T-Mech 12(2) 2007)
//        y_k = (p0 + q0 rho_k) u_k + sum_i (w_i + q_i rho_k) F_ri[u]_k + c,
//        rho_k = |u_{k-1} - u_{k-2}| / dt  [V/s]  (the previous step's input rate, so that a
//        step's weights are known before u_k and the inverse is a monotone scalar solve; the
//        inverse feeds its own errors back through the rate with the gain
//        sum q max|u| / (dt p0) and is refused when that reaches 1)
// with p0 (a_1), w_i, q_i >= 0 (the model stays monotone in u), c the sensor offset [m] (free sign).
// The classical model's inverse is again a PI model, in closed form (Kuhnen 2003, eqs. 8–10):
//   r'_i = sum_{j<=i} w_j (r_i - r_j),   w'_0 = 1/w_0,
//   w'_i = -w_i / ((w_0 + ... + w_i)(w_0 + ... + w_{i-1})),  (w_0 = p0, r_0 = 0)
//   u_k = sum_i w'_i F_r'i[y - c]_k.
// The other forms invert by a bracketed monotone scalar solve per sample.
#ifndef SYSID_HYSTERESIS_HPP_
#define SYSID_HYSTERESIS_HPP_

#include <Eigen/Core>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "sysid/hysteresis_model.hpp"
#include "sysid/io.hpp"
#include "sysid/serialize.hpp"

namespace sysid {

/// The most play operators a model may hold (fits, files, the CLI's --operators).
inline constexpr int kMaxPlayOperators = 200;

/// One play-operator step: max(u - r, min(u + r, z_prev)) [V].
inline double PlayStep(double u, double r, double z_prev) {
  const double lo = u - r, hi = u + r;
  return z_prev < lo ? lo : (z_prev > hi ? hi : z_prev);
}

/// F_r[u] over the samples u from the state z0 [V] (the output before the first sample).
/// Throws OptionsError for r < 0 or non-finite r, z0.
Eigen::VectorXd PlayOperator(const Eigen::VectorXd& u, double r, double z0 = 0);

enum class PiForm {
  kClassical,      ///< "pi"
  kPolynomial,     ///< "gpi": polynomial input function (asymmetric)
  kRateDependent,  ///< "rdpi": weights linear in the input rate
};
std::string ToString(PiForm form);
/// "pi", "gpi" or "rdpi"; OptionsError otherwise.
PiForm PiFormFromString(const std::string& name);

/// The parameters of a Prandtl–Ishlinskii model, in SI units (u in V, y in m).
struct PiParameters {
  PiForm form = PiForm::kClassical;
  std::vector<double> thresholds;   ///< r_i [V], 0 < r_1 < ... < r_n, n <= kMaxPlayOperators
  std::vector<double> weights;      ///< w_i [m/V], one per threshold
  /// a_j [m/V^j], j = 1..m: pi and rdpi hold a_1 = p0 only; gpi m >= 2.
  std::vector<double> polynomial;
  /// rdpi only: q_0, q_1..q_n [m s/V^2] (the rate parts of p0 and w_i); empty otherwise.
  std::vector<double> rate_weights;
  double offset_m = 0;              ///< c [m]
  double initial_input_v = 0;       ///< [V] the input before the first sample
  /// z_i(-1) [V], one per threshold, a state some input history reaches (|z_i - z_{i-1}| <=
  /// r_i - r_{i-1}, z_{-1} = initial_input_v, r_{-1} = 0); empty: all equal to initial_input_v
  /// (the operators at rest at that input).
  std::vector<double> initial_state;
  double input_min_v = 0;           ///< [V] the training input range (Invert's domain)
  double input_max_v = 0;           ///< [V] > input_min_v
  /// A PI model file's fields, in file order (sysid/serialize.hpp): the form is the file's
  /// "kind", rate_weights is written for rdpi only, the initial state and input may be left out
  /// (at rest at 0 V); the sizes and rules are Validate()'s.
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(form).Renamed("kind").Required());
    a->Visit(SYSID_NVP(thresholds).Required());
    a->Visit(SYSID_NVP(weights).Required());
    a->Visit(SYSID_NVP(polynomial).Required());
    a->Visit(SYSID_NVP(rate_weights).OmitEmpty());
    a->Visit(SYSID_NVP(offset_m).Required());
    a->Visit(SYSID_NVP(initial_input_v));
    a->Visit(SYSID_NVP(initial_state));
    a->Visit(SYSID_NVP(input_min_v).Required());
    a->Visit(SYSID_NVP(input_max_v).Required());
  }
  /// Validate() and throw OptionsError naming the field ("thresholds[3]") and the rule.
  void Validate() const;
};

struct PiFitOptions {
  PiForm form = PiForm::kClassical;
  /// n, the play operators with threshold > 0 (1..kMaxPlayOperators); ignored when
  /// `thresholds` is given.
  int operators = 10;
  /// [V] given thresholds, 0 < r_1 < ... < r_n; empty: uniform r_i = i R / (n + 1),
  /// R = (max u - min u) / 2 over the training recordings.
  std::vector<double> thresholds;
  bool offset = true;           ///< fit the sensor offset c [m]; false: c = 0
  int polynomial_degree = 3;    ///< gpi: m, the input polynomial's degree (3..5; odd powers fitted)
  /// Warn when the inverse's gain spread (largest over smallest slope of the loading curves,
  /// an upper bound of the inverse's condition) exceeds this [dimensionless].
  double ill_conditioned_ratio = 1e6;
  /// Invert accepts inputs within the training range widened by this fraction of its span on
  /// each side [dimensionless]; beyond, the reference is out of the model's range.
  double range_margin = 0.05;
  void Validate() const;  ///< OptionsError naming the field and the rule
};

/// What a Prandtl–Ishlinskii fit found beside the parameters.
struct PiFitReport {
  std::vector<std::string> active_constraints;  ///< parameters held at their bound 0
  double condition_number = 0;      ///< of the regression matrix's free columns (2-norm)
  double inverse_gain_ratio = 0;    ///< largest / smallest slope of the model's loading curves
  bool ill_conditioned_inverse = false;  ///< inverse_gain_ratio > the options' limit
  double residual_std = 0;          ///< [m] sqrt(RSS / (N - free parameters))
};

/// A Prandtl–Ishlinskii model (any form). Immutable; thread-safe to simulate.
class PrandtlIshlinskiiModel : public HysteresisModel {
 public:
  /// Throws OptionsError (PiParameters::Validate) for invalid parameters. `std_errors`, when
  /// not empty, is aligned with parameters() (NaN where unknown).
  explicit PrandtlIshlinskiiModel(PiParameters p, std::vector<double> std_errors = {},
                                  double range_margin = 0.05);

  std::string kind() const override { return ToString(p_.form); }
  Eigen::VectorXd Simulate(const Eigen::VectorXd& u, double dt_s) const override;
  bool invertible() const override { return why_not_invertible_.empty(); }
  /// Closed form (pi) or a bracketed scalar solve per sample (gpi, rdpi). NumericalError when
  /// not invertible (the reason names the parameter); InputError naming the sample when y
  /// needs an input outside the training range widened by range_margin.
  Eigen::VectorXd Invert(const Eigen::VectorXd& y_desired, double dt_s) const override;
  /// A PiInverseStepper (sysid/hysteresis_stepper.hpp).
  std::unique_ptr<HysteresisInverseStepper> InverseStepper(double dt_s) const override;
  std::vector<HysteresisParameter> parameters() const override;
  std::string ToJson(int indent = 2) const override;

  const PiParameters& pi() const { return p_; }
  double range_margin() const { return range_margin_; }
  /// Why Invert is unavailable, naming the parameter; empty when invertible.
  const std::string& why_not_invertible() const { return why_not_invertible_; }
  /// pi only: the inverse model's parameters (thresholds r'_i [m], weights w'_i [V/m], w'_0 as
  /// polynomial[0], its initial state), a classical PI in y - c. NumericalError when not
  /// invertible or not classical.
  PiParameters InverseParameters() const;
  /// Largest / smallest slope of the loading curves dy/du over the input range.
  double InverseGainRatio() const;
  /// The JSON text of the model with `fit_json` (an object's text) under "fit" when not empty.
  std::string ToJson(int indent, const std::string& fit_json) const;

 private:
  PiParameters p_;
  std::vector<double> std_errors_;
  double range_margin_ = 0.05;
  std::string why_not_invertible_;
};

/// Fits a PI model of options.form to recordings (columns t [s], u [V], x [m]; each from the
/// model's initial state, u before each recording's first sample taken as its first sample)
/// by non-negative least squares (Ceres with lower bounds, then an exact solve on the free
/// set). Throws OptionsError / InputError (naming the recording and column).
std::unique_ptr<PrandtlIshlinskiiModel> FitPrandtlIshlinskii(
    const std::vector<Recording>& recordings, const PiFitOptions& options = {},
    HysteresisFitSummary* summary = nullptr, PiFitReport* report = nullptr);

/// Reads a PI model file's text ({"kind": "pi"|"gpi"|"rdpi", ...}); `source` names it in
/// errors "SOURCE:LINE:COL: NAME: expected ..., found ...". Throws InputError.
std::unique_ptr<PrandtlIshlinskiiModel> PrandtlIshlinskiiFromJson(std::string_view text,
                                                                  const std::string& source);

/// The uniform thresholds r_i = i R / (n + 1), R = (u_max - u_min) / 2 [V].
std::vector<double> UniformThresholds(double u_min, double u_max, int n);

/// The sampling interval of a recording's t column [s] (median interval); InputError naming
/// the recording when it has fewer than 2 samples.
double RecordingStep(const Recording& recording);

}  // namespace sysid

#endif  // SYSID_HYSTERESIS_HPP_
