// Private numerical kernels of the one-hidden-layer tanh network in normalised units:
// residuals, the Jacobian of the residuals and the Gauss–Newton normal equations J'J, J'r.
// theta = [W1 (H x n, row-major), b1, w2, b2]; data Z is n x N (one column per sample).
// The normal equations are accumulated block by block (a few hundred samples at a time) so
// that the Jacobian block stays in cache and is never stored whole. The hot loops run in the
// kernels of the best instruction set the CPU has (mlp_kernels_isa.hpp), and the sample range
// is cut into a fixed number of chunks whose partial sums are added in chunk order, so that
// results are bit-identical for any number of threads.
#ifndef SYSID_SRC_NN_MLP_KERNELS_HPP_
#define SYSID_SRC_NN_MLP_KERNELS_HPP_

#include <Eigen/Core>

namespace sysid::internal::nn {

/// Where each part of theta = [W1 (H x n, row-major), b1, w2, b2] starts: the one definition of
/// the network's parameter layout (the kernels in mlp_kernels_impl.inc, which may not include
/// Eigen-using headers, spell the same offsets out; the kernel tests check them against the
/// network's own evaluation).
struct ParameterLayout {
  int n, H;
  int W1() const { return 0; }
  int b1() const { return H * n; }
  int w2() const { return H * n + H; }
  int b2() const { return H * n + 2 * H; }
  int count() const { return H * (n + 2) + 1; }
};

/// Views of theta's parts.
struct Weights {
  Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> W1;
  Eigen::Map<const Eigen::VectorXd> b1, w2;
  double b2;
  Weights(const Eigen::VectorXd& theta, int n, int H);
};

inline int ParameterCount(int n, int H) { return ParameterLayout{n, H}.count(); }

/// theta from its parts (W1 H x n, b1, w2 of size H, b2).
Eigen::VectorXd PackParameters(const Eigen::MatrixXd& W1, const Eigen::VectorXd& b1,
                               const Eigen::VectorXd& w2, double b2);

/// tanh through exp (Eigen vectorises exp for double but not tanh): absolute error ~1e-16,
/// exact limits +-1 for large |x|, NaN in gives NaN out.
void TanhInPlace(Eigen::Ref<Eigen::ArrayXXd> x);

/// r = net(Z) - y (size N).
void Residuals(const Eigen::MatrixXd& Z, const Eigen::VectorXd& y, int H,
               const Eigen::VectorXd& theta, Eigen::VectorXd* r);

/// Residuals of samples [first, first + count) into r (size count).
void ResidualBlock(const Eigen::MatrixXd& Z, const Eigen::VectorXd& y, int H,
                   const Eigen::VectorXd& theta, Eigen::Index first, Eigen::Index count,
                   Eigen::VectorXd* r);

/// Sum of squared residuals (blocked; no N-sized temporaries), on `threads` threads (0: all
/// cores); the result does not depend on `threads`.
double SumSquares(const Eigen::MatrixXd& Z, const Eigen::VectorXd& y, int H,
                  const Eigen::VectorXd& theta, int threads = 1);

/// Transposed Jacobian of the residuals of samples [first, first + count): P x count, column k
/// is d r_(first+k) / d theta. `A` (H x count) receives tanh(W1 z + b1); `r` the residuals.
void JacobianTransposeBlock(const Eigen::MatrixXd& Z, const Eigen::VectorXd& y, int H,
                            const Eigen::VectorXd& theta, Eigen::Index first, Eigen::Index count,
                            Eigen::MatrixXd* JT, Eigen::MatrixXd* A, Eigen::VectorXd* r);

/// Full Jacobian J (N x P) of the residuals (tests, Ceres and benchmarks).
void Jacobian(const Eigen::MatrixXd& Z, const Eigen::VectorXd& y, int H,
              const Eigen::VectorXd& theta, Eigen::MatrixXd* J);

/// Gauss–Newton pieces: the lower triangle of J'J (P x P), g = J'r and sum r^2, accumulated
/// over blocks of `block` samples by symmetric rank-k updates, on `threads` threads (0: all
/// cores); the result does not depend on `threads`. `hidden` (H x N), when given, is theta's
/// hidden layer as SolveOutputLayer left it for the same W1 and b1 (that solve changes only
/// w2 and b2): the tanh pass is skipped, and with the default block the result is bit for bit
/// the one computed without it.
void NormalEquations(const Eigen::MatrixXd& Z, const Eigen::VectorXd& y, int H,
                     const Eigen::VectorXd& theta, Eigen::MatrixXd* JtJ, Eigen::VectorXd* g,
                     double* sse, int block = 0, int threads = 1,
                     const Eigen::MatrixXd* hidden = nullptr);

/// Replaces (w2, b2) in theta by the linear least-squares optimum for theta's hidden layer,
/// min ||A' w2 + b2 - y||^2 with A = tanh(W1 Z + b1), and returns the new sum of squares.
/// `A` receives the hidden layer (H x N). A tiny ridge (1e-12 of the mean diagonal) keeps the
/// normal equations solvable when hidden units saturate alike. On `threads` threads (0: all
/// cores); the result does not depend on `threads`.
double SolveOutputLayer(const Eigen::MatrixXd& Z, const Eigen::VectorXd& y, int H,
                        Eigen::VectorXd* theta, Eigen::MatrixXd* A, int threads = 1);

/// The block size NormalEquations uses when block == 0 (keeps P x block near 256 KiB).
int DefaultBlock(int P);

/// The instruction set of the kernels in use: "generic" or "avx2+fma".
const char* KernelIsa();

/// Forces the kernels of one instruction set ("generic", "avx2+fma") or, with "auto", the best
/// one the CPU has. Returns false (and changes nothing) when that set is not built or the CPU
/// lacks it. For tests and benchmarks; not thread-safe against running kernels.
bool SetKernelIsa(const char* name);

}  // namespace sysid::internal::nn

#endif  // SYSID_SRC_NN_MLP_KERNELS_HPP_
