// The hot loops of the network kernels behind a raw-pointer interface, compiled once per
// instruction set (mlp_kernels_generic.cpp: the build's default flags; mlp_kernels_avx2.cpp:
// -mavx2 -mfma) and chosen at start-up by mlp_kernels.cpp. No Eigen type crosses this
// interface: the AVX2 translation unit renames Eigen's namespace so that its inline template
// instantiations (compiled for AVX2) can never be picked by the linker for the default path.
#ifndef SYSID_SRC_NN_MLP_KERNELS_ISA_HPP_
#define SYSID_SRC_NN_MLP_KERNELS_ISA_HPP_

namespace sysid::internal::nn::isa {

/// One network and data set in normalised units. Z is n x N column-major (one column per
/// sample); theta = [W1 (H x n, row-major), b1, w2, b2].
struct Problem {
  const double* Z;
  int n;
  const double* y;
  int H;
  const double* theta;
};

/// The kernels of one instruction set.
struct Table {
  const char* name;
  /// A (H x count) = tanh(W1 z + b1) and the residuals r (count) of samples
  /// [first, first + count).
  void (*forward_block)(const Problem&, long first, long count, double* A, double* r);
  /// JT (P x count, column-major, column k = d r_(first+k) / d theta), A (H x count) =
  /// tanh(W1 z + b1) and r (count) for samples [first, first + count).
  void (*jacobian_transpose_block)(const Problem&, long first, long count, double* JT, double* A,
                                   double* r);
  /// Adds to the lower triangle of JtJ (P x P, column-major), to g (P) and returns the sum of
  /// squared residuals of samples [first, first + count), in blocks of `block` samples.
  /// `hidden` (H x count, column-major), when not null, is those samples' hidden layer
  /// tanh(W1 z + b1) as output_normal_chunk computed it for the same W1, b1 and blocks: it
  /// replaces the tanh pass, with the same bits.
  double (*normal_chunk)(const Problem&, long first, long count, long block,
                         const double* hidden, double* JtJ, double* g);
  /// Sum of squared residuals of samples [first, first + count), in blocks of `block`.
  double (*sum_squares_chunk)(const Problem&, long first, long count, long block);
  /// Adds the output layer's normal equations of samples [first, first + count) to G (lower
  /// triangle, (H+1) x (H+1), column-major) and c (H+1): M = [A' 1], G += M'M, c += M'y.
  /// A (H x count, column-major) receives the hidden layer of those samples.
  void (*output_normal_chunk)(const Problem&, long first, long count, long block, double* G,
                              double* c, double* A);
  /// Sum of squared residuals of samples [first, first + count) from their stored hidden
  /// layer A (H x count) and theta's output layer.
  double (*output_sse_chunk)(const Problem&, long first, long count, const double* A);
};

namespace generic {
extern const Table kTable;
}

/// The table in use (internal::nn::SetKernelIsa chooses it); lets tests call the raw kernels.
const Table& ActiveTable();
namespace avx2 {
extern const Table kTable;  // defined only when SYSID_HAVE_AVX2_KERNELS is set
}

}  // namespace sysid::internal::nn::isa

#endif  // SYSID_SRC_NN_MLP_KERNELS_ISA_HPP_
