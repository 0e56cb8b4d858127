// Comparison of inverse models on recordings: the measured voltage beside the analytic inverse
//
//   u_analytic = (x'' + a1 v(t - tau) + a2 sgn v) / a3            (model.hpp)
//
// a neural network's prediction u_nn = net(v[, a]) (nn.hpp) and hysteresis models inverted on the
// recording's x (u = H^-1[x], hysteresis_model.hpp), with error metrics per model.
#ifndef SYSID_COMPARE_HPP_
#define SYSID_COMPARE_HPP_

#include <Eigen/Core>
#include <string>
#include <string_view>
#include <vector>

#include "sysid/hysteresis_model.hpp"
#include "sysid/io.hpp"
#include "sysid/model.hpp"
#include "sysid/nn.hpp"
#include "sysid/serialize.hpp"
#include "sysid/signal.hpp"

namespace sysid {

/// Errors of a predicted voltage against the measured one.
struct PredictionErrors {
  double rmse_v = 0;        ///< [V] sqrt(mean (u_hat - u)^2)
  double peak_error_v = 0;  ///< [V] max |u_hat - u|
  double nrmse_range = 0;         ///< rmse_v / (max u - min u) [dimensionless]
  double r2 = 0;            ///< 1 - SSE / SST (coefficient of determination)
  /// The fields, in file order (sysid/serialize.hpp): NaN (no samples to compare) is null.
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(rmse_v).NaNAsNull().Minimum(0).Required());
    a->Visit(SYSID_NVP(peak_error_v).NaNAsNull().Minimum(0).Required());
    a->Visit(SYSID_NVP(nrmse_range).NaNAsNull().Minimum(0).Required());
    a->Visit(SYSID_NVP(r2).NaNAsNull().Required());
  }
};

/// Errors of `predicted` against `measured` (same length, at least 2 samples).
PredictionErrors ComputePredictionErrors(const Eigen::VectorXd& measured,
                                         const Eigen::VectorXd& predicted);

/// The analytic inverse over uniformly sampled signals: v(t - tau) by linear interpolation of
/// v (v before the first sample taken as v[0]). Returns u [V] for each sample. Throws
/// OptionsError for an invalid model (FrictionModel::Validate) or unless 0 < dt_s < inf,
/// InputError when v_mps and a_mps2 differ in length.
Eigen::VectorXd AnalyticInverse(const FrictionModel& model, double dt_s,
                                const Eigen::VectorXd& v_mps, const Eigen::VectorXd& a_mps2);

/// The network's voltage [V] per sample. Inputs are taken by name: "v" from v_mps [m/s], "a" from
/// a_mps2 [m/s^2], any other name from the column of `recording` (when given). Throws InputError
/// for an input it cannot supply and when v_mps and a_mps2 differ in length.
Eigen::VectorXd NetworkInverse(const NeuralNetwork& network, const Eigen::VectorXd& v_mps,
                               const Eigen::VectorXd& a_mps2, const Recording* recording = nullptr);

/// A hysteresis model's inverse u = H^-1[x] [V] on a recording's x column [m], over the whole
/// recording from the model's initial state, at the recording's sample step. Throws
/// InputError when the recording has no x column or x leaves the model's range (naming the
/// sample), NumericalError with the model's reason when it cannot be inverted.
Eigen::VectorXd HysteresisInverse(const HysteresisModel& model, const Recording& recording);

/// A hysteresis model taking part in a comparison under a label (`sysid compare` uses
/// "KIND:FILE_STEM").
struct NamedHysteresisModel {
  std::string label;
  const HysteresisModel* model = nullptr;
};

/// One hysteresis model's inverse scored on a recording.
struct HysteresisInverseResult {
  std::string label;      ///< NamedHysteresisModel::label
  std::string kind;       ///< HysteresisModel::kind()
  Eigen::VectorXd u_v;    ///< [V] the inverse's voltage, trimmed like u_measured_v
  PredictionErrors errors;
  /// The fields of a `compare --json` "hysteresis" entry, in file order (sysid/serialize.hpp):
  /// the errors beside the label; u_v goes to the traces, not the JSON.
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(label).Required());
    a->Visit(SYSID_NVP(kind).Required());
    a->Visit(SYSID_NVP(errors).Inline());
  }
  /// The traces' column for u_v: "u_" + the label with every character outside [A-Za-z0-9_]
  /// replaced by '_' (a MATLAB variable name for --traces mat).
  std::string TraceColumn() const;
};

struct CompareOptions {
  /// Used when v and a come from x (no v column, or use_recorded_columns = false).
  DerivativeOptions derivative;
  /// The rule of every command (MotionOptions::prefer_velocity_column): the recording's v and
  /// a columns as they are when present; false (the CLI's --derivative): from x.
  bool use_recorded_columns = true;
  /// Samples dropped at each end before scoring (derivative start-up) [samples].
  int trim_samples = 5;
  /// The fields, in file order (sysid/serialize.hpp).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(derivative));
    a->Visit(SYSID_NVP(use_recorded_columns));
    a->Visit(SYSID_NVP(trim_samples));
  }
  void Validate() const;
};

struct InverseComparison {
  std::string source;
  Eigen::VectorXd t_s;           ///< [s]
  Eigen::VectorXd u_measured_v;  ///< [V]
  Eigen::VectorXd u_analytic_v;  ///< [V]; empty without a friction model
  Eigen::VectorXd u_nn_v;        ///< [V]; empty without a network
  Eigen::VectorXd v_mps;         ///< [m/s] velocity used
  Eigen::VectorXd a_mps2;        ///< [m/s^2] acceleration used
  Eigen::VectorXd x_m;           ///< [m] the recording's x, trimmed; empty without an x column
  std::string motion_from;       ///< MotionSource: "columns v, a", "x (central)", ...
  PredictionErrors analytic;  ///< meaningful when has_analytic
  PredictionErrors nn;  ///< meaningful when has_nn
  bool has_analytic = true;
  bool has_nn = false;
  std::vector<HysteresisInverseResult> hysteresis;  ///< in the order given
  /// The traces as a recording: t, u[, u_analytic][, u_nn][, u_<label>...], v, a.
  Recording AsRecording() const;
};

/// Compares the analytic inverse of `model` and (when `network` is not null) the network on one
/// recording with columns t, u and x (or v and a). The network's inputs are taken by name
/// from {v, a} or from the recording's columns. Throws InputError for missing columns.
InverseComparison CompareInverseModels(const Recording& recording, const FrictionModel& model,
                                       const NeuralNetwork* network,
                                       const CompareOptions& options = {});
/// The same with any subset of inverse models: the analytic inverse when `model` is not null,
/// the network when `network` is not null, and each hysteresis model's HysteresisInverse
/// (scored on the same trimmed samples; needs an x column). At least one model; throws
/// OptionsError otherwise, and what HysteresisInverse throws, prefixed with the recording and
/// the model's label.
InverseComparison CompareInverseModels(const Recording& recording, const FrictionModel* model,
                                       const NeuralNetwork* network,
                                       const std::vector<NamedHysteresisModel>& hysteresis,
                                       const CompareOptions& options = {});

/// The options as JSON ({"derivative": {...}, "trim_samples"}) and the reader: every key
/// optional, the result validated, InputError "SOURCE:LINE:COL: NAME: expected ..., found ..."
/// otherwise (as MotionOptionsFromJson).
std::string ToJson(const CompareOptions& options, int indent = 2);
CompareOptions CompareOptionsFromJson(std::string_view text, const std::string& source_name);

/// {"rmse_v", "peak_error_v", "nrmse_range", "r2"} (null where not finite), and back: InputError
/// "SOURCE:LINE:COL: NAME: expected ..., found ..." on bad text.
std::string ToJson(const PredictionErrors& errors, int indent = 2);
PredictionErrors PredictionErrorsFromJson(std::string_view text, const std::string& source_name);
/// One recording as `sysid compare --json` lists it: file, samples, v_a_from (MotionSource),
/// analytic errors (with a friction model), nn errors (with a network) and, with hysteresis
/// models, "hysteresis": [{label, kind, rmse_v, peak_error_v, nrmse_range, r2}]. The traces are not
/// included (AsRecording writes them).
std::string ToJson(const InverseComparison& comparison, int indent = 2);
/// The comparisons as CSV (`sysid compare -o`'s summary.csv): recording (the source's file
/// stem), model ("analytic", "nn", or a hysteresis model's label), rmse_v, peak_error_v,
/// nrmse_range, r2; one row per model.
std::string ComparisonTableCsv(const std::vector<InverseComparison>& comparisons);

}  // namespace sysid

#endif  // SYSID_COMPARE_HPP_
