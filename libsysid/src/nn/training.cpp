// TrainNeuralNetwork: scaling, seeded initialisation, restarts, and the choice of trainer.
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "core/option_rule.hpp"
#include "core/portable_random.hpp"
#include "nn/mlp_kernels.hpp"
#include "nn/trainers.hpp"
#include "sysid/error.hpp"
#include "sysid/nn.hpp"

namespace sysid {
namespace {

Eigen::VectorXd InitialParameters(NeuralInit init, int n, int H, std::uint64_t seed) {
  internal::PortableRandom rng(seed);
  Eigen::MatrixXd W1(H, n);
  Eigen::VectorXd b1(H), w2(H);
  double b2 = 0;
  if (init == NeuralInit::kNguyenWidrow) {
    // MATLAB initnw for inputs already in [-1, 1]: random directions of length
    // 0.7 H^(1/n), biases spreading the units' centres evenly across the input range.
    const double magnitude = 0.7 * std::pow(static_cast<double>(H), 1.0 / n);
    for (int h = 0; h < H; ++h) {
      for (int i = 0; i < n; ++i) W1(h, i) = rng.Symmetric();
      const double norm = W1.row(h).norm();
      W1.row(h) *= magnitude / (norm > 0 ? norm : 1.0);
      const double spread = H == 1 ? 0.0 : -1.0 + 2.0 * h / (H - 1);
      b1[h] = magnitude * spread * (W1(h, 0) >= 0 ? 1.0 : -1.0);
    }
    for (int h = 0; h < H; ++h) w2[h] = rng.Symmetric();
    b2 = rng.Symmetric();
  } else {
    for (int h = 0; h < H; ++h)
      for (int i = 0; i < n; ++i) W1(h, i) = 2.0 * rng.Symmetric();
    for (int h = 0; h < H; ++h) b1[h] = 2.0 * rng.Symmetric();
    for (int h = 0; h < H; ++h) w2[h] = rng.Normal() / std::sqrt(static_cast<double>(H));
  }
  return internal::nn::PackParameters(W1, b1, w2, b2);
}

void CheckData(const NeuralDataset& d, const char* role, const NeuralDataset* reference) {
  if (d.size() == 0) throw InputError(d.source + ": " + role + " set has no samples");
  if (d.inputs.rows() != d.size() ||
      d.inputs.cols() != static_cast<Eigen::Index>(d.input_names.size()))
    throw InputError(d.source + ": " + role + " set: inputs matrix is " +
                     std::to_string(d.inputs.rows()) + " x " + std::to_string(d.inputs.cols()) +
                     ", expected " + std::to_string(d.size()) + " x " +
                     std::to_string(d.input_names.size()));
  if (!d.inputs.allFinite() || !d.targets.allFinite())
    throw InputError(d.source + ": " + role + " set contains NaN or Inf");
  if (reference &&
      (d.input_names != reference->input_names || d.output_name != reference->output_name))
    throw InputError(d.source + ": " + role + " set columns differ from the training set's");
}

internal::nn::NormalizedData Normalize(const NeuralNetwork& net, const NeuralDataset& d) {
  internal::nn::NormalizedData out;
  out.Z.resize(net.input_count(), d.size());
  for (int i = 0; i < net.input_count(); ++i) {
    const auto& s = net.inputs()[i];
    out.Z.row(i) = (2.0 * (d.inputs.col(i).array() - s.min) / (s.max - s.min) - 1.0).transpose();
  }
  const auto& s = net.output();
  out.y = 2.0 * (d.targets.array() - s.min) / (s.max - s.min) - 1.0;
  return out;
}

// MATLAB mapminmax's range: the data's min and max; a constant column cannot be scaled.
std::pair<double, double> DataRange(const Eigen::VectorXd& x, const std::string& what,
                                    const std::string& source) {
  const double lo = x.minCoeff(), hi = x.maxCoeff();
  if (!(lo < hi))
    throw InputError(source + ": column '" + what + "' is constant (" + std::to_string(lo) +
                     "): mapminmax scaling needs min < max; give a fixed range instead");
  return {lo, hi};
}

}  // namespace

std::string ToString(TrainingStop stop) {
  switch (stop) {
    case TrainingStop::kMaxEpochs:
      return "max_epochs";
    case TrainingStop::kGoalReached:
      return "goal_reached";
    case TrainingStop::kSmallGradient:
      return "small_gradient";
    case TrainingStop::kMuTooLarge:
      return "mu_too_large";
    case TrainingStop::kValidationFailures:
      return "validation_failures";
    case TrainingStop::kConverged:
      return "converged";
    case TrainingStop::kNumericalFailure:
      return "numerical_failure";
  }
  return "unknown";
}

Termination TerminationOf(TrainingStop stop) {
  switch (stop) {
    case TrainingStop::kMaxEpochs:
      return Termination::kBudgetExhausted;
    case TrainingStop::kNumericalFailure:
      return Termination::kFailure;
    case TrainingStop::kGoalReached:
    case TrainingStop::kSmallGradient:
    case TrainingStop::kMuTooLarge:
    case TrainingStop::kValidationFailures:
    case TrainingStop::kConverged:
      return Termination::kConverged;
  }
  return Termination::kFailure;
}

std::string ToString(NeuralTrainer trainer) {
  return trainer == NeuralTrainer::kCeres ? "ceres" : "lm";
}

void NeuralTrainingOptions::Validate() const {
  auto fail = [](const std::string& field, double value, const std::string& rule) {
    internal::FailOption("NeuralTrainingOptions", field, value, rule);
  };
  if (hidden < 1 || hidden > kMaxHiddenUnits)
    fail("hidden", hidden, "1 <= hidden <= " + std::to_string(kMaxHiddenUnits));
  if (!(momentum >= 0 && momentum < 1)) fail("momentum", momentum, "0 <= momentum < 1");
  if (!(mu_initial > 0 && std::isfinite(mu_initial)))
    fail("mu_initial", mu_initial, "mu_initial > 0");
  if (!(mu_decrease > 0 && mu_decrease < 1))
    fail("mu_decrease", mu_decrease, "0 < mu_decrease < 1");
  if (!(mu_increase > 1 && std::isfinite(mu_increase)))
    fail("mu_increase", mu_increase, "mu_increase > 1");
  if (!(mu_max > mu_initial)) fail("mu_max", mu_max, "mu_max > mu_initial");
  if (!(gradient_tolerance >= 0)) fail("gradient_tolerance", gradient_tolerance, ">= 0");
  if (max_epochs < 0 || max_epochs > 1000000)
    fail("max_epochs", max_epochs, "0 <= max_epochs <= 1000000");
  if (max_validation_failures < 1)
    fail("max_validation_failures", max_validation_failures, "max_validation_failures >= 1");
  if (!(goal_mse >= 0)) fail("goal_mse", goal_mse, "goal_mse >= 0");
  if (restarts < 1 || restarts > 1000) fail("restarts", restarts, "1 <= restarts <= 1000");
  if (ceres_block_size < 1) fail("ceres_block_size", ceres_block_size, ">= 1");
  if (threads < 0) fail("threads", threads, ">= 0 (0: all cores)");
  if (solve_output_layer && trainer == NeuralTrainer::kCeres)
    fail("solve_output_layer", 1,
         "solve_output_layer needs trainer = lm (the Ceres trainer has no output-layer step)");
  // max - min finite too: the scaling divides by it (-1e308..1e308 made every value 0 or NaN).
  const auto range_ok = [](const std::pair<double, double>& r) {
    return r.first < r.second && std::isfinite(r.first) && std::isfinite(r.second) &&
           std::isfinite(r.second - r.first);
  };
  for (size_t i = 0; i < input_ranges.size(); ++i)
    if (!range_ok(input_ranges[i]))
      fail("input_ranges[" + std::to_string(i) + "].max", input_ranges[i].second,
           "finite min < max, max - min finite");
  if (output_range && !range_ok(*output_range))
    fail("output_range.max", output_range->second, "finite min < max, max - min finite");
  if (initial_parameters && !initial_parameters->allFinite())
    internal::FailOption("NeuralTrainingOptions", "initial_parameters", "NaN or Inf entries",
                         "finite");
}

std::string NeuralTrainingResult::BriefReport() const {
  std::ostringstream s;
  s << "epochs " << epochs << ", train MSE " << train_mse;
  if (!std::isnan(validation_mse)) s << ", validation MSE " << validation_mse;
  s << ", " << ToString(termination) << " on " << ToString(stop) << " (" << message << "), "
    << wall_time_s << " s";
  return s.str();
}

namespace {

// LM holds J^T J and its damped copy (P x P each) and the hidden layer of the training set
// (N x H): refuse before allocating when that passes the documented limit.
void CheckTrainingMemory(int n, int H, std::size_t rows) {
  const double P = static_cast<double>(H) * (n + 2) + 1;
  const double bytes = 16.0 * P * P + 8.0 * static_cast<double>(rows) * H;
  if (bytes > kTrainingMemoryLimitBytes) {
    internal::FailOption(
        "NeuralTrainingOptions", "hidden", H,
        fmt::format("training {} hidden units on {} inputs ({} weights) and {} rows needs "
                    "about {:.6g} GB, above the limit of {:.6g} GB; use fewer hidden units",
                    H, n, static_cast<long>(P), rows, bytes / 1e9,
                    kTrainingMemoryLimitBytes / 1e9));
  }
}

}  // namespace

NeuralTrainingResult TrainNeuralNetwork(const NeuralDataset& train, const NeuralDataset* validation,
                                        const NeuralTrainingOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  options.Validate();
  CheckData(train, "training", nullptr);
  if (validation) CheckData(*validation, "validation", &train);
  const int n = static_cast<int>(train.input_names.size());
  const int H = options.hidden;
  CheckTrainingMemory(n, H, train.targets.size());
  if (!options.input_ranges.empty() && static_cast<int>(options.input_ranges.size()) != n)
    internal::FailOption("NeuralTrainingOptions", "input_ranges",
                         fmt::format("{} entries", options.input_ranges.size()),
                         fmt::format("one per input ({}) or none", n));
  std::vector<ScaledVariable> inputs;
  for (int i = 0; i < n; ++i) {
    const auto& name = train.input_names[i];
    const auto range = options.input_ranges.empty()
                           ? DataRange(train.inputs.col(i), name, train.source)
                           : options.input_ranges[i];
    inputs.push_back({name, DefaultUnit(name), range.first, range.second});
  }
  const auto out_range = options.output_range
                             ? *options.output_range
                             : DataRange(train.targets, train.output_name, train.source);
  NeuralNetwork net(
      inputs,
      {train.output_name, DefaultUnit(train.output_name), out_range.first, out_range.second}, H);
  const double half = 0.5 * (out_range.second - out_range.first);
  const double mse_scale = half * half;
  const internal::nn::NormalizedData ztrain = Normalize(net, train);
  internal::nn::NormalizedData zval;
  if (validation) zval = Normalize(net, *validation);
  if (options.initial_parameters && options.initial_parameters->size() != net.parameter_count())
    internal::FailOption("NeuralTrainingOptions", "initial_parameters",
                         fmt::format("{} entries", options.initial_parameters->size()),
                         fmt::format("size = H n + 2 H + 1 = {}", net.parameter_count()));

  NeuralTrainingResult result;
  const int restarts = options.initial_parameters ? 1 : options.restarts;
  double best_score = std::numeric_limits<double>::infinity();
  bool have_best = false;
  for (int r = 0; r < restarts; ++r) {
    const Eigen::VectorXd theta0 = options.initial_parameters
                                       ? *options.initial_parameters
                                       : InitialParameters(options.init, n, H, options.seed + r);
    // The trainers call on_epoch with restart 0; the restart index is added here.
    NeuralTrainingOptions run_options = options;
    if (options.on_epoch)
      run_options.on_epoch = [&options, r](const EpochRecord& rec) {
        EpochRecord with_restart = rec;
        with_restart.restart = r;
        options.on_epoch(with_restart);
      };
    internal::nn::TrainerRun run =
        options.trainer == NeuralTrainer::kCeres
            ? internal::nn::RunCeres(ztrain, validation ? &zval : nullptr, H, theta0, mse_scale,
                           run_options)
            : internal::nn::RunLevenbergMarquardt(ztrain, validation ? &zval : nullptr, H, theta0, mse_scale,
                                        run_options);
    for (auto& rec : run.history) {
      rec.restart = r;
      result.history.push_back(rec);
    }
    const double score = validation ? run.validation_mse : run.train_mse;
    if (!have_best || score < best_score) {
      have_best = true;
      best_score = std::isfinite(score) ? score : std::numeric_limits<double>::infinity();
      net.set_parameters(run.theta);
      result.stop = run.stop;
      result.termination = TerminationOf(run.stop);
      result.message = run.message;
      result.epochs = run.epochs;
      result.restart = r;
      result.train_mse = run.train_mse;
      result.validation_mse =
          validation ? run.validation_mse : std::numeric_limits<double>::quiet_NaN();
    }
  }
  result.network = net;
  result.still_falling = TrainingMseStillFalling(result.history, result.restart);
  // A network that ran out of epochs while its error still fell is under-trained; one that
  // ran out on a plateau is as good as more epochs would make it.
  if (result.stop == TrainingStop::kMaxEpochs && options.max_epochs > 0 && result.still_falling)
    result.warnings.push_back(
        "training stopped at --max-epochs " + std::to_string(options.max_epochs) +
        " while the training MSE was still falling; the network may be under-trained (raise "
        "--max-epochs or check --goal-mse/--min-gradient)");
  result.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return result;
}

bool TrainingMseStillFalling(const std::vector<EpochRecord>& history, int restart) {
  std::vector<double> mse;
  for (const auto& e : history)
    if (e.restart == restart) mse.push_back(e.train_mse);
  if (mse.size() < 2) return true;
  const size_t window = std::min(
      mse.size() - 1, std::max<size_t>(kStillFallingMinEpochs, mse.size() / 10));
  const double before = mse[mse.size() - 1 - window], last = mse.back();
  if (!std::isfinite(before) || !std::isfinite(last)) return false;  // a failure, not a budget
  return before - last > kStillFallingFraction * before;
}

}  // namespace sysid
