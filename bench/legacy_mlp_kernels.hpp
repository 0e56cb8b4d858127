// The network kernels as they were before SIMD dispatch and threads (libsysid commit 849cd87,
// nn/mlp_kernels.cpp): Eigen with the build's default flags, strided Jacobian writes, one
// thread. Kept here only as the baseline of bench_nn's epoch targets.
#ifndef SYSID_BENCH_LEGACY_MLP_KERNELS_HPP_
#define SYSID_BENCH_LEGACY_MLP_KERNELS_HPP_

#include <Eigen/Core>
#include <algorithm>

namespace legacy {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

struct Weights {
  Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> W1;
  Eigen::Map<const Eigen::VectorXd> b1, w2;
  double b2;
  Weights(const VectorXd& theta, int n, int H)
      : W1(theta.data(), H, n),
        b1(theta.data() + H * n, H),
        w2(theta.data() + H * n + H, H),
        b2(theta[H * n + 2 * H]) {}
};

inline void ForwardBlock(const MatrixXd& Z, const VectorXd& y, const Weights& w, Index first,
                         Index count, MatrixXd* A, VectorXd* r) {
  A->resize(w.W1.rows(), count);
  A->noalias() = w.W1 * Z.middleCols(first, count);
  A->colwise() += w.b1;
  A->array() = 1.0 - 2.0 / ((2.0 * A->array()).exp() + 1.0);
  r->resize(count);
  r->noalias() = A->transpose() * w.w2;
  r->array() += w.b2 - y.segment(first, count).array();
}

inline int DefaultBlock(int P) { return std::clamp(32768 / std::max(P, 1), 32, 1024); }

inline double SumSquares(const MatrixXd& Z, const VectorXd& y, int H, const VectorXd& theta) {
  const int n = static_cast<int>(Z.rows());
  const Weights w(theta, n, H);
  const Index N = Z.cols();
  MatrixXd A;
  VectorXd rb;
  double sse = 0;
  const Index B = DefaultBlock(H * (n + 2) + 1);
  for (Index first = 0; first < N; first += B) {
    const Index count = std::min(B, N - first);
    ForwardBlock(Z, y, w, first, count, &A, &rb);
    sse += rb.squaredNorm();
  }
  return sse;
}

inline void JacobianTransposeBlock(const MatrixXd& Z, const VectorXd& y, int H,
                                   const VectorXd& theta, Index first, Index count, MatrixXd* JT,
                                   MatrixXd* A, VectorXd* r) {
  const int n = static_cast<int>(Z.rows());
  const int P = H * (n + 2) + 1;
  const Weights w(theta, n, H);
  ForwardBlock(Z, y, w, first, count, A, r);
  JT->resize(P, count);
  auto D = JT->middleRows(H * n, H);
  D.array() = (1.0 - A->array().square()).colwise() * w.w2.array();
  const auto Zb = Z.middleCols(first, count);
  for (int i = 0; i < n; ++i) {
    Eigen::Map<MatrixXd, 0, Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>> rows_i(
        JT->data() + i, H, count, Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>(P, n));
    rows_i.array() = D.array().rowwise() * Zb.row(i).array();
  }
  JT->middleRows(H * n + H, H) = *A;
  JT->row(P - 1).setOnes();
}

inline void NormalEquations(const MatrixXd& Z, const VectorXd& y, int H, const VectorXd& theta,
                            MatrixXd* JtJ, VectorXd* g, double* sse) {
  const int n = static_cast<int>(Z.rows());
  const int P = H * (n + 2) + 1;
  const Index N = Z.cols();
  JtJ->setZero(P, P);
  g->setZero(P);
  *sse = 0;
  MatrixXd JT, A;
  VectorXd r;
  const Index B = DefaultBlock(P);
  for (Index first = 0; first < N; first += B) {
    const Index count = std::min(B, N - first);
    JacobianTransposeBlock(Z, y, H, theta, first, count, &JT, &A, &r);
    JtJ->selfadjointView<Eigen::Lower>().rankUpdate(JT);
    g->noalias() += JT * r;
    *sse += r.squaredNorm();
  }
}

}  // namespace legacy

#endif  // SYSID_BENCH_LEGACY_MLP_KERNELS_HPP_
