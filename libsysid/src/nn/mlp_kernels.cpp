#include "nn/mlp_kernels.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <algorithm>
#include <limits>

namespace sysid::nn {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

Weights::Weights(const VectorXd& theta, int n, int H)
    : W1(theta.data(), H, n),
      b1(theta.data() + H * n, H),
      w2(theta.data() + H * n + H, H),
      b2(theta[H * n + 2 * H]) {}

void TanhInPlace(Eigen::Ref<Eigen::ArrayXXd> x) {
  // tanh(x) = 1 - 2 / (exp(2x) + 1); exp(2x) = inf gives exactly 1, exp(2x) = 0 exactly -1.
  x = 1.0 - 2.0 / ((2.0 * x).exp() + 1.0);
}

namespace {

// A = tanh(W1 Z_block + b1), r = w2' A + b2 - y_block.
void ForwardBlock(const MatrixXd& Z, const VectorXd& y, const Weights& w, Index first, Index count,
                  MatrixXd* A, VectorXd* r) {
  A->resize(w.W1.rows(), count);
  A->noalias() = w.W1 * Z.middleCols(first, count);
  A->colwise() += w.b1;
  TanhInPlace(A->array());
  r->resize(count);
  r->noalias() = A->transpose() * w.w2;
  r->array() += w.b2 - y.segment(first, count).array();
}

}  // namespace

int DefaultBlock(int P) { return std::clamp(32768 / std::max(P, 1), 32, 1024); }

void Residuals(const MatrixXd& Z, const VectorXd& y, int H, const VectorXd& theta, VectorXd* r) {
  const int n = static_cast<int>(Z.rows());
  const Weights w(theta, n, H);
  const Index N = Z.cols();
  r->resize(N);
  MatrixXd A;
  VectorXd rb;
  const Index B = DefaultBlock(ParameterCount(n, H));
  for (Index first = 0; first < N; first += B) {
    const Index count = std::min(B, N - first);
    ForwardBlock(Z, y, w, first, count, &A, &rb);
    r->segment(first, count) = rb;
  }
}

void ResidualBlock(const MatrixXd& Z, const VectorXd& y, int H, const VectorXd& theta, Index first,
                   Index count, VectorXd* r) {
  const Weights w(theta, static_cast<int>(Z.rows()), H);
  MatrixXd A;
  ForwardBlock(Z, y, w, first, count, &A, r);
}

double SumSquares(const MatrixXd& Z, const VectorXd& y, int H, const VectorXd& theta) {
  const int n = static_cast<int>(Z.rows());
  const Weights w(theta, n, H);
  const Index N = Z.cols();
  MatrixXd A;
  VectorXd rb;
  double sse = 0;
  const Index B = DefaultBlock(ParameterCount(n, H));
  for (Index first = 0; first < N; first += B) {
    const Index count = std::min(B, N - first);
    ForwardBlock(Z, y, w, first, count, &A, &rb);
    sse += rb.squaredNorm();
  }
  return sse;
}

void JacobianTransposeBlock(const MatrixXd& Z, const VectorXd& y, int H, const VectorXd& theta,
                            Index first, Index count, MatrixXd* JT, MatrixXd* A, VectorXd* r) {
  const int n = static_cast<int>(Z.rows());
  const int P = ParameterCount(n, H);
  const Weights w(theta, n, H);
  ForwardBlock(Z, y, w, first, count, A, r);
  JT->resize(P, count);
  // d r / d b1_h = w2_h (1 - a_h^2); d r / d W1_hi = that times z_i.
  auto D = JT->middleRows(H * n, H);
  D.array() = (1.0 - A->array().square()).colwise() * w.w2.array();
  const auto Zb = Z.middleCols(first, count);
  for (int i = 0; i < n; ++i) {
    // Rows h n + i of JT (h = 0..H-1): a strided view.
    Eigen::Map<MatrixXd, 0, Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>> rows_i(
        JT->data() + i, H, count, Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>(P, n));
    rows_i.array() = D.array().rowwise() * Zb.row(i).array();
  }
  JT->middleRows(H * n + H, H) = *A;
  JT->row(P - 1).setOnes();
}

void Jacobian(const MatrixXd& Z, const VectorXd& y, int H, const VectorXd& theta, MatrixXd* J) {
  const int n = static_cast<int>(Z.rows());
  const int P = ParameterCount(n, H);
  const Index N = Z.cols();
  J->resize(N, P);
  MatrixXd JT, A;
  VectorXd r;
  const Index B = DefaultBlock(P);
  for (Index first = 0; first < N; first += B) {
    const Index count = std::min(B, N - first);
    JacobianTransposeBlock(Z, y, H, theta, first, count, &JT, &A, &r);
    J->middleRows(first, count) = JT.transpose();
  }
}

void NormalEquations(const MatrixXd& Z, const VectorXd& y, int H, const VectorXd& theta,
                     MatrixXd* JtJ, VectorXd* g, double* sse, int block) {
  const int n = static_cast<int>(Z.rows());
  const int P = ParameterCount(n, H);
  const Index N = Z.cols();
  JtJ->setZero(P, P);
  g->setZero(P);
  *sse = 0;
  MatrixXd JT, A;
  VectorXd r;
  const Index B = block > 0 ? block : DefaultBlock(P);
  for (Index first = 0; first < N; first += B) {
    const Index count = std::min(B, N - first);
    JacobianTransposeBlock(Z, y, H, theta, first, count, &JT, &A, &r);
    JtJ->selfadjointView<Eigen::Lower>().rankUpdate(JT);
    g->noalias() += JT * r;
    *sse += r.squaredNorm();
  }
}

double SolveOutputLayer(const MatrixXd& Z, const VectorXd& y, int H, VectorXd* theta, MatrixXd* A) {
  const int n = static_cast<int>(Z.rows());
  const Index N = Z.cols();
  {
    const Weights w(*theta, n, H);
    A->resize(H, N);
    A->noalias() = w.W1 * Z;
    A->colwise() += w.b1;
  }
  TanhInPlace(A->array());
  // Normal equations of M = [A' 1]: G = M'M, c = M'y, accumulated by blocks.
  MatrixXd G = MatrixXd::Zero(H + 1, H + 1);
  VectorXd c(H + 1);
  c.head(H).noalias() = *A * y;
  c[H] = y.sum();
  G.topLeftCorner(H, H).selfadjointView<Eigen::Lower>().rankUpdate(*A);
  G.block(H, 0, 1, H) = A->rowwise().sum().transpose();
  G(H, H) = static_cast<double>(N);
  const double ridge = 1e-12 * G.diagonal().mean() + std::numeric_limits<double>::min();
  G.diagonal().array() += ridge;
  Eigen::LDLT<MatrixXd, Eigen::Lower> ldlt(G);
  const VectorXd sol = ldlt.solve(c);
  if (ldlt.info() != Eigen::Success || !sol.allFinite())
    return std::numeric_limits<double>::quiet_NaN();
  theta->segment(H * n + H, H) = sol.head(H);
  (*theta)[H * n + 2 * H] = sol[H];
  VectorXd r = A->transpose() * sol.head(H);
  r.array() += sol[H] - y.array();
  return r.squaredNorm();
}

}  // namespace sysid::nn
