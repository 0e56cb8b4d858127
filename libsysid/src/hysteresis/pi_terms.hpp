// Private: the regression terms of the Prandtl–Ishlinskii forms, shared by the model (simulate,
// names of the parameters) and the fit (the regression matrix).
#ifndef SYSID_SRC_HYSTERESIS_PI_TERMS_HPP_
#define SYSID_SRC_HYSTERESIS_PI_TERMS_HPP_

#include <Eigen/Core>
#include <string>
#include <vector>

#include "sysid/hysteresis.hpp"

namespace sysid::internal {

/// The parameter layout of a form with n operators and an input polynomial of degree m:
///   [a_1..a_m | q_0 (rdpi) | w_1..w_n | q_1..q_n (rdpi) | c]
struct PiLayout {
  PiForm form = PiForm::kClassical;
  int n = 0;  ///< operators
  int m = 1;  ///< polynomial degree (1 for pi and rdpi)
  bool rate() const { return form == PiForm::kRateDependent; }
  int size() const { return m + (rate() ? 1 : 0) + n + (rate() ? n : 0) + 1; }
  int q0() const { return m; }                           ///< rdpi only
  int w(int i) const { return m + (rate() ? 1 : 0) + i; }  ///< i = 0..n-1
  int q(int i) const { return m + 1 + n + i; }           ///< rdpi only
  int offset() const { return size() - 1; }
  /// Whether parameter j is bounded below by 0: a_1 (p0), the q's and w's; gpi's a_3, a_5
  /// and c are free (the fitted polynomial's monotonicity is checked afterwards).
  bool bounded(int j) const { return j < m ? j == 0 : j < offset(); }
  /// Whether the fit holds parameter j at 0: gpi's even powers (Gu et al.'s odd polynomial).
  bool held(int j) const { return form == PiForm::kPolynomial && j < m && j % 2 == 1; }
  std::string name(int j) const;
  std::string unit(int j) const;
};

PiLayout LayoutOf(const PiParameters& p);
/// The parameters packed in layout order.
Eigen::VectorXd Pack(const PiParameters& p);
/// Writes theta (layout order) into p's coefficient fields.
void Unpack(const Eigen::VectorXd& theta, PiParameters* p);

/// The initial play states z_i(-1) [V] of p.
std::vector<double> InitialState(const PiParameters& p);

/// Fills rows [row0, row0 + u.size()) of `terms` (layout columns) for the input u with step
/// dt_s, from p's initial state (p's thresholds; coefficients are not used).
void FillTerms(const PiParameters& p, const Eigen::VectorXd& u, double dt_s, Eigen::Index row0,
               Eigen::MatrixXd* terms);

}  // namespace sysid::internal

#endif  // SYSID_SRC_HYSTERESIS_PI_TERMS_HPP_
