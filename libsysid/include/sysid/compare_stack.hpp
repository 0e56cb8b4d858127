// The model table of a stack actuator's data set (docs/hysteresis.md, "Scores on outside
// data"): each hysteresis model fitted on the first part of the recordings and scored on the
// rest, forward (x from u) and inverse (u from x). The pipeline's stack report, `sysid.batch`
// over models x recordings and experiments/hysteresis_benchmark.sh use the same definitions.
#ifndef SYSID_COMPARE_STACK_HPP_
#define SYSID_COMPARE_STACK_HPP_

#include <Eigen/Core>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "sysid/compare_hysteresis.hpp"
#include "sysid/io.hpp"

namespace sysid {

/// One row of the table: a model kind and its fit options under a readable label.
struct HysteresisModelSpec {
  std::string label;  ///< e.g. "PI, 20 operators + offset"
  std::string kind;   ///< HysteresisKinds()
  HysteresisFitOptions options;
};

/// The pipeline's models for a stack (the table of docs/hysteresis.md): classical, asymmetric
/// and rate-dependent PI with 20 operators and an offset, Bouc–Wen in the piezo form, the
/// static network on the dominant variable (nn-operators with 0 operators, H = 10) and the
/// operator-input network (4 operators, H = 10). `threads`: the Bouc–Wen fit's (0: all cores).
std::vector<HysteresisModelSpec> StackModelSpecs(int threads = 0);

/// The fraction of each recording's rows the pipeline fits on (the rest is scored).
inline constexpr double kStackTrainFraction = 0.4;

/// The rows [0, round(train_fraction n)) of a recording (the training part); InputError when
/// that leaves fewer than 2 rows to fit or to score.
Recording TrainingPart(const Recording& recording, double train_fraction);

/// A model fitted on the training parts and scored on the rest.
struct HysteresisSplitScore {
  std::string label;
  std::string kind;
  int parameters = 0;       ///< every parameter of the model (held-at-bound ones too)
  double fit_time_s = 0;    ///< [s] wall time of the fit
  HysteresisFitSummary summary;
  std::shared_ptr<const HysteresisModel> model;  ///< null when the fit failed
  Eigen::Index train_samples = 0;  ///< rows fitted on, over every recording
  Eigen::Index test_samples = 0;   ///< rows scored, over every recording
  /// Forward: the model simulated from each recording's u alone over the whole recording (its
  /// state runs through the training part), e = x_model - x over the scored rows of every
  /// recording; RMS [m] and NRMSE = RMS / std(x over the scored rows) [1].
  double forward_rms_m = std::numeric_limits<double>::quiet_NaN();
  double forward_nrmse_std = std::numeric_limits<double>::quiet_NaN();
  /// Inverse: the model inverted on each recording's measured x (whole recording), e = u_model
  /// - u over the scored rows; RMS [V] and NRMSE = RMS / std(u over the scored rows) [1].
  double inverse_rms_v = std::numeric_limits<double>::quiet_NaN();
  double inverse_nrmse_std = std::numeric_limits<double>::quiet_NaN();
  std::string inverse_error;  ///< why there is no inverse score (the model's reason), else ""
  std::string error;          ///< why there is no score at all (the fit failed), else ""
  /// x_model over each whole recording and u_model (empty without an inverse), for plots.
  std::vector<Eigen::VectorXd> x_model;
  std::vector<Eigen::VectorXd> u_model;
  /// The fields, in file order (sysid/serialize.hpp), a score not computed null; of the fit's
  /// summary its last two (converged, message). The model and the traces are not visited.
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(label).Required());
    a->Visit(SYSID_NVP(kind).Required());
    a->Visit(SYSID_NVP(parameters).Minimum(0).Required());
    a->Visit(SYSID_NVP(fit_time_s).Minimum(0).Required());
    a->Visit(SYSID_NVP(train_samples).Minimum(0).Required());
    a->Visit(SYSID_NVP(test_samples).Minimum(0).Required());
    a->Visit(SYSID_NVP(forward_rms_m).NaNAsNull().Minimum(0).Required());
    a->Visit(SYSID_NVP(forward_nrmse_std).NaNAsNull().Minimum(0).Required());
    a->Visit(SYSID_NVP(inverse_rms_v).NaNAsNull().Minimum(0).Required());
    a->Visit(SYSID_NVP(inverse_nrmse_std).NaNAsNull().Minimum(0).Required());
    a->Visit(SYSID_NVP(inverse_error).Required());
    a->Visit(SYSID_NVP(error).Required());
    FieldSlice<Archive> outcome(a, 4, 2);
    summary.Serialize(&outcome);
  }
};

/// Fits `spec` on the training parts of `recordings` (columns t [s], u [V], x [m]) and scores
/// it as HysteresisSplitScore says. A fit or simulation that fails numerically, and an inverse
/// the model refuses, are recorded in `error` / `inverse_error` (the model's words); bad
/// recordings and options throw (InputError, OptionsError).
HysteresisSplitScore FitAndScoreHysteresis(const HysteresisModelSpec& spec,
                                           const std::vector<Recording>& recordings,
                                           double train_fraction = kStackTrainFraction);

/// {label, kind, parameters, fit_time_s, train_samples, test_samples, forward_rms_m,
/// forward_nrmse_std, inverse_rms_v, inverse_nrmse_std, inverse_error, error, converged, message}
/// (NaN as null).
std::string ToJson(const HysteresisSplitScore& score, int indent = 2);

}  // namespace sysid

#endif  // SYSID_COMPARE_STACK_HPP_
