#include "core/small_vector_ops.hpp"

#include <cmath>

// Bit-identity with the serial operations needs every product rounded before its sum: this
// file is compiled with -ffp-contract=off (libsysid/CMakeLists.txt), so -march=native does not
// fuse them.

namespace sysid::internal {
namespace {

template <int N>
double* Data(N_Vector v) {
  return NV_DATA_S(v);
}

template <int N>
void LinearSum(double a, N_Vector x, double b, N_Vector y, N_Vector z) {
  const double* xd = Data<N>(x);
  const double* yd = Data<N>(y);
  double* zd = Data<N>(z);
  if (a == b) {
    for (int i = 0; i < N; ++i) zd[i] = a * (xd[i] + yd[i]);
  } else if (a == -b) {
    for (int i = 0; i < N; ++i) zd[i] = a * (xd[i] - yd[i]);
  } else {
    for (int i = 0; i < N; ++i) zd[i] = a * xd[i] + b * yd[i];
  }
}

// In N_VLinearSum_Serial, a = b = -1 and (a, b) = (1, -1), (-1, 1) take paths that give the
// same numbers as the formulas above: -(y) - x = -1 (x + y), x - y = 1 (x - y),
// y - x = -1 (x - y) (negation is exact, x - y = -(y - x)). Only a = b and a = -b round
// differently from a x + b y, and the ones taken first (in-place a x + y, a = b = 1) agree.

template <int N>
void Scale(double c, N_Vector x, N_Vector z) {
  const double* xd = Data<N>(x);
  double* zd = Data<N>(z);
  for (int i = 0; i < N; ++i) zd[i] = c * xd[i];
}

template <int N>
double WrmsNorm(N_Vector x, N_Vector w) {
  const double* xd = Data<N>(x);
  const double* wd = Data<N>(w);
  double sum = 0.0;
  for (int i = 0; i < N; ++i) {
    const double p = xd[i] * wd[i];
    sum += p * p;
  }
  sum /= N;
  return sum <= 0.0 ? 0.0 : std::sqrt(sum);
}

// z = c[0] X[0] + c[1] X[1] + ... in that order; two vectors are a linear sum (the serial
// operation hands them to N_VLinearSum_Serial, special cases included).
template <int N>
int LinearCombination(int nvec, double* c, N_Vector* X, N_Vector z) {
  if (nvec < 1) return -1;
  if (nvec == 2) {
    LinearSum<N>(c[0], X[0], c[1], X[1], z);
    return 0;
  }
  double* zd = Data<N>(z);
  const double* x0 = Data<N>(X[0]);
  for (int j = 0; j < N; ++j) zd[j] = c[0] * x0[j];
  for (int i = 1; i < nvec; ++i) {
    const double* xi = Data<N>(X[i]);
    for (int j = 0; j < N; ++j) zd[j] += c[i] * xi[j];
  }
  return 0;
}

// Z[i] = a[i] x + Y[i].
template <int N>
int ScaleAddMulti(int nvec, double* a, N_Vector x, N_Vector* Y, N_Vector* Z) {
  if (nvec < 1) return -1;
  const double* xd = Data<N>(x);
  for (int i = 0; i < nvec; ++i) {
    const double* yd = Data<N>(Y[i]);
    double* zd = Data<N>(Z[i]);
    for (int j = 0; j < N; ++j) zd[j] = a[i] * xd[j] + yd[j];
  }
  return 0;
}

// The error weights, once per step: 1 / (rtol |y| + atol).
template <int N>
void Abs(N_Vector x, N_Vector z) {
  const double* xd = Data<N>(x);
  double* zd = Data<N>(z);
  for (int i = 0; i < N; ++i) zd[i] = std::fabs(xd[i]);
}

template <int N>
void AddConst(N_Vector x, double b, N_Vector z) {
  const double* xd = Data<N>(x);
  double* zd = Data<N>(z);
  for (int i = 0; i < N; ++i) zd[i] = xd[i] + b;
}

template <int N>
void Inv(N_Vector x, N_Vector z) {
  const double* xd = Data<N>(x);
  double* zd = Data<N>(z);
  for (int i = 0; i < N; ++i) zd[i] = 1.0 / xd[i];
}

template <int N>
void Const(double c, N_Vector z) {
  double* zd = Data<N>(z);
  for (int i = 0; i < N; ++i) zd[i] = c;
}

// The vector-array operations, for CVODES' sensitivities (one vector per parameter). Each is
// the single-vector operation above on every vector of the array: N_VLinearSumVectorArray_Serial's
// special cases (axpy in place, a = 1, a = -1) give the same numbers as LinearSum's formulas, as
// the single ones do.

template <int N>
int LinearSumVectorArray(int nvec, double a, N_Vector* X, double b, N_Vector* Y, N_Vector* Z) {
  if (nvec < 1) return -1;
  if (a == b) {
    for (int i = 0; i < nvec; ++i) {
      const double* xd = Data<N>(X[i]);
      const double* yd = Data<N>(Y[i]);
      double* zd = Data<N>(Z[i]);
      for (int j = 0; j < N; ++j) zd[j] = a * (xd[j] + yd[j]);
    }
  } else if (a == -b) {
    for (int i = 0; i < nvec; ++i) {
      const double* xd = Data<N>(X[i]);
      const double* yd = Data<N>(Y[i]);
      double* zd = Data<N>(Z[i]);
      for (int j = 0; j < N; ++j) zd[j] = a * (xd[j] - yd[j]);
    }
  } else {
    for (int i = 0; i < nvec; ++i) {
      const double* xd = Data<N>(X[i]);
      const double* yd = Data<N>(Y[i]);
      double* zd = Data<N>(Z[i]);
      for (int j = 0; j < N; ++j) zd[j] = a * xd[j] + b * yd[j];
    }
  }
  return 0;
}

template <int N>
int ScaleVectorArray(int nvec, double* c, N_Vector* X, N_Vector* Z) {
  if (nvec < 1) return -1;
  for (int i = 0; i < nvec; ++i) Scale<N>(c[i], X[i], Z[i]);
  return 0;
}

template <int N>
int ConstVectorArray(int nvec, double c, N_Vector* Z) {
  if (nvec < 1) return -1;
  for (int i = 0; i < nvec; ++i) Const<N>(c, Z[i]);
  return 0;
}

template <int N>
int WrmsNormVectorArray(int nvec, N_Vector* X, N_Vector* W, double* norms) {
  if (nvec < 1) return -1;
  for (int i = 0; i < nvec; ++i) norms[i] = WrmsNorm<N>(X[i], W[i]);
  return 0;
}

// Z[j][i] = a[j] X[i] + Y[j][i]. With b = 1 every special case of the serial linear sum
// equals a x + y (a = 1: x + y; a = -1: y - x), so there is one formula.
template <int N>
int ScaleAddMultiVectorArray(int nvec, int nsum, double* a, N_Vector* X, N_Vector** Y,
                             N_Vector** Z) {
  if (nvec < 1 || nsum < 1) return -1;
  for (int i = 0; i < nvec; ++i) {
    const double* xd = Data<N>(X[i]);
    for (int j = 0; j < nsum; ++j) {
      const double* yd = Data<N>(Y[j][i]);
      double* zd = Data<N>(Z[j][i]);
      for (int k = 0; k < N; ++k) zd[k] = a[j] * xd[k] + yd[k];
    }
  }
  return 0;
}

// Z[j] = c[0] X[0][j] + c[1] X[1][j] + ... in that order; two terms are a linear sum, as in
// LinearCombination.
template <int N>
int LinearCombinationVectorArray(int nvec, int nsum, double* c, N_Vector** X, N_Vector* Z) {
  if (nvec < 1 || nsum < 1) return -1;
  if (nsum == 2) return LinearSumVectorArray<N>(nvec, c[0], X[0], c[1], X[1], Z);
  for (int j = 0; j < nvec; ++j) {
    double* zd = Data<N>(Z[j]);
    const double* x0 = Data<N>(X[0][j]);
    for (int k = 0; k < N; ++k) zd[k] = c[0] * x0[k];
    for (int i = 1; i < nsum; ++i) {
      const double* xi = Data<N>(X[i][j]);
      for (int k = 0; k < N; ++k) zd[k] += c[i] * xi[k];
    }
  }
  return 0;
}

template <int N>
void Install(N_Vector v) {
  v->ops->nvlinearsum = &LinearSum<N>;
  v->ops->nvscale = &Scale<N>;
  v->ops->nvwrmsnorm = &WrmsNorm<N>;
  v->ops->nvlinearcombination = &LinearCombination<N>;
  v->ops->nvscaleaddmulti = &ScaleAddMulti<N>;
  v->ops->nvabs = &Abs<N>;
  v->ops->nvaddconst = &AddConst<N>;
  v->ops->nvinv = &Inv<N>;
  v->ops->nvconst = &Const<N>;
  v->ops->nvlinearsumvectorarray = &LinearSumVectorArray<N>;
  v->ops->nvscalevectorarray = &ScaleVectorArray<N>;
  v->ops->nvconstvectorarray = &ConstVectorArray<N>;
  v->ops->nvwrmsnormvectorarray = &WrmsNormVectorArray<N>;
  v->ops->nvscaleaddmultivectorarray = &ScaleAddMultiVectorArray<N>;
  v->ops->nvlinearcombinationvectorarray = &LinearCombinationVectorArray<N>;
}

}  // namespace

bool UseSmallVectorOps(N_Vector v) {
  if (N_VGetVectorID(v) != SUNDIALS_NVEC_SERIAL) return false;
  switch (NV_LENGTH_S(v)) {
    case 1: Install<1>(v); return true;
    case 2: Install<2>(v); return true;
    case 3: Install<3>(v); return true;
    case 4: Install<4>(v); return true;
    default: return false;
  }
}

}  // namespace sysid::internal
