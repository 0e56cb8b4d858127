// The LM trainer's momentum retry: when the trial with the momentum term fails, the same mu is
// tried without it, and the trainer reuses that mu's factorisation for it. Reference: the rule
// as written, refactorising J'J + mu I at every trial, on the same kernels; the weights must
// agree bit for bit, on a run where momentum trials do fail.
#include <Eigen/Cholesky>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "nn/mlp_kernels.hpp"
#include "nn/trainers.hpp"

namespace {

namespace nn = sysid::internal::nn;

struct Reference {
  Eigen::VectorXd theta;
  int momentum_failures = 0;  ///< momentum trials rejected, retried without it
};

Reference ReferenceLm(const nn::NormalizedData& d, int H, Eigen::VectorXd theta,
                      const sysid::NeuralTrainingOptions& o) {
  Reference out;
  const Eigen::Index P = theta.size();
  double sse = nn::SumSquares(d.Z, d.y, H, theta, 1);
  double mu = o.mu_initial;
  Eigen::VectorXd dw = Eigen::VectorXd::Zero(P);
  Eigen::MatrixXd JtJ;
  Eigen::VectorXd g;
  for (int epoch = 0; epoch < o.max_epochs; ++epoch) {
    double unused = 0;
    nn::NormalEquations(d.Z, d.y, H, theta, &JtJ, &g, &unused, 0, 1);
    bool with_momentum = dw.squaredNorm() > 0;
    bool accepted = false;
    while (mu <= o.mu_max && !accepted) {
      Eigen::MatrixXd damped = JtJ;
      damped.diagonal().array() += mu;
      Eigen::LLT<Eigen::MatrixXd, Eigen::Lower> llt(damped);
      Eigen::VectorXd step = -llt.solve(g);
      if (with_momentum) step += o.momentum * dw;
      const Eigen::VectorXd candidate = theta + step;
      const double trial = nn::SumSquares(d.Z, d.y, H, candidate, 1);
      if (trial < sse) {
        dw = candidate - theta;
        theta = candidate;
        sse = trial;
        mu *= o.mu_decrease;
        accepted = true;
      } else if (with_momentum) {
        with_momentum = false;
        ++out.momentum_failures;
      } else {
        mu *= o.mu_increase;
      }
    }
    if (!accepted) break;
  }
  out.theta = theta;
  return out;
}

}  // namespace

TEST_CASE("LM with momentum: the retry without it matches refactorising at every trial",
          "[nn][train]") {
  constexpr int kN = 400, kH = 8;
  std::mt19937 gen(31u);
  std::uniform_real_distribution<double> U(-1, 1);
  std::normal_distribution<double> noise(0.0, 0.05);
  nn::NormalizedData d;
  d.Z.resize(1, kN);
  d.y.resize(kN);
  for (int k = 0; k < kN; ++k) {
    d.Z(0, k) = U(gen);
    d.y[k] = 0.6 * std::sin(3.0 * d.Z(0, k)) + noise(gen);
  }
  Eigen::MatrixXd W1(kH, 1);
  Eigen::VectorXd b1(kH), w2(kH);
  for (int h = 0; h < kH; ++h) {
    W1(h, 0) = 2 * U(gen);
    b1[h] = U(gen);
    w2[h] = 0.5 * U(gen);
  }
  const Eigen::VectorXd theta0 = nn::PackParameters(W1, b1, w2, 0.1);
  sysid::NeuralTrainingOptions o;
  o.hidden = kH;
  o.momentum = 0.9;  // large: many momentum trials overshoot
  o.max_epochs = 40;
  o.gradient_tolerance = 0;
  o.threads = 1;
  const Reference ref = ReferenceLm(d, kH, theta0, o);
  REQUIRE(ref.momentum_failures > 0);
  const nn::TrainerRun run = nn::RunLevenbergMarquardt(d, nullptr, kH, theta0, 1.0, o);
  INFO("stop: " << run.message << ", momentum failures " << ref.momentum_failures);
  CHECK(run.theta == ref.theta);
}
