// Validation of an identified model on a held-out recording, as MATLAB's compare and resid do:
// the model is simulated free-run from the recording's input u (no measured output fed back) and
// its output ŷ is scored against the measured y, then the residual e = y - ŷ is tested.
//
//   fit %        = 100 (1 - ||y - ŷ|| / ||y - mean y||)          (MATLAB compare, NRMSE fit)
//   RMSE         = sqrt(mean (y - ŷ)^2)                          [y's unit]
//   nrmse_std    = RMSE / std y   (population std, so fit % = 100 (1 - nrmse_std))
//   nrmse_range  = RMSE / (max y - min y)
//
// Residual tests (Ljung, System Identification, 2nd ed., sec. 16.6; MATLAB resid), on e and u
// with their means removed, N samples:
//
//   r_e(k)  = sum_{t=k}^{N-1} e_t e_{t-k} / sum_t e_t^2,                 k = 1..L
//   r_eu(k) = sum_{t=k}^{N-1} e_t u_{t-k} / sqrt(sum_t e_t^2 sum_t u_t^2), k = 0..L
//
// Each is compared with the 99 % band ±z/sqrt(N), z = 2.58 (the normal 99.5 % quantile): for a
// white residual independent of u each r(k) is about N(0, 1/N). The verdict of a test (one
// statement for L lags, not L statements) fails when
//   (a) more lags leave the band than chance explains: more than the 99th percentile of
//       Binomial(lags, 0.01) (for 25 or 26 lags: 3 or more lags outside), or
//   (b) one lag leaves it further than chance explains for any of the lags: |r(k)| sqrt(N)
//       above the Bonferroni bound z_{1 - 0.01/(2 lags)} (3.54 for 25 lags).
// A white residual fails either with probability about 1 % each, so at most about 2 % in all.
#ifndef SYSID_VALIDATE_HPP_
#define SYSID_VALIDATE_HPP_

#include <Eigen/Core>
#include <string>
#include <vector>

#include "sysid/hysteresis_model.hpp"
#include "sysid/io.hpp"
#include "sysid/model.hpp"
#include "sysid/motion.hpp"
#include "sysid/serialize.hpp"

namespace sysid {

/// How well a simulated output follows the measured one (MATLAB compare's numbers).
struct FitScores {
  double fit_percent = 0;  ///< 100 (1 - ||y - ŷ|| / ||y - mean y||) [%]; -inf..100
  double rmse = 0;         ///< sqrt(mean (y - ŷ)^2) [the output's unit]
  double nrmse_std = 0;    ///< rmse / std y (population std) [dimensionless]
  double nrmse_range = 0;  ///< rmse / (max y - min y) [dimensionless]
  /// The fields, in file order (sysid/serialize.hpp): a score a constant y leaves undefined
  /// (NaN) or a fit of -inf is null.
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(fit_percent).NaNAsNull().Maximum(100).Required());
    a->Visit(SYSID_NVP(rmse).NaNAsNull().Minimum(0).Required());
    a->Visit(SYSID_NVP(nrmse_std).NaNAsNull().Minimum(0).Required());
    a->Visit(SYSID_NVP(nrmse_range).NaNAsNull().Minimum(0).Required());
  }
};

/// Scores `simulated` against `measured` (same length, at least 2 samples, all finite). Throws
/// InputError otherwise. A constant measured y gives fit_percent, nrmse_std and nrmse_range NaN.
FitScores ScoreFit(const Eigen::VectorXd& measured, const Eigen::VectorXd& simulated);

/// r_e(k) for k = 0..max_lag (r_e(0) = 1) of `e` with its mean removed, by the direct sum
/// (formula at the top). Throws InputError when e is constant, OptionsError unless
/// 0 <= max_lag < e.size().
Eigen::VectorXd NormalisedAutocorrelation(const Eigen::VectorXd& e, int max_lag);

/// r_eu(k) for k = 0..max_lag: the residual e against the input u, k samples earlier, both with
/// their means removed. Throws InputError when the lengths differ or either is constant,
/// OptionsError unless 0 <= max_lag < e.size().
Eigen::VectorXd NormalisedCrossCorrelation(const Eigen::VectorXd& e, const Eigen::VectorXd& u,
                                           int max_lag);

struct ResidualTestOptions {
  int max_lag = 25;  ///< L [samples]: lags 1..L (autocorrelation), 0..L (cross); in [1, 1000]
  double z = 2.58;   ///< band half-width in units of 1/sqrt(N) (99 %); in (0, 10]
  double lag_probability = 0.01;  ///< chance a white residual's lag leaves the band; (0, 0.5)
  double test_level = 0.01;       ///< each verdict rule's false-alarm rate; in (0, 0.5)
  void Validate() const;          ///< throws OptionsError naming the field and the rule
  /// The fields (sysid/serialize.hpp); the rules are Validate()'s.
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(max_lag));
    a->Visit(SYSID_NVP(z));
    a->Visit(SYSID_NVP(lag_probability));
    a->Visit(SYSID_NVP(test_level));
  }
};

/// One correlation test with its bounds and verdict.
struct CorrelationTest {
  std::string name;         ///< "autocorrelation" or "cross-correlation with u"
  std::vector<int> lags;    ///< [samples]
  Eigen::VectorXd r;        ///< normalised correlation per lag [dimensionless]
  double bound = 0;         ///< z / sqrt(N): the 99 % band is ±bound
  double strong_bound = 0;  ///< Bonferroni bound over the lags / sqrt(N) (rule (b))
  int outside = 0;          ///< lags with |r| > bound
  int allowed_outside = 0;  ///< rule (a): at most this many lags outside
  double max_abs_r = 0;     ///< max |r| over the lags
  /// false when e or u is constant (a perfect model, a constant input): no correlation is
  /// defined, r is NaN and pass is true.
  bool tested = true;
  bool pass = false;
  std::string verdict;  ///< one sentence: "pass: 1 of 25 lags outside ±0.0816 ..."
  /// The fields, in file order (sysid/serialize.hpp): an untested test's numbers are null.
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(name).Required());
    a->Visit(SYSID_NVP(lags).Required());
    a->Visit(SYSID_NVP(r).Required());
    a->Visit(SYSID_NVP(bound).NaNAsNull().Minimum(0).Required());
    a->Visit(SYSID_NVP(strong_bound).NaNAsNull().Minimum(0).Required());
    a->Visit(SYSID_NVP(outside).Minimum(0).Required());
    a->Visit(SYSID_NVP(allowed_outside).Minimum(0).Required());
    a->Visit(SYSID_NVP(max_abs_r).NaNAsNull().Minimum(0).Required());
    a->Visit(SYSID_NVP(tested).Required());
    a->Visit(SYSID_NVP(pass).Required());
    a->Visit(SYSID_NVP(verdict).Required());
  }
};

/// Rule (a)'s allowance: the smallest k with P(Binomial(lags, p) > k) <= level. Throws
/// OptionsError unless lags >= 1 and p, level in (0, 1).
int AllowedLagsOutside(int lags, double p, double level);
/// The standard normal quantile Φ^-1(q) for q in (0, 1) (bisection on erfc, to 1e-12).
double NormalQuantile(double q);

/// The whiteness test of e (lags 1..L) and the independence test of e and u (lags 0..L).
/// Throws InputError for fewer than 4 (L + 1) samples (the correlations would rest on too few
/// products); a constant e or u gives an untested (tested = false) result.
CorrelationTest AutocorrelationTest(const Eigen::VectorXd& e, const ResidualTestOptions& options);
CorrelationTest CrossCorrelationTest(const Eigen::VectorXd& e, const Eigen::VectorXd& u,
                                     const ResidualTestOptions& options);

/// One output of a model on one recording.
struct OutputValidation {
  std::string output;         ///< "v" or "x"
  std::string unit;           ///< "m/s" or "m"
  Eigen::VectorXd measured;   ///< y [unit]
  Eigen::VectorXd simulated;  ///< ŷ [unit], free-run from u
  FitScores scores;
  CorrelationTest autocorrelation;
  CorrelationTest cross_correlation;
  /// The fields, in file order (sysid/serialize.hpp): the scores beside the output's name; the
  /// signals go to the plots, not the JSON.
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(output).Required());
    a->Visit(SYSID_NVP(unit).Required());
    a->Visit(SYSID_NVP(scores).Inline());
    a->Visit(SYSID_NVP(autocorrelation).Required());
    a->Visit(SYSID_NVP(cross_correlation).Required());
  }
};

/// A model validated on one recording.
struct Validation {
  std::string source;      ///< the recording's source
  std::string model_kind;  ///< "friction" or the hysteresis model's kind()
  Eigen::VectorXd t_s;     ///< [s]
  Eigen::VectorXd u_v;     ///< [V] (or the input's unit)
  std::vector<OutputValidation> outputs;
  /// The fields, in file order (sysid/serialize.hpp); ToJson writes the samples (t_s's
  /// length) after the model, the signals go to the plots.
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(source).Required());
    a->Visit(SYSID_NVP(model_kind).Renamed("model").Required());
    a->Visit(SYSID_NVP(outputs).Required());
  }
};

struct ValidationOptions {
  ResidualTestOptions residual;
  /// Measured v: the recording's v column when present, else derived from x (MotionOptions).
  MotionOptions motion;
  double sim_rtol = 1e-8;   ///< CVODE relative tolerance of the friction simulation
  double sim_atol = 1e-12;  ///< CVODE absolute tolerance [m, m/s]
  void Validate() const;    ///< throws OptionsError naming the field and the rule
  /// The fields (sysid/serialize.hpp); the rules are Validate()'s.
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(residual));
    a->Visit(SYSID_NVP(motion));
    a->Visit(SYSID_NVP(sim_rtol));
    a->Visit(SYSID_NVP(sim_atol));
  }
};

/// The friction model simulated free-run from the recording's u (zero-order hold between
/// samples, the delayed stick–slip simulator of simulate.hpp) from the measured x and v at the
/// first sample (v constant before it), scored on v and x. Throws InputError for a recording
/// without u and x, NumericalError when the simulation fails (with the simulator's reason).
Validation ValidateFrictionModel(const Recording& recording, const FrictionModel& model,
                                 const ValidationOptions& options = {});

/// A hysteresis model simulated from the recording's u from its initial state
/// (HysteresisModel::Simulate at the recording's step), scored on x.
Validation ValidateHysteresisModel(const Recording& recording, const HysteresisModel& model,
                                   const ValidationOptions& options = {});

/// {"source", "model", "samples", "outputs": [{"output", "unit", "fit_percent", "rmse",
/// "nrmse_std", "nrmse_range", "autocorrelation": {...}, "cross_correlation": {...}}]}; each
/// test {"name", "lags", "r", "bound", "strong_bound", "outside", "allowed_outside",
/// "max_abs_r", "tested", "pass", "verdict"}.
std::string ToJson(const Validation& validation, int indent = 2);

}  // namespace sysid

#endif  // SYSID_VALIDATE_HPP_
