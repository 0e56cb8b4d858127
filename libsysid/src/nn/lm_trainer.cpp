// The paper's Levenberg–Marquardt rule with momentum,
//   w <- w - (J'J + mu I)^-1 J'e + alpha dw_prev,
// and MATLAB trainlm's mu schedule: a trial step is accepted when it lowers the sum of squares
// (then mu *= mu_decrease); otherwise mu *= mu_increase and the step is re-solved, until
// mu > mu_max. One epoch = one accepted step.
#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "nn/mlp_kernels.hpp"
#include "nn/trainers.hpp"

namespace sysid::internal::nn {
namespace {

std::string Fmt(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", x);
  return buf;
}

}  // namespace

TrainerRun RunLevenbergMarquardt(const NormalizedData& train, const NormalizedData* validation,
                                 int H, const Eigen::VectorXd& theta0, double mse_scale,
                                 const NeuralTrainingOptions& o) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double N = static_cast<double>(train.y.size());
  const int P = static_cast<int>(theta0.size());
  auto val_mse = [&](const Eigen::VectorXd& th) {
    return validation ? mse_scale * SumSquares(validation->Z, validation->y, H, th, o.threads) /
                            static_cast<double>(validation->y.size())
                      : nan;
  };

  TrainerRun run;
  Eigen::VectorXd theta = theta0;
  Eigen::MatrixXd hidden_scratch;
  // hidden_scratch holds theta's hidden layer: the output-layer solve leaves it for the
  // candidate's W1 and b1, which an accepted step makes theta's, and the next normal equations
  // then skip their tanh pass (same bits).
  bool hidden_is_theta = false;
  double sse = SumSquares(train.Z, train.y, H, theta, o.threads);
  if (o.solve_output_layer) {
    Eigen::VectorXd solved = theta;
    const double sse_solved =
        SolveOutputLayer(train.Z, train.y, H, &solved, &hidden_scratch, o.threads);
    hidden_is_theta = std::isfinite(sse_solved);  // solved keeps theta's W1 and b1
    if (std::isfinite(sse_solved) && sse_solved < sse) {
      theta = solved;
      sse = sse_solved;
    }
  }
  run.theta = theta;
  run.train_mse = mse_scale * sse / N;
  run.validation_mse = val_mse(theta);
  if (!std::isfinite(sse) || (validation && !std::isfinite(run.validation_mse))) {
    run.stop = TrainingStop::kNumericalFailure;
    run.message = "the initial weights give a non-finite error";
    return run;
  }
  double best_val = run.validation_mse;
  int val_fails = 0;
  double mu = o.mu_initial;
  Eigen::VectorXd dw_prev = Eigen::VectorXd::Zero(P);
  Eigen::MatrixXd JtJ, A;
  Eigen::VectorXd g, step, candidate;
  Eigen::LLT<Eigen::MatrixXd, Eigen::Lower> llt(P);
  int epoch = 0;
  for (;;) {
    const double mse = mse_scale * sse / N;
    if (epoch >= o.max_epochs) {
      run.stop = TrainingStop::kMaxEpochs;
      run.message = "reached max_epochs = " + std::to_string(o.max_epochs);
      break;
    }
    if (mse <= o.goal_mse) {
      run.stop = TrainingStop::kGoalReached;
      run.message = "training MSE " + Fmt(mse) + " <= goal_mse " + Fmt(o.goal_mse);
      break;
    }
    if (validation && val_fails >= o.max_validation_failures) {
      run.stop = TrainingStop::kValidationFailures;
      run.message = "validation MSE rose " + std::to_string(val_fails) +
                    " epochs in a row; kept the weights of its minimum " + Fmt(best_val);
      break;
    }
    double sse_check = 0;
    NormalEquations(train.Z, train.y, H, theta, &JtJ, &g, &sse_check, 0, o.threads,
                    hidden_is_theta ? &hidden_scratch : nullptr);
    const double grad_norm = 2.0 * g.norm() / N;
    if (!(grad_norm >= o.gradient_tolerance)) {
      run.stop =
          std::isfinite(grad_norm) ? TrainingStop::kSmallGradient : TrainingStop::kNumericalFailure;
      run.message = std::isfinite(grad_norm)
                        ? "gradient norm " + Fmt(grad_norm) + " < gradient_tolerance " +
                              Fmt(o.gradient_tolerance)
                        : "the gradient is not finite";
      break;
    }
    bool accepted = false;
    int trials = 0, non_finite = 0;
    // The momentum term is tried first at each mu; when that trial fails the same mu is
    // retried without it (a constant momentum term would otherwise keep the step from
    // shrinking as mu grows, and no mu could rescue the epoch).
    bool with_momentum = o.momentum != 0.0 && dw_prev.squaredNorm() > 0;
    while (mu <= o.mu_max) {
      ++trials;
      A = JtJ;
      A.diagonal().array() += mu;
      llt.compute(A);
      if (llt.info() != Eigen::Success) {
        // J'J + mu I is positive definite in exact arithmetic; failing means rounding or
        // non-finite entries dominate: more damping is the fallback.
        ++non_finite;
        mu *= o.mu_increase;
        continue;
      }
      step = -llt.solve(g);
      if (with_momentum) step += o.momentum * dw_prev;
      candidate = theta + step;
      double sse_new = o.solve_output_layer ? SolveOutputLayer(train.Z, train.y, H, &candidate,
                                                               &hidden_scratch, o.threads)
                                            : SumSquares(train.Z, train.y, H, candidate, o.threads);
      // From here hidden_scratch is the candidate's (when the solve succeeded), not theta's.
      const bool hidden_is_candidate = o.solve_output_layer && std::isfinite(sse_new);
      hidden_is_theta = false;
      if (o.solve_output_layer && !std::isfinite(sse_new)) {
        candidate = theta + step;  // keep the plain LM trial when the solve fails
        sse_new = SumSquares(train.Z, train.y, H, candidate, o.threads);
      }
      if (!std::isfinite(sse_new)) ++non_finite;
      if (std::isfinite(sse_new) && sse_new < sse) {
        dw_prev = candidate - theta;
        theta.swap(candidate);
        hidden_is_theta = hidden_is_candidate;
        sse = sse_new;
        mu *= o.mu_decrease;
        accepted = true;
        break;
      }
      if (with_momentum) {
        with_momentum = false;
        continue;
      }
      mu *= o.mu_increase;
    }
    if (!accepted) {
      if (non_finite == trials) {
        run.stop = TrainingStop::kNumericalFailure;
        run.message =
            "every trial step gave a non-finite error or a failed Cholesky "
            "factorisation (mu > " +
            Fmt(o.mu_max) + ")";
      } else {
        run.stop = TrainingStop::kMuTooLarge;
        run.message =
            "mu = " + Fmt(mu) + " > mu_max = " + Fmt(o.mu_max) + ": no step lowers the error";
      }
      break;
    }
    ++epoch;
    EpochRecord rec;
    rec.epoch = epoch;
    rec.mu = mu;
    rec.train_mse = mse_scale * sse / N;
    rec.validation_mse = val_mse(theta);
    rec.gradient_norm = grad_norm;
    run.history.push_back(rec);
    if (o.on_epoch) o.on_epoch(rec);
    if (validation) {
      if (rec.validation_mse < best_val) {
        best_val = rec.validation_mse;
        run.theta = theta;
        run.train_mse = rec.train_mse;
        run.validation_mse = best_val;
        val_fails = 0;
      } else {
        ++val_fails;
      }
    }
  }
  run.epochs = epoch;
  if (!validation) {
    run.theta = theta;  // accepted steps only lower the error: the last is the best
    run.train_mse = mse_scale * sse / N;
  }
  return run;
}

}  // namespace sysid::internal::nn
