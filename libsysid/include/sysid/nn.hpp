// Neural inverse models: a static feedforward network with n inputs, one hidden layer of H tanh
// units and one linear output,
//
//   z_i = 2 (x_i - x_i,min) / (x_i,max - x_i,min) - 1          (MATLAB mapminmax, per input)
//   y   = w2 . tanh(W1 z + b1) + b2                           (normalised output)
//   u   = u_min + (y + 1) (u_max - u_min) / 2                 (inverse mapminmax) [output unit]
//
// trained by Levenberg–Marquardt on the normalised residuals r_k = y_k - y_target,k. Parameters
// are packed as theta = [W1 (H x n, row-major), b1 (H), w2 (H), b2] (P = H n + 2 H + 1).
//
// Model files are JSON: {"type": "tanh-mlp", "inputs": [{"name","unit","min","max"}...],
// "output": {"name","unit","min","max"}, "hidden": H, "W1": [[...] x H], "b1": [...],
// "W2": [...], "b2": x, "note": "..."}; a "training" object may ride along and is ignored.
#ifndef SYSID_NN_HPP_
#define SYSID_NN_HPP_

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "sysid/io.hpp"
#include "sysid/serialize.hpp"
#include "sysid/termination.hpp"

namespace sysid {

/// A named variable and its mapminmax range: `min` maps to -1 and `max` to +1.
struct ScaledVariable {
  std::string name;  ///< CSV column / symbol: "v", "a", "u"
  std::string unit;  ///< SI unit, e.g. "m/s", "m/s^2", "V"
  double min = -1;   ///< [unit] value mapped to -1
  double max = 1;    ///< [unit] value mapped to +1; must exceed min

  double Normalize(double x) const { return 2.0 * (x - min) / (max - min) - 1.0; }
  double Denormalize(double z) const { return min + 0.5 * (z + 1.0) * (max - min); }
  /// A network file's variable object, in file order (sysid/serialize.hpp); a file without
  /// "unit" takes DefaultUnit(name), and max > min is the file reader's check.
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(name).Required());
    a->Visit(SYSID_NVP(unit));
    a->Visit(SYSID_NVP(min).Required());
    a->Visit(SYSID_NVP(max).Required());
  }
};

/// The SI unit of a well-known symbol (t, u, x, v, a), or "" when unknown.
std::string DefaultUnit(std::string_view symbol);

/// The most hidden units a network may have (`train --hidden`, a network file's "hidden", the
/// NeuralNetwork constructor): a typo such as 10^9 is refused before allocating gigabytes.
inline constexpr int kMaxHiddenUnits = 100000;

/// A one-hidden-layer tanh network with input and output scaling.
class NeuralNetwork {
 public:
  NeuralNetwork() = default;
  /// A network with all weights zero. Throws OptionsError for hidden outside
  /// [1, kMaxHiddenUnits], no inputs or an empty/inverted range.
  NeuralNetwork(std::vector<ScaledVariable> inputs, ScaledVariable output, int hidden);

  const std::vector<ScaledVariable>& inputs() const { return inputs_; }
  const ScaledVariable& output() const { return output_; }
  std::vector<std::string> input_names() const;
  int input_count() const { return static_cast<int>(inputs_.size()); }
  int hidden_size() const { return static_cast<int>(b1_.size()); }
  /// P = H n + 2 H + 1.
  int parameter_count() const { return hidden_size() * (input_count() + 2) + 1; }

  const Eigen::MatrixXd& W1() const { return W1_; }  ///< H x n (normalised units)
  const Eigen::VectorXd& b1() const { return b1_; }  ///< H
  const Eigen::VectorXd& w2() const { return w2_; }  ///< H
  double b2() const { return b2_; }

  /// theta = [W1 row-major, b1, w2, b2].
  Eigen::VectorXd parameters() const;
  /// Sets theta; throws OptionsError when its size is not parameter_count().
  void set_parameters(const Eigen::VectorXd& theta);
  void set_input_range(int i, double min, double max);
  void set_output_range(double min, double max);

  /// Output [output unit] for one input vector in physical units (size n). No allocation.
  double Evaluate(const Eigen::Ref<const Eigen::VectorXd>& x) const;
  /// Outputs for the rows of X (N x n, physical units, columns in inputs() order).
  Eigen::VectorXd EvaluateBatch(const Eigen::MatrixXd& X) const;

  /// Free text carried in the model file (e.g. how the scaling was chosen).
  std::string note;

  /// Throws OptionsError naming the field and the rule (finite weights, min < max, sizes).
  void Validate() const;

 private:
  std::vector<ScaledVariable> inputs_;
  ScaledVariable output_;
  Eigen::MatrixXd W1_;
  Eigen::VectorXd b1_, w2_;
  double b2_ = 0;
};

/// Parses a network model file's text; `source` names it in errors ("FILE:LINE:COLUMN: ...").
/// Unknown keys are errors. Throws InputError.
NeuralNetwork ParseNeuralNetwork(std::string_view json_text, const std::string& source);
/// Reads a network model file. Throws InputError.
NeuralNetwork ReadNeuralNetwork(const std::string& path);
/// The network as JSON text. `extra_json`, when not empty, must be a JSON object text and is
/// stored under the key "training" (reports ride along with the weights).
std::string NeuralNetworkToJson(const NeuralNetwork& net, int indent = 2,
                                const std::string& extra_json = "");
/// Writes a network model file atomically.
void WriteNeuralNetwork(const std::string& path, const NeuralNetwork& net,
                        const std::string& extra_json = "");

/// Training or test data in physical units.
struct NeuralDataset {
  std::vector<std::string> input_names;  ///< column names, in network input order
  std::string output_name;               ///< target column name
  Eigen::MatrixXd inputs;                ///< N x n
  Eigen::VectorXd targets;               ///< N
  std::string source;                    ///< file name for messages
  Eigen::Index size() const { return targets.size(); }
};

/// Picks the named columns from a recording. Throws InputError naming the missing column.
NeuralDataset MakeNeuralDataset(const Recording& recording,
                                const std::vector<std::string>& input_names,
                                const std::string& output_name);
/// Reads a recording (CSV, MAT or HDF5 through `mapping`) with the input and output columns
/// ("t" optional). Throws InputError.
NeuralDataset ReadNeuralDataset(const std::string& path,
                                const std::vector<std::string>& input_names,
                                const std::string& output_name, const SourceMapping& mapping = {});

/// Every `stride`-th row (rows 0, stride, 2 stride, ...); stride <= 1 returns the set unchanged.
/// The typical (v, a) network's 481 parameters make each LM epoch cost N P^2 flops: the
/// pipeline and the stage facts train it on every 2nd row.
NeuralDataset SubsampleRows(const NeuralDataset& data, int stride);

/// Mean of (net(x_k) - target_k)^2 over the set [output unit^2].
double MeanSquaredError(const NeuralNetwork& net, const NeuralDataset& data);

enum class NeuralTrainer {
  kLevenbergMarquardt,  ///< the paper's rule with trainlm's mu schedule (this library)
  kCeres,               ///< Ceres' Levenberg–Marquardt on the same residuals
};
enum class NeuralInit {
  kNguyenWidrow,  ///< MATLAB initnw: |W1 row| = 0.7 H^(1/n), b1 spread over [-|.|, |.|]
  kUniform,       ///< W1, b1 ~ U(-2, 2), w2 ~ N(0, 1/H), b2 = 0 (the Python peer's rule)
};
enum class TrainingStop {
  kMaxEpochs,           ///< epoch == max_epochs
  kGoalReached,         ///< training MSE <= goal_mse
  kSmallGradient,       ///< ||g|| < gradient_tolerance
  kMuTooLarge,          ///< mu > mu_max (no step lowers the error)
  kValidationFailures,  ///< validation MSE rose max_validation_failures epochs in a row
  kConverged,           ///< Ceres: function or parameter tolerance reached
  kNumericalFailure,    ///< NaN/Inf or divergence; the best finite weights are kept
};
std::string ToString(TrainingStop stop);
/// The shared vocabulary (termination.hpp): a goal, a small gradient, mu too large (no step
/// lowers the error: a stationary point), early stopping on validation and Ceres' tolerances
/// are kConverged; max epochs is kBudgetExhausted; a numerical failure is kFailure.
Termination TerminationOf(TrainingStop stop);
std::string ToString(NeuralTrainer trainer);

/// [bytes] Training refuses (OptionsError) before allocating when its estimated memory,
/// 16 P^2 + 8 N H for P weights and N training rows, passes this limit.
inline constexpr double kTrainingMemoryLimitBytes = 4e9;

/// One epoch of training (one accepted or final step).
struct EpochRecord {
  int epoch = 0;              ///< 1-based
  int restart = 0;            ///< which initialisation
  double mu = 0;              ///< mu after this epoch (Ceres: 1 / trust region radius)
  double train_mse = 0;       ///< [output unit^2]
  double validation_mse = 0;  ///< [output unit^2], NaN without a validation set
  double gradient_norm = 0;   ///< ||2 J'e / N||_2 in normalised units at the epoch's start
  /// The fields of a training report's "history" entry, in file order (sysid/serialize.hpp).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(restart).Minimum(0).Required());
    a->Visit(SYSID_NVP(epoch).Minimum(0).Required());
    a->Visit(SYSID_NVP(mu).Minimum(0).Required());
    a->Visit(SYSID_NVP(train_mse).Minimum(0).Required());
    a->Visit(SYSID_NVP(validation_mse).NaNAsNull().Minimum(0).Required());
    a->Visit(SYSID_NVP(gradient_norm).Minimum(0).Required());
  }
};

struct NeuralTrainingOptions {
  int hidden = 24;  ///< H, number of tanh units (>= 1)
  NeuralTrainer trainer = NeuralTrainer::kLevenbergMarquardt;
  NeuralInit init = NeuralInit::kNguyenWidrow;
  double momentum = 0.0;  ///< alpha in w += -(J'J + mu I)^-1 J'e + alpha dw_prev, [0, 1)
  /// After every trial step, replace (w2, b2) by their linear least-squares optimum for the
  /// trial's hidden layer (the output layer is linear: a partial variable projection). The
  /// step is still accepted only if it lowers the error. false: the paper's rule exactly.
  /// Library LM trainer only: Validate() rejects it with trainer = kCeres.
  bool solve_output_layer = false;
  double mu_initial = 1e-3;          ///< initial mu (trainlm: 1e-3); Ceres: 1/mu = trust radius
  double mu_decrease = 0.1;          ///< mu *= this after a successful step, in (0, 1)
  double mu_increase = 10.0;         ///< mu *= this after a failed step, > 1
  double mu_max = 1e10;              ///< stop when mu > mu_max
  double gradient_tolerance = 1e-7;  ///< stop when ||2 J'e / N||_2 < this (normalised units)
  int max_epochs = 1000;             ///< epoch limit (>= 0)
  int max_validation_failures = 6;   ///< consecutive epochs with validation MSE above its best
  double goal_mse = 0.0;             ///< [output unit^2] stop when training MSE <= goal_mse
  std::uint64_t seed = 1;            ///< initialisation seed; restart r uses seed + r
  int restarts = 1;                  ///< independent initialisations; the best one is kept
  /// Fixed input ranges (mapminmax min/max per input, physical units); empty: the training
  /// data's min/max (MATLAB's default).
  std::vector<std::pair<double, double>> input_ranges;
  /// Fixed output range; unset: the training targets' min/max. {-1, 1} leaves y unscaled.
  std::optional<std::pair<double, double>> output_range;
  /// Starting parameters theta (size P); when set, init/seed/restarts are not used.
  std::optional<Eigen::VectorXd> initial_parameters;
  /// Ceres only: samples per residual block (the Jacobian is evaluated block by block).
  int ceres_block_size = 512;
  /// Threads for one network's LM epoch (Jacobian, J'J and forward passes); 0: all cores.
  /// Results are identical for any value (fixed-order reductions). The Ceres trainer runs on
  /// one thread (its parallel evaluator's sums depend on the schedule).
  int threads = 0;
  /// When set, asked before each parallel pass of the LM trainer for its thread count instead
  /// of `threads`: a network trained beside others (SweepHiddenSize, the pipeline) takes over
  /// their threads when they finish. Results are identical for any answer.
  std::function<int()> threads_now;
  /// Called after every epoch of every restart, on the training thread (progress reports; it
  /// must not throw). Does not change the result. SweepHiddenSize ignores it (its networks
  /// train side by side): use HiddenSweepOptions::on_network there.
  std::function<void(const EpochRecord&)> on_epoch;
  /// Throws OptionsError naming the field and the violated rule.
  /// The fields, in file order (sysid/serialize.hpp).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(hidden));
    a->Visit(SYSID_NVP(trainer));
    a->Visit(SYSID_NVP(init));
    a->Visit(SYSID_NVP(momentum));
    a->Visit(SYSID_NVP(solve_output_layer));
    a->Visit(SYSID_NVP(mu_initial));
    a->Visit(SYSID_NVP(mu_decrease));
    a->Visit(SYSID_NVP(mu_increase));
    a->Visit(SYSID_NVP(mu_max));
    a->Visit(SYSID_NVP(gradient_tolerance));
    a->Visit(SYSID_NVP(max_epochs));
    a->Visit(SYSID_NVP(max_validation_failures));
    a->Visit(SYSID_NVP(goal_mse));
    a->Visit(SYSID_NVP(seed));
    a->Visit(SYSID_NVP(restarts));
    a->Visit(SYSID_NVP(input_ranges));
    a->Visit(SYSID_NVP(output_range));
    a->Visit(SYSID_NVP(initial_parameters));
    a->Visit(SYSID_NVP(ceres_block_size));
    a->Visit(SYSID_NVP(threads));
  }
  void Validate() const;
};


/// The under-trained test: whether the training MSE of restart `restart` in `history` was still
/// falling at its last epoch, i.e. fell by more than kStillFallingFraction of its value over
/// the last max(kStillFallingMinEpochs, epochs / 10) epochs (all of them when fewer). A run
/// with fewer than two epochs counts as still falling (nothing shows it settled).
inline constexpr double kStillFallingFraction = 0.01;
inline constexpr int kStillFallingMinEpochs = 5;
bool TrainingMseStillFalling(const std::vector<EpochRecord>& history, int restart);

struct NeuralTrainingResult {
  NeuralNetwork network;  ///< best weights (lowest validation MSE, else training MSE)
  Termination termination = Termination::kBudgetExhausted;  ///< TerminationOf(stop)
  TrainingStop stop = TrainingStop::kMaxEpochs;             ///< the stopping rule that fired
  std::string message;               ///< why it stopped, in words
  int epochs = 0;                    ///< epochs of the kept restart
  int restart = 0;                   ///< index of the kept restart
  double train_mse = 0;              ///< [output unit^2] of the kept network
  double validation_mse = 0;         ///< [output unit^2], NaN without a validation set
  double wall_time_s = 0;            ///< [s]
  std::vector<EpochRecord> history;  ///< every epoch of every restart
  /// TrainingMseStillFalling of the kept restart: the training MSE was still going down when
  /// training stopped.
  bool still_falling = false;
  /// Doubts in words: stopped by the epoch budget while the training MSE was still falling
  /// (under-trained). A budget stop on a plateau is not a doubt and gives no warning.
  std::vector<std::string> warnings;
  /// The fields of `sysid train --json` after the options' (hidden, parameters, trainer, ...),
  /// in file order (sysid/serialize.hpp); the network lives in its own file and still_falling
  /// is said by the warnings.
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(restart).Minimum(0).Required());
    a->Visit(SYSID_NVP(epochs).Minimum(0).Required());
    a->Visit(SYSID_NVP(train_mse).Minimum(0).Required());
    a->Visit(SYSID_NVP(validation_mse).NaNAsNull().Minimum(0).Required());
    a->Visit(SYSID_NVP(termination).Required());
    a->Visit(SYSID_NVP(stop).Renamed("stop_reason").Required());
    a->Visit(SYSID_NVP(message).Required());
    a->Visit(SYSID_NVP(warnings).Required());
    a->Visit(SYSID_NVP(wall_time_s).Minimum(0).Required());
    a->Visit(SYSID_NVP(history).Required());
  }
  std::string BriefReport() const;
  /// BriefReport plus every diagnostic: stopping rule, kept restart, MSEs, warnings and the
  /// last epoch of every restart.
  std::string FullReport() const;
};

/// Trains a network on `train` (optionally early-stopped on `validation`, may be null).
/// Throws OptionsError for invalid options and InputError for unusable data (no samples, a
/// constant input column, a range that does not match the inputs, non-finite values).
NeuralTrainingResult TrainNeuralNetwork(const NeuralDataset& train, const NeuralDataset* validation,
                                        const NeuralTrainingOptions& options = {});

struct HiddenSweepRow;

struct HiddenSweepOptions {
  std::vector<int> hidden_sizes{16, 18, 20, 22, 24, 26, 28, 30, 32};  ///< H values to try
  NeuralTrainingOptions training;                                     ///< everything but `hidden`
  int threads = 0;  ///< worker threads; 0: std::thread::hardware_concurrency()
  /// Called when a network has finished, with its row and how many of `total` are done (in
  /// completion order, one call at a time; it must not throw). Does not change the result.
  std::function<void(const HiddenSweepRow& row, size_t done, size_t total)> on_network;
  /// The fields, in file order (sysid/serialize.hpp).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(hidden_sizes));
    a->Visit(SYSID_NVP(training));
    a->Visit(SYSID_NVP(threads));
  }
  void Validate() const;
};

struct HiddenSweepRow {
  int hidden = 0;
  int epochs = 0;
  double train_mse = 0;       ///< [output unit^2]
  double validation_mse = 0;  ///< [output unit^2], NaN without a validation set
  double test_mse = 0;        ///< [output unit^2], NaN without a test set
  TrainingStop stop = TrainingStop::kMaxEpochs;
  bool still_falling = false;  ///< NeuralTrainingResult::still_falling of this network
  double wall_time_s = 0;  ///< [s]
  /// The fields of a sweep's "rows" entry, in file order (sysid/serialize.hpp); still_falling is
  /// said by the sweep's warnings.
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(hidden).Minimum(1).Maximum(kMaxHiddenUnits));
    a->Visit(SYSID_NVP(epochs).Minimum(0));
    a->Visit(SYSID_NVP(train_mse).Minimum(0));
    a->Visit(SYSID_NVP(validation_mse).NaNAsNull().Minimum(0));
    a->Visit(SYSID_NVP(test_mse).NaNAsNull().Minimum(0));
    a->Visit(SYSID_NVP(stop).Renamed("stop_reason"));
    a->Visit(SYSID_NVP(wall_time_s).Minimum(0));
  }
};

struct HiddenSweepResult {
  std::vector<HiddenSweepRow> rows;        ///< in hidden_sizes order
  std::vector<NeuralTrainingResult> runs;  ///< the trained networks, same order
  int chosen = -1;                         ///< index into rows
  /// The rule used: "min validation MSE" when a validation set is given, else "min test MSE"
  /// (the paper's choice), else "min training MSE".
  std::string rule;
  double wall_time_s = 0;  ///< [s]
  std::vector<std::string> warnings;  ///< one per hidden size stopped by the budget while falling
  /// The fields of `sysid sweep --json` after the options' (trainer, momentum, seed), in file
  /// order (sysid/serialize.hpp); the chosen row is written as its "chosen_hidden" after the
  /// rows, the trained networks are not written.
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(rows));
    a->Visit(SYSID_NVP(rule));
    a->Visit(SYSID_NVP(wall_time_s).Minimum(0));
    a->Visit(SYSID_NVP(warnings));
  }
};

/// Trains one network per hidden size, in parallel threads, and picks one by `rule`.
HiddenSweepResult SweepHiddenSize(const NeuralDataset& train, const NeuralDataset* validation,
                                  const NeuralDataset* test, const HiddenSweepOptions& options);

/// Parses "16:32:2" (first:last:step) or "16,20,24" into hidden sizes. Throws OptionsError.
std::vector<int> ParseHiddenSizes(const std::string& spec);

/// A network evaluated on a recording (`sysid predict`).
struct NetworkPrediction {
  std::string column;                 ///< the column the prediction was stored in
  Eigen::Index rows = 0;              ///< rows evaluated
  long rows_outside_input_range = 0;  ///< rows with an input outside the network's range
  /// [output unit^2] against the recording's output column; NaN when it has none.
  double mse = std::numeric_limits<double>::quiet_NaN();
};
/// Evaluates `network` on `recording`'s input columns and stores the prediction as column
/// `column` (empty: "<output>_nn"). Throws InputError for a missing input column, OptionsError
/// (field "column") when the column would replace the output column, or, for the default
/// name, any existing column.
NetworkPrediction PredictColumn(const NeuralNetwork& network, Recording& recording,
                                const std::string& column = "");
/// {"rows", "column", "rows_outside_input_range", "mse" (only when the recording has the
/// output column)}: the summary of `sysid predict --json`.
std::string ToJson(const NetworkPrediction& prediction, int indent = 2);

/// The options as JSON, every field but the callbacks (init "nguyen-widrow" or "uniform";
/// ranges as [min, max]; an unset output_range or initial_parameters as null), and their
/// readers: every key optional, the result validated, InputError "SOURCE:LINE:COL: NAME:
/// expected ..., found ..." otherwise (as MotionOptionsFromJson).
std::string ToJson(const NeuralTrainingOptions& options, int indent = 2);
std::string ToJson(const HiddenSweepOptions& options, int indent = 2);
NeuralTrainingOptions NeuralTrainingOptionsFromJson(std::string_view text,
                                                    const std::string& source_name);
HiddenSweepOptions HiddenSweepOptionsFromJson(std::string_view text,
                                              const std::string& source_name);

/// A training run as `sysid train --json` reports it: hidden, parameters, the trainer options
/// (trainer, momentum, solve_output_layer, seed), restart, epochs, MSEs (null when absent),
/// termination, stop_reason, message, warnings, wall_time_s and the epoch history.
std::string ToJson(const NeuralTrainingResult& result, const NeuralTrainingOptions& options,
                   int indent = 2);
/// Reads what ToJson(NeuralTrainingResult, NeuralTrainingOptions) writes: every result field
/// but `network`, which stays empty (the report carries the parameter count, not the weights:
/// attach the network file's ReadNeuralNetwork). A null MSE reads as NaN. The options part is
/// checked always (hidden, parameters = H n + 2 H + 1, trainer, momentum, solve_output_layer,
/// seed) and stored in `*options` when given (its other fields keep their values). Throws
/// InputError "SOURCE:LINE:COL: NAME: expected ..., found ..." on bad text, including a
/// termination that is not TerminationOf(stop_reason).
NeuralTrainingResult NeuralTrainingResultFromJson(std::string_view text,
                                                  const std::string& source_name,
                                                  NeuralTrainingOptions* options = nullptr);
/// A sweep as `sysid sweep --json` reports it: trainer, momentum, seed, one row per hidden size
/// (hidden, epochs, MSEs, stop_reason, wall_time_s), chosen_hidden, rule, wall_time_s, warnings.
std::string ToJson(const HiddenSweepResult& result, const HiddenSweepOptions& options,
                   int indent = 2);

}  // namespace sysid

#endif  // SYSID_NN_HPP_
