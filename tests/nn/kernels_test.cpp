// The private kernels against independent references: central finite differences for the
// Jacobian, a dense product for the blocked J'J, std::tanh, and a QR least-squares solve.
#include <Eigen/QR>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "nn/mlp_kernels.hpp"

namespace {

struct Problem {
  Eigen::MatrixXd Z;
  Eigen::VectorXd y, theta;
  int H;
};

Problem MakeProblem(int n, int H, int N, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> U(-1, 1);
  Problem p{Eigen::MatrixXd(n, N), Eigen::VectorXd(N),
            Eigen::VectorXd(sysid::nn::ParameterCount(n, H)), H};
  for (int k = 0; k < N; ++k) {
    for (int i = 0; i < n; ++i) p.Z(i, k) = U(gen);
    p.y[k] = U(gen);
  }
  for (Eigen::Index j = 0; j < p.theta.size(); ++j) p.theta[j] = 1.5 * U(gen);
  return p;
}

}  // namespace

TEST_CASE("Jacobian matches central finite differences", "[nn][kernels]") {
  for (int n : {1, 2, 3}) {
    const Problem p = MakeProblem(n, 5, 37, 11u + static_cast<unsigned>(n));
    Eigen::MatrixXd J;
    sysid::nn::Jacobian(p.Z, p.y, p.H, p.theta, &J);
    const double h = 1e-6;
    Eigen::VectorXd rp, rm;
    double worst = 0;
    for (Eigen::Index j = 0; j < p.theta.size(); ++j) {
      Eigen::VectorXd tp = p.theta, tm = p.theta;
      tp[j] += h;
      tm[j] -= h;
      sysid::nn::Residuals(p.Z, p.y, p.H, tp, &rp);
      sysid::nn::Residuals(p.Z, p.y, p.H, tm, &rm);
      worst = std::max(worst, ((rp - rm) / (2 * h) - J.col(j)).cwiseAbs().maxCoeff());
    }
    // Central differences with h = 1e-6 on O(1) functions: truncation ~h^2, rounding ~1e-10.
    CHECK(worst < 1e-7);
  }
}

TEST_CASE("blocked normal equations equal J'J and J'r of the whole Jacobian", "[nn][kernels]") {
  const Problem p = MakeProblem(2, 7, 1001, 5u);
  Eigen::MatrixXd J;
  sysid::nn::Jacobian(p.Z, p.y, p.H, p.theta, &J);
  Eigen::VectorXd r;
  sysid::nn::Residuals(p.Z, p.y, p.H, p.theta, &r);
  const Eigen::MatrixXd JtJ_ref = J.transpose() * J;
  for (int block : {1, 37, 256, 5000}) {
    Eigen::MatrixXd JtJ;
    Eigen::VectorXd g;
    double sse = 0;
    sysid::nn::NormalEquations(p.Z, p.y, p.H, p.theta, &JtJ, &g, &sse, block);
    const Eigen::MatrixXd full = JtJ.selfadjointView<Eigen::Lower>();
    // Sums of ~1000 O(1) products in a different order: agreement to ~1e-12 relative.
    CHECK((full - JtJ_ref).cwiseAbs().maxCoeff() < 1e-10 * JtJ_ref.cwiseAbs().maxCoeff());
    CHECK((g - J.transpose() * r).cwiseAbs().maxCoeff() < 1e-10 * (1 + g.cwiseAbs().maxCoeff()));
    CHECK(sse == Approx(r.squaredNorm()).epsilon(1e-12));
  }
}

TEST_CASE("exp-based tanh agrees with std::tanh", "[nn][kernels]") {
  Eigen::ArrayXXd x(1, 2001);
  for (int k = 0; k < 2001; ++k) x(0, k) = -400.0 + 0.4 * k;
  Eigen::ArrayXXd t = x;
  sysid::nn::TanhInPlace(t);
  double worst = 0;
  for (int k = 0; k < 2001; ++k) worst = std::max(worst, std::abs(t(0, k) - std::tanh(x(0, k))));
  // 1 - 2/(e^2x + 1) loses at most a few ulps of 1 in absolute terms.
  CHECK(worst < 1e-15);
  CHECK(t(0, 0) == -1.0);
  CHECK(t(0, 2000) == 1.0);
}

TEST_CASE("output-layer solve equals a QR least-squares fit", "[nn][kernels]") {
  Problem p = MakeProblem(1, 6, 500, 9u);
  // Units with distinct centres and slopes keep [tanh(...) 1] well conditioned.
  p.theta.head(12) << 3.0, -2.0, 1.5, 4.0, -3.5, 2.5, -2.0, 1.0, 0.0, -1.0, 0.5, 2.0;
  Eigen::VectorXd theta = p.theta;
  Eigen::MatrixXd A;
  const double sse = sysid::nn::SolveOutputLayer(p.Z, p.y, p.H, &theta, &A);
  // Reference: M = [tanh(W1 z + b1)' 1], solved by column-pivoting QR.
  Eigen::MatrixXd M(500, 7);
  for (int k = 0; k < 500; ++k) {
    for (int h = 0; h < 6; ++h) M(k, h) = std::tanh(p.theta[h] * p.Z(0, k) + p.theta[6 + h]);
    M(k, 6) = 1.0;
  }
  const Eigen::VectorXd c = M.colPivHouseholderQr().solve(p.y);
  // Normal equations lose ~cond(M)^2 eps relative (cond ~1e3-1e4 here): 1e-6 of max |c|.
  CHECK((theta.segment(12, 7) - c).cwiseAbs().maxCoeff() < 1e-6 * c.cwiseAbs().maxCoeff());
  CHECK(sse == Approx((M * c - p.y).squaredNorm()).epsilon(1e-10));
  CHECK(theta.head(12) == p.theta.head(12));
}
