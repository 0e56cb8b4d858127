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

/// One sample of the forward model: moves the play states z (one per threshold) with the input
/// u_k [V] and returns y_k [m]; rho [V/s] is the previous step's input rate (rdpi; 0 otherwise).
/// Simulate and the inverse's stepper share it, so their sums run in one order.
inline double PiOutputStep(const PiParameters& p, const PiLayout& l, double uk, double rho,
                           double* z) {
  const double q0 = l.rate() ? p.rate_weights[0] : 0.0;
  double sum = p.offset_m + q0 * rho * uk, power = uk;
  for (int j = 0; j < l.m; ++j, power *= uk) sum += p.polynomial[static_cast<size_t>(j)] * power;
  for (int i = 0; i < l.n; ++i) {
    const size_t s = static_cast<size_t>(i);
    z[s] = PlayStep(uk, p.thresholds[s], z[s]);
    sum += (p.weights[s] + (l.rate() ? p.rate_weights[s + 1] * rho : 0.0)) * z[s];
  }
  return sum;
}

/// PiOutputStep's y_k for a trial input u_k, leaving the states z as they are.
inline double PiTrialOutput(const PiParameters& p, const PiLayout& l, double uk, double rho,
                            const double* z) {
  const double q0 = l.rate() ? p.rate_weights[0] : 0.0;
  double sum = p.offset_m + q0 * rho * uk, power = uk;
  for (int j = 0; j < l.m; ++j, power *= uk) sum += p.polynomial[static_cast<size_t>(j)] * power;
  for (int i = 0; i < l.n; ++i) {
    const size_t s = static_cast<size_t>(i);
    sum += (p.weights[s] + (l.rate() ? p.rate_weights[s + 1] * rho : 0.0)) *
           PlayStep(uk, p.thresholds[s], z[s]);
  }
  return sum;
}

/// Fills rows [row0, row0 + u.size()) of `terms` (layout columns) for the input u with step
/// dt_s, from p's initial state (p's thresholds; coefficients are not used).
void FillTerms(const PiParameters& p, const Eigen::VectorXd& u, double dt_s, Eigen::Index row0,
               Eigen::MatrixXd* terms);

}  // namespace sysid::internal

#endif  // SYSID_SRC_HYSTERESIS_PI_TERMS_HPP_
