// Forward sensitivities of the Newmark/trapezoidal recursion, differentiated in the mechanical
// parameters: the benchmark chain's (then the FIR decimation, linear, so it decimates them as it
// does y) and the fixed step's (every m-th step kept). The Jacobian a fit needs in one pass
// instead of 2 p + 1 simulations.
//
// The step's equations R(y1, z1; y0, v0, a0, z0, p) = 0,
//   R1 = m a1 + c v1 + k y1 + z1 - u1,   R2 = z1 - z0 - h/2 (f(v0, z0) + f(v1, z1)),
//   v1 = 2 (y1 - y0) / h - v0,   a1 = 4 (y1 - y0 - h v0) / h^2 - a0,
// hold at the Newton solution for every p, so their total derivative in p is zero: the Newton
// matrix (dR/d(y1, z1)) times the new state's sensitivities equals minus the rest of the
// derivative, carried from the previous state's sensitivities and R's explicit p-dependence.
#include <fmt/format.h>

#include <cmath>

#include "hysteresis/bouc_wen_internal.hpp"
#include "sysid/error.hpp"

namespace sysid::internal {

namespace {

using Vec = MechanicalParameterVector;

}  // namespace

void NewmarkSensitivity(const MechanicalBoucWenParameters& p, const Eigen::VectorXd& uf, double h,
                        Eigen::Index stride, bool with_nu, Eigen::VectorXd* y,
                        NewmarkJacobian* dy_dp) {
  const Eigen::Index nf = uf.size();
  const Eigen::Index kept = nf > 0 ? (nf - 1) / stride + 1 : 0;
  const double m = p.m_kg, c = p.c_n_s_per_m, k = p.k_n_per_m;
  y->resize(kept);
  // Column i: dy/dp at kept sample i (the parameters of one sample side by side).
  dy_dp->resize(kMechanicalParameters, kept);
  if (nf == 0) return;
  // From rest: y = v = z = 0 for every p, a = u0 / m.
  double y0 = 0, v0 = 0, z0 = 0, a0 = uf[0] / m;
  Vec sy = Vec::Zero(), sv = Vec::Zero(), sz = Vec::Zero(), sa = Vec::Zero();
  sa[0] = -a0 / m;
  (*y)[0] = 0;
  dy_dp->col(0).setZero();
  BoucWenRate r0 = MechanicalRate(p, v0, z0);
  Vec f0p = MechanicalRateParameterPartials(p, v0, z0, with_nu);
  const double j11 = 4 * m / (h * h) + 2 * c / h + k;
  for (Eigen::Index i = 1; i < nf; ++i) {
    double y1 = 0, v1 = 0, a1 = 0, z1 = 0;
    NewmarkAdvance(p, uf[i], h, y0, v0, a0, z0, r0.f, i, &y1, &v1, &a1, &z1);
    const BoucWenRate r1 = MechanicalRate(p, v1, z1);
    const Vec f1p = MechanicalRateParameterPartials(p, v1, z1, with_nu);
    // R1's derivative without the (y1, z1) terms, moved to the right.
    Vec rhs1 = m * ((4 / (h * h)) * sy + (4 / h) * sv + sa) + c * ((2 / h) * sy + sv);
    rhs1[0] -= a1;
    rhs1[1] -= v1;
    rhs1[2] -= y1;
    // R2's, with dv1 = 2/h dy1 - 2/h dy0 - dv0 split the same way.
    const Vec rhs2 = sz + (0.5 * h) * (r0.df_dv * sv + r0.df_dz * sz + f0p + f1p) -
                     r1.df_dv * (sy + (0.5 * h) * sv);
    const double j21 = -r1.df_dv, j22 = 1 - 0.5 * h * r1.df_dz;
    const double det = j11 * j22 - j21;
    const Vec sy1 = (j22 * rhs1 - rhs2) / det;
    const Vec sz1 = (j11 * rhs2 - j21 * rhs1) / det;
    const Vec sv1 = (2 / h) * (sy1 - sy) - sv;
    sa = (4 / (h * h)) * (sy1 - sy - h * sv) - sa;
    sy = sy1;
    sv = sv1;
    sz = sz1;
    y0 = y1;
    v0 = v1;
    a0 = a1;
    z0 = z1;
    r0 = r1;
    f0p = f1p;
    if (i % stride == 0) {
      (*y)[i / stride] = y1;
      dy_dp->col(i / stride) = sy;
    }
  }
}

void ChainOutputSensitivity(const MechanicalBoucWenParameters& p, const Eigen::VectorXd& ufx,
                            Eigen::Index n, double dt_s, int upsampling, bool with_nu,
                            Eigen::VectorXd* y, Eigen::MatrixXd* dy_dp) {
  Eigen::VectorXd yf;
  NewmarkJacobian sf;
  NewmarkSensitivity(p, ufx, dt_s / upsampling, 1, with_nu, &yf, &sf);
  const std::vector<int> factors = PrimeFactors(upsampling);
  *y = DecimateChain(std::move(yf), factors).head(n);
  dy_dp->resize(n, kMechanicalParameters);
  for (int j = 0; j < kMechanicalParameters; ++j) {
    if (j == 7 && !with_nu) {
      dy_dp->col(j).setZero();
      continue;
    }
    dy_dp->col(j) = DecimateChain(sf.row(j).transpose(), factors).head(n);
  }
}

}  // namespace sysid::internal
