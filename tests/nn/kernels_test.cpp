// The private kernels against independent references: central finite differences for the
// Jacobian, a dense product for the blocked J'J, std::tanh, and a QR least-squares solve.
#include <Eigen/QR>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <string>

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

TEST_CASE("every instruction set's kernels agree with the generic ones to 1e-12",
          "[nn][kernels][simd]") {
  // The AVX2/FMA kernels (when built and the CPU has them) against the default-flag ones:
  // same formulas, different rounding (FMA, packet exp), so agreement to 1e-12 relative.
  for (int n : {1, 2, 3}) {
    const Problem p = MakeProblem(n, 13, 2100, 40u + static_cast<unsigned>(n));
    auto run = [&](Eigen::MatrixXd* JtJ, Eigen::VectorXd* g, double* sse, Eigen::MatrixXd* J,
                   double* ss) {
      sysid::nn::NormalEquations(p.Z, p.y, p.H, p.theta, JtJ, g, sse);
      sysid::nn::Jacobian(p.Z, p.y, p.H, p.theta, J);
      *ss = sysid::nn::SumSquares(p.Z, p.y, p.H, p.theta);
    };
    REQUIRE(sysid::nn::SetKernelIsa("generic"));
    CHECK(std::string(sysid::nn::KernelIsa()) == "generic");
    Eigen::MatrixXd JtJ0, J0;
    Eigen::VectorXd g0;
    double sse0 = 0, ss0 = 0;
    run(&JtJ0, &g0, &sse0, &J0, &ss0);
    const bool avx2 = sysid::nn::SetKernelIsa("avx2+fma");
    if (!avx2) WARN("AVX2+FMA kernels not built or not supported by this CPU: generic only");
    Eigen::MatrixXd JtJ1, J1;
    Eigen::VectorXd g1;
    double sse1 = 0, ss1 = 0;
    run(&JtJ1, &g1, &sse1, &J1, &ss1);
    REQUIRE(sysid::nn::SetKernelIsa("auto"));
    const Eigen::MatrixXd L0 = JtJ0.triangularView<Eigen::Lower>();
    const Eigen::MatrixXd L1 = JtJ1.triangularView<Eigen::Lower>();
    CHECK((L1 - L0).norm() <= 1e-12 * L0.norm());
    CHECK((g1 - g0).norm() <= 1e-12 * g0.norm());
    CHECK(std::abs(sse1 - sse0) <= 1e-12 * sse0);
    CHECK(std::abs(ss1 - ss0) <= 1e-12 * ss0);
    CHECK((J1 - J0).norm() <= 1e-12 * J0.norm());
  }
  CHECK_FALSE(sysid::nn::SetKernelIsa("no-such-isa"));
}

TEST_CASE("normal equations and sums of squares are bit-identical for 1 and N threads",
          "[nn][kernels][threads]") {
  // Fixed chunks with partial sums added in chunk order: the thread count cannot change a bit.
  const Problem p = MakeProblem(2, 9, 5003, 77u);
  Eigen::MatrixXd JtJ1, JtJ2, JtJ3;
  Eigen::VectorXd g1, g2, g3;
  double sse1 = 0, sse2 = 0, sse3 = 0;
  sysid::nn::NormalEquations(p.Z, p.y, p.H, p.theta, &JtJ1, &g1, &sse1, 64, 1);
  sysid::nn::NormalEquations(p.Z, p.y, p.H, p.theta, &JtJ2, &g2, &sse2, 64, 2);
  sysid::nn::NormalEquations(p.Z, p.y, p.H, p.theta, &JtJ3, &g3, &sse3, 64, 3);
  CHECK(JtJ1 == JtJ2);
  CHECK(JtJ1 == JtJ3);
  CHECK(g1 == g2);
  CHECK(g1 == g3);
  CHECK(sse1 == sse2);
  CHECK(sse1 == sse3);
  CHECK(sysid::nn::SumSquares(p.Z, p.y, p.H, p.theta, 1) ==
        sysid::nn::SumSquares(p.Z, p.y, p.H, p.theta, 2));
  // And the chunked sums are the whole-Jacobian ones.
  Eigen::MatrixXd J;
  sysid::nn::Jacobian(p.Z, p.y, p.H, p.theta, &J);
  const Eigen::MatrixXd ref = J.transpose() * J;
  const Eigen::MatrixXd L = JtJ1.triangularView<Eigen::Lower>();
  const Eigen::MatrixXd Lref = ref.triangularView<Eigen::Lower>();
  CHECK((L - Lref).norm() <= 1e-12 * Lref.norm());
}
