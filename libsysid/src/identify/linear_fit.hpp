// Private: rank-revealing linear least squares with the diagnostics of sysid::LinearFit.
#ifndef SYSID_SRC_IDENTIFY_LINEAR_FIT_HPP_
#define SYSID_SRC_IDENTIFY_LINEAR_FIT_HPP_

#include <Eigen/Core>
#include <string>
#include <vector>

#include "sysid/identify.hpp"

namespace sysid::internal {

/// Solves y ~ X theta by column-pivoted Householder QR. When X is rank deficient the result has
/// rank < cols and `unidentified` lists the parameters of the pivots beyond the rank (theta is
/// then not meaningful); the caller turns that into a NumericalError with its own wording.
struct LinearFitOutcome {
  LinearFit fit;
  std::vector<std::string> unidentified;
};
LinearFitOutcome SolveLinearFit(const Eigen::MatrixXd& X, const Eigen::VectorXd& y,
                                const std::vector<std::string>& names);

/// Column scaling keeps the rank decision and the condition number independent of units:
/// X D with D = diag(1 / |X_j|). Used for the rank test only.
double RelativeRankThreshold();

}  // namespace sysid::internal

#endif  // SYSID_SRC_IDENTIFY_LINEAR_FIT_HPP_
