// The parameter layout and regression terms of the Prandtl–Ishlinskii forms.
#include "pi_terms.hpp"

#include <cmath>

namespace sysid::internal {

std::string PiLayout::name(int j) const {
  if (j < m) return form == PiForm::kPolynomial ? "a" + std::to_string(j + 1) : "p0";
  if (rate() && j == q0()) return "q0";
  if (j == offset()) return "c";
  const int first_w = w(0);
  if (j < first_w + n) return "w" + std::to_string(j - first_w + 1);
  return "q" + std::to_string(j - q(0) + 1);
}

std::string PiLayout::unit(int j) const {
  if (j < m) return j == 0 ? "m/V" : "m/V^" + std::to_string(j + 1);
  if (j == offset()) return "m";
  if (rate() && (j == q0() || j >= q(0))) return "m*s/V^2";
  return "m/V";
}

PiLayout LayoutOf(const PiParameters& p) {
  PiLayout l;
  l.form = p.form;
  l.n = static_cast<int>(p.thresholds.size());
  l.m = static_cast<int>(p.polynomial.size());
  return l;
}

Eigen::VectorXd Pack(const PiParameters& p) {
  const PiLayout l = LayoutOf(p);
  Eigen::VectorXd theta(l.size());
  for (int j = 0; j < l.m; ++j) theta[j] = p.polynomial[static_cast<size_t>(j)];
  if (l.rate()) theta[l.q0()] = p.rate_weights[0];
  for (int i = 0; i < l.n; ++i) {
    theta[l.w(i)] = p.weights[static_cast<size_t>(i)];
    if (l.rate()) theta[l.q(i)] = p.rate_weights[static_cast<size_t>(i) + 1];
  }
  theta[l.offset()] = p.offset_m;
  return theta;
}

void Unpack(const Eigen::VectorXd& theta, PiParameters* p) {
  const PiLayout l = LayoutOf(*p);
  for (int j = 0; j < l.m; ++j) p->polynomial[static_cast<size_t>(j)] = theta[j];
  p->weights.assign(static_cast<size_t>(l.n), 0.0);
  if (l.rate()) {
    p->rate_weights.assign(static_cast<size_t>(l.n) + 1, 0.0);
    p->rate_weights[0] = theta[l.q0()];
  }
  for (int i = 0; i < l.n; ++i) {
    p->weights[static_cast<size_t>(i)] = theta[l.w(i)];
    if (l.rate()) p->rate_weights[static_cast<size_t>(i) + 1] = theta[l.q(i)];
  }
  p->offset_m = theta[l.offset()];
}

std::vector<double> InitialState(const PiParameters& p) {
  if (!p.initial_state.empty()) return p.initial_state;
  return std::vector<double>(p.thresholds.size(), p.initial_input_v);
}

void FillTerms(const PiParameters& p, const Eigen::VectorXd& u, double dt_s, Eigen::Index row0,
               Eigen::MatrixXd* terms) {
  const PiLayout l = LayoutOf(p);
  std::vector<double> z = InitialState(p);
  Eigen::MatrixXd& T = *terms;
  for (Eigen::Index k = 0; k < u.size(); ++k) {
    const Eigen::Index row = row0 + k;
    const double uk = u[k];
    // The input's rate over the previous step (docs/hysteresis.md): 0 for the first two samples.
    const double rho = k >= 2 ? std::abs(u[k - 1] - u[k - 2]) / dt_s : 0.0;
    double power = uk;
    for (int j = 0; j < l.m; ++j, power *= uk) T(row, j) = power;
    if (l.rate()) T(row, l.q0()) = rho * uk;
    for (int i = 0; i < l.n; ++i) {
      const size_t s = static_cast<size_t>(i);
      z[s] = PlayStep(uk, p.thresholds[s], z[s]);
      T(row, l.w(i)) = z[s];
      if (l.rate()) T(row, l.q(i)) = rho * z[s];
    }
    T(row, l.offset()) = 1.0;
  }
}

}  // namespace sysid::internal
