#include "nn/mlp_kernels.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <algorithm>
#include <atomic>
#include <limits>
#include <string>
#include <vector>

#include "core/parallel_for.hpp"
#include "nn/mlp_kernels_isa.hpp"

namespace sysid::internal::nn {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

Weights::Weights(const VectorXd& theta, int n, int H)
    : W1(theta.data() + ParameterLayout{n, H}.W1(), H, n),
      b1(theta.data() + ParameterLayout{n, H}.b1(), H),
      w2(theta.data() + ParameterLayout{n, H}.w2(), H),
      b2(theta[ParameterLayout{n, H}.b2()]) {}

VectorXd PackParameters(const MatrixXd& W1, const VectorXd& b1, const VectorXd& w2, double b2) {
  const int H = static_cast<int>(W1.rows()), n = static_cast<int>(W1.cols());
  const ParameterLayout l{n, H};
  VectorXd theta(l.count());
  for (int h = 0; h < H; ++h)
    for (int i = 0; i < n; ++i) theta[l.W1() + h * n + i] = W1(h, i);
  theta.segment(l.b1(), H) = b1;
  theta.segment(l.w2(), H) = w2;
  theta[l.b2()] = b2;
  return theta;
}

void TanhInPlace(Eigen::Ref<Eigen::ArrayXXd> x) {
  // tanh(x) = 1 - 2 / (exp(2x) + 1); exp(2x) = inf gives exactly 1, exp(2x) = 0 exactly -1.
  x = 1.0 - 2.0 / ((2.0 * x).exp() + 1.0);
}

namespace {

bool CpuHasAvx2Fma() {
#if defined(SYSID_HAVE_AVX2_KERNELS) && (defined(__GNUC__) || defined(__clang__))
  __builtin_cpu_init();
  return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
#else
  return false;
#endif
}

const isa::Table* BestTable() {
#ifdef SYSID_HAVE_AVX2_KERNELS
  if (CpuHasAvx2Fma()) return &isa::avx2::kTable;
#endif
  return &isa::generic::kTable;
}

std::atomic<const isa::Table*>& Current() {
  static std::atomic<const isa::Table*> table{BestTable()};
  return table;
}

const isa::Table& Kernels() { return *Current().load(std::memory_order_relaxed); }

isa::Problem MakeProblem(const MatrixXd& Z, const VectorXd& y, int H, const VectorXd& theta) {
  return {Z.data(), static_cast<int>(Z.rows()), y.data(), H, theta.data()};
}

// The fixed partition of N samples into chunks of whole blocks: chunk c holds blocks
// [c nb / C, (c + 1) nb / C). Independent of the thread count, so sums are too.
constexpr Index kChunks = 8;
struct Chunks {
  Index N, B, nb, C;
  Chunks(Index N_, Index B_) : N(N_), B(B_), nb((N_ + B_ - 1) / B_), C(std::min(kChunks, nb)) {}
  Index First(Index c) const { return std::min(N, (c * nb / C) * B); }
  Index Count(Index c) const { return First(c + 1) - First(c); }
};

void ForwardBlock(const MatrixXd& Z, const VectorXd& y, int H, const VectorXd& theta, Index first,
                  Index count, MatrixXd* A, VectorXd* r) {
  A->resize(H, count);
  r->resize(count);
  Kernels().forward_block(MakeProblem(Z, y, H, theta), first, count, A->data(), r->data());
}

}  // namespace

const isa::Table& isa::ActiveTable() { return Kernels(); }

const char* KernelIsa() { return Kernels().name; }

bool SetKernelIsa(const char* name) {
  const std::string s = name;
  const isa::Table* t = nullptr;
  if (s == "auto") t = BestTable();
  if (s == isa::generic::kTable.name) t = &isa::generic::kTable;
#ifdef SYSID_HAVE_AVX2_KERNELS
  if (s == isa::avx2::kTable.name && CpuHasAvx2Fma()) t = &isa::avx2::kTable;
#endif
  if (t == nullptr) return false;
  Current().store(t);
  return true;
}

int DefaultBlock(int P) { return std::clamp(32768 / std::max(P, 1), 32, 1024); }

namespace {

// f(first, count) for the consecutive blocks of DefaultBlock(P) samples out of N, in order.
template <class F>
void ForEachBlock(Index N, int P, F&& f) {
  const Index B = DefaultBlock(P);
  for (Index first = 0; first < N; first += B) f(first, std::min(B, N - first));
}

}  // namespace

void Residuals(const MatrixXd& Z, const VectorXd& y, int H, const VectorXd& theta, VectorXd* r) {
  const int n = static_cast<int>(Z.rows());
  const Index N = Z.cols();
  r->resize(N);
  MatrixXd A;
  VectorXd rb;
  ForEachBlock(N, ParameterCount(n, H), [&](Index first, Index count) {
    ForwardBlock(Z, y, H, theta, first, count, &A, &rb);
    r->segment(first, count) = rb;
  });
}

void ResidualBlock(const MatrixXd& Z, const VectorXd& y, int H, const VectorXd& theta, Index first,
                   Index count, VectorXd* r) {
  MatrixXd A;
  ForwardBlock(Z, y, H, theta, first, count, &A, r);
}

double SumSquares(const MatrixXd& Z, const VectorXd& y, int H, const VectorXd& theta, int threads) {
  const int n = static_cast<int>(Z.rows());
  const Chunks ch(Z.cols(), DefaultBlock(ParameterCount(n, H)));
  const isa::Problem p = MakeProblem(Z, y, H, theta);
  const isa::Table& k = Kernels();
  double part[kChunks] = {};
  internal::ParallelFor(ch.C, threads, [&](long c) {
    part[c] = k.sum_squares_chunk(p, ch.First(c), ch.Count(c), ch.B);
  });
  double sse = 0;
  for (Index c = 0; c < ch.C; ++c) sse += part[c];
  return sse;
}

void JacobianTransposeBlock(const MatrixXd& Z, const VectorXd& y, int H, const VectorXd& theta,
                            Index first, Index count, MatrixXd* JT, MatrixXd* A, VectorXd* r) {
  const int n = static_cast<int>(Z.rows());
  JT->resize(ParameterCount(n, H), count);
  A->resize(H, count);
  r->resize(count);
  Kernels().jacobian_transpose_block(MakeProblem(Z, y, H, theta), first, count, JT->data(),
                                     A->data(), r->data());
}

void Jacobian(const MatrixXd& Z, const VectorXd& y, int H, const VectorXd& theta, MatrixXd* J) {
  const int n = static_cast<int>(Z.rows());
  const int P = ParameterCount(n, H);
  const Index N = Z.cols();
  J->resize(N, P);
  MatrixXd JT, A;
  VectorXd r;
  ForEachBlock(N, P, [&](Index first, Index count) {
    JacobianTransposeBlock(Z, y, H, theta, first, count, &JT, &A, &r);
    J->middleRows(first, count) = JT.transpose();
  });
}

void NormalEquations(const MatrixXd& Z, const VectorXd& y, int H, const VectorXd& theta,
                     MatrixXd* JtJ, VectorXd* g, double* sse, int block, int threads,
                     const MatrixXd* hidden) {
  const int n = static_cast<int>(Z.rows());
  const int P = ParameterCount(n, H);
  const Chunks ch(Z.cols(), block > 0 ? block : DefaultBlock(P));
  const isa::Problem p = MakeProblem(Z, y, H, theta);
  const isa::Table& k = Kernels();
  // Chunk 0 accumulates into the outputs, the others into their own partial sums, which are
  // then added in chunk order.
  JtJ->setZero(P, P);
  g->setZero(P);
  std::vector<MatrixXd> JtJ_part(static_cast<std::size_t>(std::max<Index>(ch.C - 1, 0)));
  std::vector<VectorXd> g_part(JtJ_part.size());
  double sse_part[kChunks] = {};
  internal::ParallelFor(ch.C, threads, [&](long c) {
    double* jtj = JtJ->data();
    double* gp = g->data();
    if (c > 0) {
      JtJ_part[c - 1].setZero(P, P);
      g_part[c - 1].setZero(P);
      jtj = JtJ_part[c - 1].data();
      gp = g_part[c - 1].data();
    }
    const double* a = hidden != nullptr ? hidden->data() + ch.First(c) * H : nullptr;
    sse_part[c] = k.normal_chunk(p, ch.First(c), ch.Count(c), ch.B, a, jtj, gp);
  });
  *sse = sse_part[0];
  for (Index c = 1; c < ch.C; ++c) {
    JtJ->triangularView<Eigen::Lower>() += JtJ_part[c - 1];
    *g += g_part[c - 1];
    *sse += sse_part[c];
  }
}

double SolveOutputLayer(const MatrixXd& Z, const VectorXd& y, int H, VectorXd* theta, MatrixXd* A,
                        int threads) {
  const int n = static_cast<int>(Z.rows());
  const Chunks ch(Z.cols(), DefaultBlock(ParameterCount(n, H)));
  const isa::Problem p = MakeProblem(Z, y, H, *theta);
  const isa::Table& k = Kernels();
  // Normal equations of M = [A' 1]: G = M'M, c = M'y, by chunks added in chunk order.
  // A keeps the hidden layer for the final residuals (no second tanh pass).
  A->resize(H, Z.cols());
  std::vector<MatrixXd> G(static_cast<std::size_t>(ch.C));
  std::vector<VectorXd> c(G.size());
  internal::ParallelFor(ch.C, threads, [&](long i) {
    G[i].setZero(H + 1, H + 1);
    c[i].setZero(H + 1);
    k.output_normal_chunk(p, ch.First(i), ch.Count(i), ch.B, G[i].data(), c[i].data(),
                          A->data() + ch.First(i) * H);
  });
  for (Index i = 1; i < ch.C; ++i) {
    G[0].triangularView<Eigen::Lower>() += G[i];
    c[0] += c[i];
  }
  MatrixXd& Gs = G[0];
  const double ridge = 1e-12 * Gs.diagonal().mean() + std::numeric_limits<double>::min();
  Gs.diagonal().array() += ridge;
  Eigen::LDLT<MatrixXd, Eigen::Lower> ldlt(Gs);
  const VectorXd sol = ldlt.solve(c[0]);
  if (ldlt.info() != Eigen::Success || !sol.allFinite())
    return std::numeric_limits<double>::quiet_NaN();
  theta->segment(ParameterLayout{n, H}.w2(), H) = sol.head(H);
  (*theta)[ParameterLayout{n, H}.b2()] = sol[H];
  const isa::Problem solved = MakeProblem(Z, y, H, *theta);
  double part[kChunks] = {};
  internal::ParallelFor(ch.C, threads, [&](long i) {
    part[i] = k.output_sse_chunk(solved, ch.First(i), ch.Count(i), A->data() + ch.First(i) * H);
  });
  double sse = 0;
  for (Index i = 0; i < ch.C; ++i) sse += part[i];
  return sse;
}

}  // namespace sysid::internal::nn
