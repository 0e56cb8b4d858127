// The Bouc–Wen fit's options and its parameter vector: which parameters are free, their scales,
// bounds and starting values.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <unsupported/Eigen/FFT>

#include "core/option_rule.hpp"
#include "hysteresis/bouc_wen_fit_problem.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"

namespace sysid {

void BoucWenFitOptions::Validate() const {
  simulation.Validate();
  if (mechanical_initial_given) mechanical_initial.Validate();
  if (piezo_initial_given) piezo_initial.Validate();
  auto rule = [](const char* field, double value, const char* what) {
    internal::FailOption("BoucWenFitOptions", field, value, what);
  };
  if (fit_beta && !fit_nu)
    rule("fit_beta", 1,
         "fit_beta needs fit_nu (with nu fixed, beta only appears in beta*gamma "
         "and beta*delta)");
  if (starts < 1 || starts > 64) rule("starts", starts, "1 <= starts <= 64");
  if (!(start_spread >= 0 && start_spread <= 3))
    rule("start_spread", start_spread, "0 <= start_spread <= 3");
  if (start_iterations < 1 || start_iterations > 10000)
    rule("start_iterations", start_iterations, "1 <= start_iterations <= 10000");
  if (!(start_rtol >= simulation.rtol && start_rtol <= 1e-2))
    rule("start_rtol", start_rtol, "simulation.rtol <= start_rtol <= 1e-2");
  if (max_iterations < 1 || max_iterations > 10000)
    rule("max_iterations", max_iterations, "1 <= max_iterations <= 10000");
  if (threads < 0) rule("threads", threads, "threads >= 0");
  if (!(fixed_step_tolerance > 0 && fixed_step_tolerance <= 0.1))
    rule("fixed_step_tolerance", fixed_step_tolerance, "0 < fixed_step_tolerance <= 0.1");
  if (!(max_time_s >= 0) || !std::isfinite(max_time_s))
    rule("max_time_s", max_time_s, "max_time_s >= 0 and finite (0: no bound)");
}

namespace internal::bouc_wen_fit {

MechanicalBoucWenParameters MechanicalParameters(const Eigen::VectorXd& p) {
  MechanicalBoucWenParameters m;
  m.m_kg = p[0];
  m.c_n_s_per_m = p[1];
  m.k_n_per_m = p[2];
  m.alpha_n_per_m = p[3];
  m.beta_per_m = p[4];
  m.gamma = p[5];
  m.delta = p[6];
  m.nu = p[7];
  return m;
}

PiezoBoucWenParameters PiezoParameters(const Eigen::VectorXd& p) {
  PiezoBoucWenParameters z;
  z.d_m_per_v = p[0];
  z.alpha = p[1];
  z.beta_per_v = p[2];
  z.gamma_per_v = p[3];
  z.offset_m = p[4];
  return z;
}

std::unique_ptr<HysteresisModel> Layout::Model(const Eigen::VectorXd& p,
                                               std::vector<double> errors) const {
  if (form == BoucWenForm::kMechanical)
    return std::make_unique<MechanicalBoucWen>(MechanicalParameters(p), sim, std::move(errors));
  return std::make_unique<PiezoBoucWen>(PiezoParameters(p), sim, std::move(errors));
}

namespace {

// The best linear approximation m s^2 + c s + K of U / Y by least squares over the lines where
// u has power (the excited lines), as the mechanical form's starting point.
void LinearStart(const std::vector<Series>& data, double* m, double* c, double* k) {
  Eigen::MatrixXd A(0, 3);
  Eigen::VectorXd b(0);
  std::vector<Eigen::RowVector3d> rows;
  std::vector<double> rhs;
  for (const auto& s : data) {
    const Eigen::Index n = s.u.size();
    if (n < 8) continue;
    Eigen::FFT<double> fft;
    std::vector<std::complex<double>> ui(static_cast<size_t>(n)), xi(static_cast<size_t>(n)), U, X;
    for (Eigen::Index i = 0; i < n; ++i) {
      ui[static_cast<size_t>(i)] = s.u[i];
      xi[static_cast<size_t>(i)] = s.x[i];
    }
    fft.fwd(U, ui);
    fft.fwd(X, xi);
    double umax = 0;
    for (Eigen::Index j = 1; j < n / 2; ++j)
      umax = std::max(umax, std::abs(U[static_cast<size_t>(j)]));
    for (Eigen::Index j = 1; j < n / 2; ++j) {
      const auto Uj = U[static_cast<size_t>(j)], Xj = X[static_cast<size_t>(j)];
      if (std::abs(Uj) < 0.1 * umax) continue;  // not an excited line
      const double w = 2 * M_PI * static_cast<double>(j) / (static_cast<double>(n) * s.dt_s);
      // U = (-m w^2 + i c w + K) X, weighted by 1/|X| so each line counts alike.
      const double wt = 1 / std::max(std::abs(Xj), 1e-300);
      const std::complex<double> cm = -w * w * Xj * wt, cc = std::complex<double>(0, w) * Xj * wt,
                                 ck = Xj * wt, cu = Uj * wt;
      rows.emplace_back(cm.real(), cc.real(), ck.real());
      rhs.push_back(cu.real());
      rows.emplace_back(cm.imag(), cc.imag(), ck.imag());
      rhs.push_back(cu.imag());
    }
  }
  A.resize(static_cast<Eigen::Index>(rows.size()), 3);
  b.resize(static_cast<Eigen::Index>(rhs.size()));
  for (size_t i = 0; i < rows.size(); ++i) {
    A.row(static_cast<Eigen::Index>(i)) = rows[i];
    b[static_cast<Eigen::Index>(i)] = rhs[i];
  }
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  if (A.rows() >= 3) p = A.colPivHouseholderQr().solve(b);
  *m = p[0] > 0 && std::isfinite(p[0]) ? p[0] : 1.0;
  *c = p[1] > 0 && std::isfinite(p[1]) ? p[1] : 0.0;
  *k = p[2] > 0 && std::isfinite(p[2]) ? p[2] : 1.0;
}

}  // namespace

Layout MakeLayout(BoucWenForm form, const std::vector<Series>& data, const BoucWenFitOptions& o) {
  Layout l;
  l.form = form;
  l.sim = o.simulation;
  const double inf = std::numeric_limits<double>::infinity();
  double xrms = 0, urms = 0;
  Eigen::Index count = 0;
  for (const auto& s : data) {
    xrms += (s.x.array() - s.x.mean()).square().sum();
    urms += (s.u.array() - s.u.mean()).square().sum();
    count += s.x.size();
  }
  xrms = std::sqrt(xrms / static_cast<double>(count));
  urms = std::sqrt(urms / static_cast<double>(count));
  auto add = [&](int index, double typical, double lower, double upper) {
    const double s = std::max(std::abs(l.all[index]), typical);
    l.free.push_back(index);
    l.scale.push_back(s);
    l.lower.push_back(lower / s);
    l.upper.push_back(upper / s);
  };
  if (form == BoucWenForm::kMechanical) {
    MechanicalBoucWenParameters p = o.mechanical_initial;
    if (!o.mechanical_initial_given) {
      // From the best linear approximation: K = k + (the hysteresis' stiffness), split in two;
      // beta from the amplitude (beta |z| ~ 1 at the typical force), the loop shape neutral.
      double m = 1, c = 0, K = 1;
      LinearStart(data, &m, &c, &K);
      p.m_kg = m;
      p.c_n_s_per_m = 0.1 * c;
      p.k_n_per_m = 0.5 * K;
      p.alpha_n_per_m = 0.5 * K;
      p.beta_per_m = 1 / std::max(xrms, 1e-300);
      p.gamma = 0.5 * K * xrms / std::max(urms, 1e-300);
      p.delta = -0.5 * K * xrms / std::max(urms, 1e-300);
      p.nu = 1;
    }
    l.all.resize(8);
    l.all << p.m_kg, p.c_n_s_per_m, p.k_n_per_m, p.alpha_n_per_m, p.beta_per_m, p.gamma, p.delta,
        p.nu;
    const double K = p.k_n_per_m + p.alpha_n_per_m;
    add(0, 1e-9, 1e-9 * std::max(p.m_kg, 1e-9), inf);  // m > 0
    add(1, 1e-3 * std::sqrt(K * p.m_kg), 0, inf);      // c >= 0
    add(2, 1e-3 * K, 0, inf);                          // k >= 0
    add(3, 1e-3 * K, 1e-9 * K, inf);                   // alpha > 0
    if (o.fit_beta) add(4, 1e-9, 1e-9 * p.beta_per_m, inf);
    add(5, 0.1, -inf, inf);
    add(6, 0.1, -inf, inf);
    if (o.fit_nu) add(7, 1, 1, 10);
  } else {
    PiezoBoucWenParameters p = o.piezo_initial;
    if (!o.piezo_initial_given) {
      // The straight line x = d u + offset by least squares; a mild loop to start from.
      double mu = 0, mx = 0, sux = 0, suu = 0;
      for (const auto& s : data) {
        mu += s.u.sum();
        mx += s.x.sum();
      }
      mu /= static_cast<double>(count);
      mx /= static_cast<double>(count);
      for (const auto& s : data) {
        sux += ((s.u.array() - mu) * (s.x.array() - mx)).sum();
        suu += (s.u.array() - mu).square().sum();
      }
      p.d_m_per_v = suu > 0 && sux > 0 ? sux / suu : 1e-6;
      p.offset_m = mx - p.d_m_per_v * mu;
      p.alpha = 0.2;
      p.beta_per_v = 1 / std::max(urms, 1e-300);
      p.gamma_per_v = 0.2 / std::max(urms, 1e-300);
    }
    l.all.resize(5);
    l.all << p.d_m_per_v, p.alpha, p.beta_per_v, p.gamma_per_v, p.offset_m;
    add(0, 1e-300, 1e-9 * p.d_m_per_v, inf);
    add(1, 0.01, -inf, inf);
    add(2, 1e-3 / std::max(urms, 1e-300), -inf, inf);
    add(3, 1e-3 / std::max(urms, 1e-300), -inf, inf);
    add(4, std::max(xrms, 1e-300), -inf, inf);
  }
  return l;
}

SampledRecordings Inputs(const std::vector<Series>& data) {
  internal::SampledRecordings r;
  for (const auto& s : data) {
    r.u.push_back(&s.u);
    r.dt_s.push_back(s.dt_s);
  }
  return r;
}

void ShareCvodeInputs(const std::vector<Recording>& recordings, const Layout& layout,
                      std::vector<Series>* data) {
  if (!layout.SimulatedByCvode()) return;
  for (size_t i = 0; i < data->size(); ++i) {
    Series& s = (*data)[i];
    try {
      s.input = std::make_shared<const SampledInput>(s.u, s.dt_s, layout.sim.input);
    } catch (const InputError& e) {
      throw InputError(recordings[i].source + ": " + e.what());
    }
  }
}

}  // namespace internal::bouc_wen_fit

}  // namespace sysid
