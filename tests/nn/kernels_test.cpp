// The private kernels against independent references: central finite differences for the
// Jacobian, a dense product for the blocked J'J, std::tanh, and a QR least-squares solve.
#include <Eigen/QR>
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "nn/mlp_kernels.hpp"
#include "nn/mlp_kernels_isa.hpp"

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
            Eigen::VectorXd(sysid::internal::nn::ParameterCount(n, H)), H};
  for (int k = 0; k < N; ++k) {
    for (int i = 0; i < n; ++i) p.Z(i, k) = U(gen);
    p.y[k] = U(gen);
  }
  for (Eigen::Index j = 0; j < p.theta.size(); ++j) p.theta[j] = 1.5 * U(gen);
  return p;
}

}  // namespace

TEST_CASE("the kernels read theta in the one parameter layout", "[nn][kernels]") {
  // The kernels spell the layout's offsets out (mlp_kernels_impl.inc may not include the
  // header that defines them): their residuals must be the network written with the layout's
  // parts, w2' tanh(W1 z + b1) + b2 - y, by std::tanh.
  for (int n : {1, 2, 3}) {
    const Problem p = MakeProblem(n, 7, 40, 11u + static_cast<unsigned>(n));
    const sysid::internal::nn::ParameterLayout l{n, p.H};
    REQUIRE(p.theta.size() == l.count());
    Eigen::VectorXd r;
    sysid::internal::nn::Residuals(p.Z, p.y, p.H, p.theta, &r);
    for (Eigen::Index k = 0; k < p.Z.cols(); ++k) {
      double out = p.theta[l.b2()];
      for (int h = 0; h < p.H; ++h) {
        double z = p.theta[l.b1() + h];
        for (int i = 0; i < n; ++i) z += p.theta[l.W1() + h * n + i] * p.Z(i, k);
        out += p.theta[l.w2() + h] * std::tanh(z);
      }
      CHECK(r[k] == Approx(out - p.y[k]).margin(1e-13));
    }
    // PackParameters and Weights are each other's inverse.
    const sysid::internal::nn::Weights w(p.theta, n, p.H);
    CHECK(sysid::internal::nn::PackParameters(w.W1, w.b1, w.w2, w.b2) == p.theta);
  }
}

TEST_CASE("Jacobian matches central finite differences", "[nn][kernels]") {
  for (int n : {1, 2, 3}) {
    const Problem p = MakeProblem(n, 5, 37, 11u + static_cast<unsigned>(n));
    Eigen::MatrixXd J;
    sysid::internal::nn::Jacobian(p.Z, p.y, p.H, p.theta, &J);
    const double h = 1e-6;
    Eigen::VectorXd rp, rm;
    double worst = 0;
    for (Eigen::Index j = 0; j < p.theta.size(); ++j) {
      Eigen::VectorXd tp = p.theta, tm = p.theta;
      tp[j] += h;
      tm[j] -= h;
      sysid::internal::nn::Residuals(p.Z, p.y, p.H, tp, &rp);
      sysid::internal::nn::Residuals(p.Z, p.y, p.H, tm, &rm);
      worst = std::max(worst, ((rp - rm) / (2 * h) - J.col(j)).cwiseAbs().maxCoeff());
    }
    // Central differences with h = 1e-6 on O(1) functions: truncation ~h^2, rounding ~1e-10.
    CHECK(worst < 1e-7);
  }
}

TEST_CASE("blocked normal equations equal J'J and J'r of the whole Jacobian", "[nn][kernels]") {
  const Problem p = MakeProblem(2, 7, 1001, 5u);
  Eigen::MatrixXd J;
  sysid::internal::nn::Jacobian(p.Z, p.y, p.H, p.theta, &J);
  Eigen::VectorXd r;
  sysid::internal::nn::Residuals(p.Z, p.y, p.H, p.theta, &r);
  const Eigen::MatrixXd JtJ_ref = J.transpose() * J;
  for (int block : {1, 37, 256, 5000}) {
    Eigen::MatrixXd JtJ;
    Eigen::VectorXd g;
    double sse = 0;
    sysid::internal::nn::NormalEquations(p.Z, p.y, p.H, p.theta, &JtJ, &g, &sse, block);
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
  sysid::internal::nn::TanhInPlace(t);
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
  const double sse = sysid::internal::nn::SolveOutputLayer(p.Z, p.y, p.H, &theta, &A);
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
      sysid::internal::nn::NormalEquations(p.Z, p.y, p.H, p.theta, JtJ, g, sse);
      sysid::internal::nn::Jacobian(p.Z, p.y, p.H, p.theta, J);
      *ss = sysid::internal::nn::SumSquares(p.Z, p.y, p.H, p.theta);
    };
    REQUIRE(sysid::internal::nn::SetKernelIsa("generic"));
    CHECK(std::string(sysid::internal::nn::KernelIsa()) == "generic");
    Eigen::MatrixXd JtJ0, J0;
    Eigen::VectorXd g0;
    double sse0 = 0, ss0 = 0;
    run(&JtJ0, &g0, &sse0, &J0, &ss0);
    const bool avx2 = sysid::internal::nn::SetKernelIsa("avx2+fma");
    if (!avx2) WARN("AVX2+FMA kernels not built or not supported by this CPU: generic only");
    Eigen::MatrixXd JtJ1, J1;
    Eigen::VectorXd g1;
    double sse1 = 0, ss1 = 0;
    run(&JtJ1, &g1, &sse1, &J1, &ss1);
    REQUIRE(sysid::internal::nn::SetKernelIsa("auto"));
    const Eigen::MatrixXd L0 = JtJ0.triangularView<Eigen::Lower>();
    const Eigen::MatrixXd L1 = JtJ1.triangularView<Eigen::Lower>();
    CHECK((L1 - L0).norm() <= 1e-12 * L0.norm());
    CHECK((g1 - g0).norm() <= 1e-12 * g0.norm());
    CHECK(std::abs(sse1 - sse0) <= 1e-12 * sse0);
    CHECK(std::abs(ss1 - ss0) <= 1e-12 * ss0);
    CHECK((J1 - J0).norm() <= 1e-12 * J0.norm());
  }
  CHECK_FALSE(sysid::internal::nn::SetKernelIsa("no-such-isa"));
}

TEST_CASE("normal equations and sums of squares are bit-identical for 1 and N threads",
          "[nn][kernels][threads]") {
  // Fixed chunks with partial sums added in chunk order: the thread count cannot change a bit.
  const Problem p = MakeProblem(2, 9, 5003, 77u);
  Eigen::MatrixXd JtJ1, JtJ2, JtJ3;
  Eigen::VectorXd g1, g2, g3;
  double sse1 = 0, sse2 = 0, sse3 = 0;
  sysid::internal::nn::NormalEquations(p.Z, p.y, p.H, p.theta, &JtJ1, &g1, &sse1, 64, 1);
  sysid::internal::nn::NormalEquations(p.Z, p.y, p.H, p.theta, &JtJ2, &g2, &sse2, 64, 2);
  sysid::internal::nn::NormalEquations(p.Z, p.y, p.H, p.theta, &JtJ3, &g3, &sse3, 64, 3);
  CHECK(JtJ1 == JtJ2);
  CHECK(JtJ1 == JtJ3);
  CHECK(g1 == g2);
  CHECK(g1 == g3);
  CHECK(sse1 == sse2);
  CHECK(sse1 == sse3);
  CHECK(sysid::internal::nn::SumSquares(p.Z, p.y, p.H, p.theta, 1) ==
        sysid::internal::nn::SumSquares(p.Z, p.y, p.H, p.theta, 2));
  Eigen::VectorXd theta1 = p.theta, theta2 = p.theta;
  Eigen::MatrixXd A1, A2;
  const double out1 = sysid::internal::nn::SolveOutputLayer(p.Z, p.y, p.H, &theta1, &A1, 1);
  const double out2 = sysid::internal::nn::SolveOutputLayer(p.Z, p.y, p.H, &theta2, &A2, 2);
  CHECK(out1 == out2);
  CHECK(theta1 == theta2);
  CHECK(A1 == A2);
  // And the chunked sums are the whole-Jacobian ones.
  Eigen::MatrixXd J;
  sysid::internal::nn::Jacobian(p.Z, p.y, p.H, p.theta, &J);
  const Eigen::MatrixXd ref = J.transpose() * J;
  const Eigen::MatrixXd L = JtJ1.triangularView<Eigen::Lower>();
  const Eigen::MatrixXd Lref = ref.triangularView<Eigen::Lower>();
  CHECK((L - Lref).norm() <= 1e-12 * Lref.norm());
}

namespace {

// One kernel call's inputs and outputs copied into buffers that start `offset` bytes past a
// 32-byte boundary, so that a test controls what malloc otherwise decides.
class OffsetBuffer {
 public:
  OffsetBuffer(const double* src, std::size_t size, std::size_t offset)
      : store_(size + 8), data_(nullptr) {
    auto base = reinterpret_cast<std::uintptr_t>(store_.data());
    base = (base + 31) / 32 * 32 + offset;
    data_ = reinterpret_cast<double*>(base);
    if (src != nullptr) std::memcpy(data_, src, size * sizeof(double));
    else std::fill(data_, data_ + size, 0.0);
    size_ = size;
  }
  double* data() { return data_; }
  std::vector<double> Copy() const { return {data_, data_ + size_}; }

 private:
  std::vector<double> store_;
  double* data_;
  std::size_t size_ = 0;
};

// Every output of every kernel of the active table for one problem, with all buffers placed
// `offset` bytes past a 32-byte boundary.
std::vector<std::vector<double>> RunKernelsAt(const Problem& prob, std::size_t offset) {
  namespace isa = sysid::internal::nn::isa;
  const isa::Table& k = isa::ActiveTable();
  const int n = static_cast<int>(prob.Z.rows()), H = prob.H;
  const long N = prob.Z.cols();
  const auto P = static_cast<std::size_t>(sysid::internal::nn::ParameterCount(n, H));
  const auto uH = static_cast<std::size_t>(H), uN = static_cast<std::size_t>(N);
  OffsetBuffer Z(prob.Z.data(), prob.Z.size(), offset), y(prob.y.data(), uN, offset),
      theta(prob.theta.data(), P, offset);
  const isa::Problem p{Z.data(), n, y.data(), H, theta.data()};
  std::vector<std::vector<double>> out;
  // Start at sample 3 so that the samples' own offsets differ from the buffers' too.
  const long first = 3, count = N - 3, block = 64;
  OffsetBuffer A(nullptr, uH * uN, offset), r(nullptr, uN, offset), JT(nullptr, P * uN, offset);
  k.forward_block(p, first, count, A.data(), r.data());
  out.push_back(A.Copy());
  out.push_back(r.Copy());
  k.jacobian_transpose_block(p, first, count, JT.data(), A.data(), r.data());
  out.push_back(JT.Copy());
  out.push_back(A.Copy());
  out.push_back(r.Copy());
  OffsetBuffer JtJ(nullptr, P * P, offset), g(nullptr, P, offset);
  const double sse = k.normal_chunk(p, first, count, block, nullptr, JtJ.data(), g.data());
  out.push_back(JtJ.Copy());
  out.push_back(g.Copy());
  out.push_back({sse, k.sum_squares_chunk(p, first, count, block)});
  OffsetBuffer G(nullptr, (uH + 1) * (uH + 1), offset), c(nullptr, uH + 1, offset);
  k.output_normal_chunk(p, first, count, block, G.data(), c.data(), A.data());
  out.push_back(G.Copy());
  out.push_back(c.Copy());
  out.push_back(A.Copy());
  out.push_back({k.output_sse_chunk(p, first, count, A.data())});
  return out;
}

}  // namespace

TEST_CASE("every kernel's results are bit-identical wherever malloc puts the buffers",
          "[nn][kernels][simd][threads]") {
  // The AVX2 kernels work on 32-byte packets, but the program's buffers are only 16-byte
  // aligned (glibc malloc), and where each lands depends on the heap's history (threads,
  // earlier work). Results must not depend on it, or training is not reproducible.
  for (const char* isa_name : {"generic", "avx2+fma"}) {
    if (!sysid::internal::nn::SetKernelIsa(isa_name)) {
      WARN(isa_name << " kernels not built or not supported by this CPU: skipped");
      continue;
    }
    for (int n : {1, 2}) {
      for (int H : {13, 24}) {
        const Problem p = MakeProblem(n, H, 263, 90u + static_cast<unsigned>(n * H));
        const auto ref = RunKernelsAt(p, 0);
        for (std::size_t offset : {8u, 16u, 24u}) {
          INFO(isa_name << " n=" << n << " H=" << H << " offset " << offset << " bytes");
          const auto got = RunKernelsAt(p, offset);
          REQUIRE(got.size() == ref.size());
          for (std::size_t i = 0; i < ref.size(); ++i) {
            // Count the differing values rather than print thousands of them.
            std::size_t differ = got[i].size() == ref[i].size() ? 0 : ref[i].size();
            for (std::size_t j = 0; j < ref[i].size() && j < got[i].size(); ++j) {
              if (std::memcmp(&got[i][j], &ref[i][j], sizeof(double)) != 0) ++differ;
            }
            INFO("output " << i << ": " << differ << " of " << ref[i].size() << " values differ");
            CHECK(differ == 0);
          }
        }
      }
    }
  }
  REQUIRE(sysid::internal::nn::SetKernelIsa("auto"));
}

TEST_CASE("normal equations from the output-layer solve's hidden layer are bit-identical to "
          "those that recompute it",
          "[nn][kernels]") {
  // The LM trainer hands NormalEquations the hidden layer its last output-layer solve left
  // (same W1, b1; new w2, b2); that must change no bit of J'J, J'r or the sum of squares, on
  // every instruction set, and the hidden layer must really be used (a wrong one changes them).
  for (const char* isa : {"generic", "avx2+fma"}) {
    if (!sysid::internal::nn::SetKernelIsa(isa)) continue;
    for (int n : {1, 2}) {
      const Problem p = MakeProblem(n, 13, 3001, 91u + static_cast<unsigned>(n));
      Eigen::VectorXd theta = p.theta;
      Eigen::MatrixXd A;
      REQUIRE(std::isfinite(sysid::internal::nn::SolveOutputLayer(p.Z, p.y, p.H, &theta, &A, 2)));
      Eigen::MatrixXd JtJ0, JtJ1;
      Eigen::VectorXd g0, g1;
      double sse0 = 0, sse1 = 0;
      sysid::internal::nn::NormalEquations(p.Z, p.y, p.H, theta, &JtJ0, &g0, &sse0, 0, 2);
      sysid::internal::nn::NormalEquations(p.Z, p.y, p.H, theta, &JtJ1, &g1, &sse1, 0, 2, &A);
      CHECK(JtJ1.triangularView<Eigen::Lower>().toDenseMatrix() ==
            JtJ0.triangularView<Eigen::Lower>().toDenseMatrix());
      CHECK(g1 == g0);
      CHECK(sse1 == sse0);
      Eigen::MatrixXd wrong = A;
      wrong(3, 17) += 1e-3;
      sysid::internal::nn::NormalEquations(p.Z, p.y, p.H, theta, &JtJ1, &g1, &sse1, 0, 2, &wrong);
      CHECK(sse1 != sse0);
    }
  }
  REQUIRE(sysid::internal::nn::SetKernelIsa("auto"));
}
