#include "identify/linear_fit.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <Eigen/QR>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <limits>

#include "sysid/error.hpp"

namespace sysid::internal {

// A column whose pivot falls below 1e-10 of the largest (after scaling every column to unit
// norm) is numerically a combination of the others: beyond what 1 kHz data can separate.
double RelativeRankThreshold() { return 1e-10; }

LinearFitOutcome SolveLinearFit(const Eigen::MatrixXd& X, const Eigen::VectorXd& y,
                                const std::vector<std::string>& names) {
  SYSID_CHECK(static_cast<size_t>(X.cols()) == names.size() && X.rows() == y.size(),
              "regressor shape");
  const Eigen::Index n = X.rows(), p = X.cols();
  // Finite data can still overflow (a gain of 1e308 times a voltage): said, never solved into
  // NaN parameters that a report would print and a model file could not hold.
  if (!X.allFinite() || !y.allFinite())
    throw NumericalError(fmt::format(
        "least squares for {}: the {} holds inf or NaN (a value or gain out of range; largest "
        "finite |target| {:.3g})",
        fmt::join(names, ", "), X.allFinite() ? "target" : "regressor",
        y.unaryExpr([](double v) { return std::isfinite(v) ? std::abs(v) : 0.0; }).maxCoeff()));
  LinearFitOutcome out;
  LinearFit& f = out.fit;
  f.names = names;
  f.rows = n;
  // Unit-norm columns: the rank test and the pivot order must not depend on units (a1 v is
  // ~0.1 m/s^2 per unit while the Coulomb column is 1).
  Eigen::VectorXd scale(p);
  for (Eigen::Index j = 0; j < p; ++j) {
    const double c = X.col(j).norm();
    scale[j] = c > 0 ? 1.0 / c : 1.0;
  }
  const Eigen::MatrixXd Xs = X * scale.asDiagonal();
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(Xs);
  qr.setThreshold(RelativeRankThreshold());
  f.rank = static_cast<int>(qr.rank());
  const auto& perm = qr.colsPermutation().indices();
  // |R_ii| of the unscaled problem: R_s = Q^T X D P, so column j of R carries 1/scale.
  const Eigen::MatrixXd R =
      qr.matrixR().topLeftCorner(std::min(n, p), p).template triangularView<Eigen::Upper>();
  for (Eigen::Index i = 0; i < std::min(n, p); ++i) {
    const Eigen::Index col = perm[i];
    f.r_diagonal.emplace_back(names[static_cast<size_t>(col)], std::abs(R(i, i)) / scale[col]);
  }
  if (f.rank < p || n < p) {
    for (Eigen::Index i = f.rank; i < p; ++i)
      out.unidentified.push_back(names[static_cast<size_t>(perm[i])]);
    f.theta = Eigen::VectorXd::Zero(p);
    return out;
  }
  f.theta = scale.asDiagonal() * qr.solve(y);
  for (Eigen::Index j = 0; j < p; ++j)
    if (!std::isfinite(f.theta[j]))
      throw NumericalError(fmt::format("least squares: {} = {} (the solution overflowed: values "
                                       "or gains out of range)",
                                       names[static_cast<size_t>(j)], f.theta[j]));
  f.residuals = y - X * f.theta;
  f.dof = static_cast<int>(n - p);
  const double rss = f.residuals.squaredNorm();
  f.rms_residual = std::sqrt(rss / static_cast<double>(n));
  const double ynorm = y.norm();
  f.relative_error = ynorm > 0 ? std::sqrt(rss) / ynorm : 0.0;
  // (X^T X)^-1 = D P R^-1 R^-T P^T D from the scaled factorisation.
  const Eigen::MatrixXd Rp = R.topLeftCorner(p, p);
  const Eigen::MatrixXd Rinv =
      Rp.triangularView<Eigen::Upper>().solve(Eigen::MatrixXd::Identity(p, p));
  Eigen::MatrixXd inv_scaled = Rinv * Rinv.transpose();  // in pivoted order
  Eigen::MatrixXd inv(p, p);
  for (Eigen::Index i = 0; i < p; ++i)
    for (Eigen::Index j = 0; j < p; ++j)
      inv(perm[i], perm[j]) = inv_scaled(i, j) * scale[perm[i]] * scale[perm[j]];
  const double s2 = f.dof > 0 ? rss / f.dof : std::numeric_limits<double>::quiet_NaN();
  f.covariance = s2 * inv;
  f.std_error = f.covariance.diagonal().cwiseSqrt();
  // Singular values of X equal those of R (Q is orthogonal); undo the column scaling first.
  Eigen::MatrixXd Ru(p, p);
  for (Eigen::Index j = 0; j < p; ++j) Ru.col(j) = Rp.col(j) / scale[perm[j]];
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(Ru);
  const auto& sv = svd.singularValues();
  f.condition_number = sv[p - 1] > 0 ? sv[0] / sv[p - 1] : std::numeric_limits<double>::infinity();
  return out;
}

}  // namespace sysid::internal
