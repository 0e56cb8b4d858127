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

// The iterate and the work buffers of one LM run.
struct Iterate {
  Eigen::VectorXd theta;
  double sse = 0;  ///< training sum of squares at theta
  double mu = 0;
  Eigen::VectorXd dw_prev;  ///< the last accepted step (momentum)
  // hidden holds theta's hidden layer when hidden_is_theta: the output-layer solve leaves it
  // for the candidate's W1 and b1, which an accepted step makes theta's, and the next normal
  // equations then skip their tanh pass (same bits).
  Eigen::MatrixXd hidden;
  bool hidden_is_theta = false;
  Eigen::MatrixXd damped;
  Eigen::LLT<Eigen::MatrixXd, Eigen::Lower> llt;
  Eigen::VectorXd lm_step;  ///< -(J'J + mu I)^-1 J'e for the mu llt holds
  Eigen::VectorXd step, candidate;
};

// Threads for the next parallel pass: the caller's current share when it gives one.
int ThreadsNow(const NeuralTrainingOptions& o) {
  return o.threads_now ? o.threads_now() : o.threads;
}

struct EpochTrials {
  bool accepted = false;
  int trials = 0, non_finite = 0;
};

// trainlm's mu schedule for one epoch: trial steps until one lowers the sum of squares (it
// becomes the iterate) or mu passes mu_max.
EpochTrials TryStepsUntilOneLowersTheError(const NormalizedData& train, int H,
                                           const NeuralTrainingOptions& o,
                                           const Eigen::MatrixXd& JtJ, const Eigen::VectorXd& g,
                                           Iterate* it) {
  EpochTrials out;
  // The momentum term is tried first at each mu; when that trial fails the same mu is
  // retried without it (a constant momentum term would otherwise keep the step from
  // shrinking as mu grows, and no mu could rescue the epoch). That retry reuses the
  // factorisation and the LM step of the momentum trial (same mu, same bits).
  bool with_momentum = o.momentum != 0.0 && it->dw_prev.squaredNorm() > 0;
  bool factored = false;  // lm_step is the step for the current mu
  while (it->mu <= o.mu_max) {
    ++out.trials;
    if (!factored) {
      it->damped = JtJ;
      it->damped.diagonal().array() += it->mu;
      it->llt.compute(it->damped);
      if (it->llt.info() != Eigen::Success) {
        // J'J + mu I is positive definite in exact arithmetic; failing means rounding or
        // non-finite entries dominate: more damping is the fallback.
        ++out.non_finite;
        it->mu *= o.mu_increase;
        continue;
      }
      it->lm_step = -it->llt.solve(g);
      factored = true;
    }
    it->step = it->lm_step;
    if (with_momentum) it->step += o.momentum * it->dw_prev;
    it->candidate = it->theta + it->step;
    const int threads = ThreadsNow(o);
    double sse_new = o.solve_output_layer ? SolveOutputLayer(train.Z, train.y, H, &it->candidate,
                                                             &it->hidden, threads)
                                          : SumSquares(train.Z, train.y, H, it->candidate, threads);
    // From here the hidden layer is the candidate's (when the solve succeeded), not theta's.
    const bool hidden_is_candidate = o.solve_output_layer && std::isfinite(sse_new);
    it->hidden_is_theta = false;
    if (o.solve_output_layer && !std::isfinite(sse_new)) {
      it->candidate = it->theta + it->step;  // keep the plain LM trial when the solve fails
      sse_new = SumSquares(train.Z, train.y, H, it->candidate, threads);
    }
    if (!std::isfinite(sse_new)) ++out.non_finite;
    if (std::isfinite(sse_new) && sse_new < it->sse) {
      it->dw_prev = it->candidate - it->theta;
      it->theta.swap(it->candidate);
      it->hidden_is_theta = hidden_is_candidate;
      it->sse = sse_new;
      it->mu *= o.mu_decrease;
      out.accepted = true;
      return out;
    }
    if (with_momentum) {
      with_momentum = false;
      continue;
    }
    it->mu *= o.mu_increase;
    factored = false;  // a new mu: a new factorisation
  }
  return out;
}

// Why the epoch loop must stop before its next step, or false: the epoch budget, the goal, the
// validation rule.
bool StopsBeforeTheStep(const NeuralTrainingOptions& o, int epoch, double mse, bool validating,
                        int val_fails, double best_val, TrainerRun* run) {
  if (epoch >= o.max_epochs) {
    run->stop = TrainingStop::kMaxEpochs;
    run->message = "reached max_epochs = " + std::to_string(o.max_epochs);
  } else if (mse <= o.goal_mse) {
    run->stop = TrainingStop::kGoalReached;
    run->message = "training MSE " + Fmt(mse) + " <= goal_mse " + Fmt(o.goal_mse);
  } else if (validating && val_fails >= o.max_validation_failures) {
    run->stop = TrainingStop::kValidationFailures;
    run->message = "validation MSE rose " + std::to_string(val_fails) +
                   " epochs in a row; kept the weights of its minimum " + Fmt(best_val);
  } else {
    return false;
  }
  return true;
}

}  // namespace

TrainerRun RunLevenbergMarquardt(const NormalizedData& train, const NormalizedData* validation,
                                 int H, const Eigen::VectorXd& theta0, double mse_scale,
                                 const NeuralTrainingOptions& o) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double N = static_cast<double>(train.y.size());
  const int P = static_cast<int>(theta0.size());
  auto val_mse = [&](const Eigen::VectorXd& th) {
    return validation ? mse_scale * SumSquares(validation->Z, validation->y, H, th, ThreadsNow(o)) /
                            static_cast<double>(validation->y.size())
                      : nan;
  };

  TrainerRun run;
  Iterate it;
  it.theta = theta0;
  it.sse = SumSquares(train.Z, train.y, H, it.theta, ThreadsNow(o));
  if (o.solve_output_layer) {
    Eigen::VectorXd solved = it.theta;
    const double sse_solved =
        SolveOutputLayer(train.Z, train.y, H, &solved, &it.hidden, ThreadsNow(o));
    it.hidden_is_theta = std::isfinite(sse_solved);  // solved keeps theta's W1 and b1
    if (std::isfinite(sse_solved) && sse_solved < it.sse) {
      it.theta = solved;
      it.sse = sse_solved;
    }
  }
  run.theta = it.theta;
  run.train_mse = mse_scale * it.sse / N;
  run.validation_mse = val_mse(it.theta);
  if (!std::isfinite(it.sse) || (validation && !std::isfinite(run.validation_mse))) {
    run.stop = TrainingStop::kNumericalFailure;
    run.message = "the initial weights give a non-finite error";
    return run;
  }
  double best_val = run.validation_mse;
  int val_fails = 0;
  it.mu = o.mu_initial;
  it.dw_prev = Eigen::VectorXd::Zero(P);
  it.llt = Eigen::LLT<Eigen::MatrixXd, Eigen::Lower>(P);
  Eigen::MatrixXd JtJ;
  Eigen::VectorXd g;
  int epoch = 0;
  while (!StopsBeforeTheStep(o, epoch, mse_scale * it.sse / N, validation != nullptr, val_fails,
                             best_val, &run)) {
    double sse_check = 0;
    NormalEquations(train.Z, train.y, H, it.theta, &JtJ, &g, &sse_check, 0, ThreadsNow(o),
                    it.hidden_is_theta ? &it.hidden : nullptr);
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
    const EpochTrials t = TryStepsUntilOneLowersTheError(train, H, o, JtJ, g, &it);
    if (!t.accepted) {
      if (t.non_finite == t.trials) {
        run.stop = TrainingStop::kNumericalFailure;
        run.message =
            "every trial step gave a non-finite error or a failed Cholesky "
            "factorisation (mu > " +
            Fmt(o.mu_max) + ")";
      } else {
        run.stop = TrainingStop::kMuTooLarge;
        run.message =
            "mu = " + Fmt(it.mu) + " > mu_max = " + Fmt(o.mu_max) + ": no step lowers the error";
      }
      break;
    }
    ++epoch;
    EpochRecord rec;
    rec.epoch = epoch;
    rec.mu = it.mu;
    rec.train_mse = mse_scale * it.sse / N;
    rec.validation_mse = val_mse(it.theta);
    rec.gradient_norm = grad_norm;
    run.history.push_back(rec);
    if (o.on_epoch) o.on_epoch(rec);
    if (validation) {
      if (rec.validation_mse < best_val) {
        best_val = rec.validation_mse;
        run.theta = it.theta;
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
    run.theta = it.theta;  // accepted steps only lower the error: the last is the best
    run.train_mse = mse_scale * it.sse / N;
  }
  return run;
}

}  // namespace sysid::internal::nn
