// Ceres' Levenberg–Marquardt on the network's residuals: the reference trainer. One residual
// block per `ceres_block_size` samples, each with the analytic Jacobian of mlp_kernels; the
// linear algebra is Ceres' own (dense QR of the Jacobian), so it shares no solver code with
// the library's LM.
#include <ceres/ceres.h>

#include <Eigen/Core>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <string>

#include "nn/mlp_kernels.hpp"
#include "nn/trainers.hpp"

namespace sysid::internal::nn {
namespace {

class BlockCost final : public ceres::CostFunction {
 public:
  BlockCost(const NormalizedData& data, int H, Eigen::Index first, Eigen::Index count)
      : data_(data), H_(H), first_(first), count_(count) {
    set_num_residuals(static_cast<int>(count));
    mutable_parameter_block_sizes()->push_back(ParameterCount(static_cast<int>(data.Z.rows()), H));
  }

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    const int P = parameter_block_sizes()[0];
    const Eigen::VectorXd theta = Eigen::Map<const Eigen::VectorXd>(parameters[0], P);
    Eigen::VectorXd r;
    if (jacobians != nullptr && jacobians[0] != nullptr) {
      Eigen::MatrixXd JT, A;
      JacobianTransposeBlock(data_.Z, data_.y, H_, theta, first_, count_, &JT, &A, &r);
      // Ceres wants the count x P Jacobian row-major: the same memory as JT column-major.
      std::memcpy(jacobians[0], JT.data(), sizeof(double) * static_cast<size_t>(JT.size()));
    } else {
      ResidualBlock(data_.Z, data_.y, H_, theta, first_, count_, &r);
    }
    Eigen::Map<Eigen::VectorXd>(residuals, count_) = r;
    return r.allFinite();
  }

 private:
  const NormalizedData& data_;
  int H_;
  Eigen::Index first_, count_;
};

// Records each iteration, tracks the best validation weights and applies the early stops.
class Monitor final : public ceres::IterationCallback {
 public:
  Monitor(const NormalizedData& train, const NormalizedData* validation, int H, const double* x,
          int P, double mse_scale, const NeuralTrainingOptions& o, TrainerRun* run)
      : train_(train),
        validation_(validation),
        H_(H),
        x_(x),
        P_(P),
        mse_scale_(mse_scale),
        o_(o),
        run_(run) {}

  ceres::CallbackReturnType operator()(const ceres::IterationSummary& s) override {
    const double N = static_cast<double>(train_.y.size());
    const double train_mse = mse_scale_ * 2.0 * s.cost / N;  // Ceres' cost is sse / 2
    const Eigen::VectorXd theta = Eigen::Map<const Eigen::VectorXd>(x_, P_);
    double val = std::numeric_limits<double>::quiet_NaN();
    if (validation_)
      val = mse_scale_ * SumSquares(validation_->Z, validation_->y, H_, theta) /
            static_cast<double>(validation_->y.size());
    if (s.iteration > 0) {
      EpochRecord rec;
      rec.epoch = s.iteration;
      rec.mu = 1.0 / s.trust_region_radius;
      rec.train_mse = train_mse;
      rec.validation_mse = val;
      rec.gradient_norm = 2.0 * s.gradient_norm / N;
      run_->history.push_back(rec);
      if (o_.on_epoch) o_.on_epoch(rec);
    }
    if (validation_) {
      if (s.iteration == 0 || val < best_val_) {
        best_val_ = val;
        run_->theta = theta;
        run_->validation_mse = val;
        run_->train_mse = train_mse;
        fails_ = 0;
      } else if (s.step_is_successful) {
        ++fails_;
      }
      if (fails_ >= o_.max_validation_failures) {
        stop_ = TrainingStop::kValidationFailures;
        return ceres::SOLVER_TERMINATE_SUCCESSFULLY;
      }
    }
    if (train_mse <= o_.goal_mse) {
      stop_ = TrainingStop::kGoalReached;
      return ceres::SOLVER_TERMINATE_SUCCESSFULLY;
    }
    return ceres::SOLVER_CONTINUE;
  }

  TrainingStop user_stop() const { return stop_; }
  double best_validation() const { return best_val_; }

 private:
  const NormalizedData& train_;
  const NormalizedData* validation_;
  int H_;
  const double* x_;
  int P_;
  double mse_scale_;
  const NeuralTrainingOptions& o_;
  TrainerRun* run_;
  double best_val_ = std::numeric_limits<double>::infinity();
  int fails_ = 0;
  TrainingStop stop_ = TrainingStop::kConverged;
};

}  // namespace

TrainerRun RunCeres(const NormalizedData& train, const NormalizedData* validation, int H,
                    const Eigen::VectorXd& theta0, double mse_scale,
                    const NeuralTrainingOptions& o) {
  const int P = static_cast<int>(theta0.size());
  const Eigen::Index N = train.y.size();
  TrainerRun run;
  run.validation_mse = std::numeric_limits<double>::quiet_NaN();
  Eigen::VectorXd x = theta0;
  ceres::Problem problem;
  for (Eigen::Index first = 0; first < N; first += o.ceres_block_size) {
    const Eigen::Index count = std::min<Eigen::Index>(o.ceres_block_size, N - first);
    problem.AddResidualBlock(new BlockCost(train, H, first, count), nullptr, x.data());
  }
  ceres::Solver::Options so;
  so.minimizer_type = ceres::TRUST_REGION;
  so.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  // N >> P: the normal equations (P x P) are far cheaper than a QR of the N x P Jacobian.
  so.linear_solver_type = ceres::DENSE_NORMAL_CHOLESKY;
  so.max_num_iterations = o.max_epochs;
  so.initial_trust_region_radius = 1.0 / o.mu_initial;
  so.min_trust_region_radius = 1.0 / o.mu_max;
  // Ceres' gradient is J'r (cost sse/2) and its norm the max-norm; ours is ||2 J'r / N||_2.
  so.gradient_tolerance = o.gradient_tolerance * static_cast<double>(N) / 2.0;
  so.function_tolerance = 1e-12;
  so.parameter_tolerance = 1e-12;
  // One thread: Ceres' parallel evaluator adds per-thread partial costs and gradients in a
  // schedule-dependent order, so results would change with the thread count (options.threads
  // speeds up the library LM trainer, whose reductions are in a fixed order).
  so.num_threads = 1;
  so.logging_type = ceres::SILENT;
  so.minimizer_progress_to_stdout = false;
  so.update_state_every_iteration = true;
  Monitor monitor(train, validation, H, x.data(), P, mse_scale, o, &run);
  so.callbacks.push_back(&monitor);
  ceres::Solver::Summary summary;
  ceres::Solve(so, &problem, &summary);
  run.epochs = static_cast<int>(summary.iterations.size()) - 1;
  run.message = "Ceres: " + summary.message;
  switch (summary.termination_type) {
    case ceres::CONVERGENCE:
      run.stop = TrainingStop::kConverged;
      break;
    case ceres::NO_CONVERGENCE:
      run.stop = TrainingStop::kMaxEpochs;
      break;
    case ceres::USER_SUCCESS:
      run.stop = monitor.user_stop();
      break;
    default:
      run.stop = TrainingStop::kNumericalFailure;
      break;
  }
  if (validation && run.theta.size() != P) {
    run.theta = theta0;
    run.validation_mse = mse_scale * SumSquares(validation->Z, validation->y, H, theta0) /
                         static_cast<double>(validation->y.size());
    run.train_mse = mse_scale * SumSquares(train.Z, train.y, H, theta0) / static_cast<double>(N);
  }
  if (!validation) {
    // Ceres keeps the best accepted point in x; recompute rather than trust a stale cost.
    const double sse = SumSquares(train.Z, train.y, H, x);
    if (std::isfinite(sse)) {
      run.theta = x;
      run.train_mse = mse_scale * sse / static_cast<double>(N);
    } else {
      run.theta = theta0;
      run.train_mse = mse_scale * SumSquares(train.Z, train.y, H, theta0) / static_cast<double>(N);
      run.stop = TrainingStop::kNumericalFailure;
    }
  }
  return run;
}

}  // namespace sysid::internal::nn
