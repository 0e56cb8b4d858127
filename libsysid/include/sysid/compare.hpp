// Comparison of inverse models on recordings: the measured voltage beside the analytic inverse
//
//   u_analytic = (x'' + a1 v(t - tau) + a2 sgn v) / a3            (model.hpp)
//
// and a neural network's prediction u_nn = net(v[, a]) (nn.hpp), with error metrics per model.
#ifndef SYSID_COMPARE_HPP_
#define SYSID_COMPARE_HPP_

#include <Eigen/Core>
#include <string>
#include <string_view>
#include <vector>

#include "sysid/io.hpp"
#include "sysid/model.hpp"
#include "sysid/nn.hpp"
#include "sysid/signal.hpp"

namespace sysid {

/// Errors of a predicted voltage against the measured one.
struct PredictionErrors {
  double rmse_v = 0;        ///< [V] sqrt(mean (u_hat - u)^2)
  double peak_error_v = 0;  ///< [V] max |u_hat - u|
  double nrmse = 0;         ///< rmse_v / (max u - min u) [dimensionless]
  double r2 = 0;            ///< 1 - SSE / SST (coefficient of determination)
};

/// Errors of `predicted` against `measured` (same length, at least 2 samples).
PredictionErrors ComputePredictionErrors(const Eigen::VectorXd& measured,
                                         const Eigen::VectorXd& predicted);

/// The analytic inverse over uniformly sampled signals: v(t - tau) by linear interpolation of
/// v (v before the first sample taken as v[0]). Returns u [V] for each sample. Throws
/// InputError when v_mps and a_mps2 differ in length, OptionsError unless 0 < dt_s < inf.
Eigen::VectorXd AnalyticInverse(const FrictionModel& model, double dt_s,
                                const Eigen::VectorXd& v_mps, const Eigen::VectorXd& a_mps2);

/// The network's voltage [V] per sample. Inputs are taken by name: "v" from v_mps [m/s], "a" from
/// a_mps2 [m/s^2], any other name from the column of `recording` (when given). Throws InputError
/// for an input it cannot supply and when v_mps and a_mps2 differ in length.
Eigen::VectorXd NetworkInverse(const NeuralNetwork& network, const Eigen::VectorXd& v_mps,
                               const Eigen::VectorXd& a_mps2, const Recording* recording = nullptr);

struct CompareOptions {
  /// Used when v and a come from x (no v column, or use_recorded_columns = false).
  DerivativeOptions derivative;
  /// The rule of every command (MotionOptions::prefer_velocity_column): the recording's v and
  /// a columns as they are when present; false (the CLI's --derivative): from x.
  bool use_recorded_columns = true;
  /// Samples dropped at each end before scoring (derivative start-up) [samples].
  int trim_samples = 5;
  void Validate() const;
};

struct InverseComparison {
  std::string source;
  Eigen::VectorXd t_s;           ///< [s]
  Eigen::VectorXd u_measured_v;  ///< [V]
  Eigen::VectorXd u_analytic_v;  ///< [V]
  Eigen::VectorXd u_nn_v;        ///< [V]; empty without a network
  Eigen::VectorXd v_mps;         ///< [m/s] velocity used
  Eigen::VectorXd a_mps2;        ///< [m/s^2] acceleration used
  std::string motion_from;       ///< MotionSource: "columns v, a", "x (central)", ...
  PredictionErrors analytic;
  PredictionErrors nn;  ///< meaningful when has_nn
  bool has_nn = false;
  /// The traces as a recording: t, u, u_analytic[, u_nn], v, a.
  Recording AsRecording() const;
};

/// Compares the analytic inverse of `model` and (when `network` is not null) the network on one
/// recording with columns t, u and x (or v and a). The network's inputs are taken by name
/// from {v, a} or from the recording's columns. Throws InputError for missing columns.
InverseComparison CompareInverseModels(const Recording& recording, const FrictionModel& model,
                                       const NeuralNetwork* network,
                                       const CompareOptions& options = {});

/// The options as JSON ({"derivative": {...}, "trim_samples"}) and the reader: every key
/// optional, the result validated, InputError "SOURCE:LINE:COL: NAME: expected ..., found ..."
/// otherwise (as MotionOptionsFromJson).
std::string ToJson(const CompareOptions& options, int indent = 2);
CompareOptions CompareOptionsFromJson(std::string_view text, const std::string& source_name);

/// {"rmse_v", "peak_error_v", "nrmse", "r2"} (null where not finite), and back: InputError
/// "SOURCE:LINE:COL: NAME: expected ..., found ..." on bad text.
std::string ToJson(const PredictionErrors& errors, int indent = 2);
PredictionErrors PredictionErrorsFromJson(std::string_view text, const std::string& source_name);
/// One recording as `sysid compare --json` lists it: file, samples, v_a_from (MotionSource),
/// analytic errors and (with a network) nn errors. The traces are not included (AsRecording
/// writes them).
std::string ToJson(const InverseComparison& comparison, int indent = 2);
/// The comparisons as CSV (`sysid compare -o`'s summary.csv): recording (the source's file
/// stem), model ("analytic", "nn"), rmse_v, peak_error_v, nrmse, r2; one row per model.
std::string ComparisonTableCsv(const std::vector<InverseComparison>& comparisons);

}  // namespace sysid

#endif  // SYSID_COMPARE_HPP_
