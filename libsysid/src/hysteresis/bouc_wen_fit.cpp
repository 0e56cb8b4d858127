// Output-error fit of the Bouc–Wen models (Ceres; the Jacobian by the benchmark chain's forward
// sensitivities, or by central differences through the simulator, its columns simulated in
// parallel).
#include <ceres/ceres.h>
#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <unsupported/Eigen/FFT>

#include "core/option_rule.hpp"
#include "core/parallel_for.hpp"
#include "core/portable_random.hpp"
#include "hysteresis/bouc_wen_internal.hpp"
#include "sysid/error.hpp"
#include "sysid/hysteresis_bouc_wen.hpp"
#include "sysid/io.hpp"
#include "sysid/motion.hpp"

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
  if (max_iterations < 1 || max_iterations > 10000)
    rule("max_iterations", max_iterations, "1 <= max_iterations <= 10000");
  if (threads < 0) rule("threads", threads, "threads >= 0");
  if (!(fixed_step_tolerance > 0 && fixed_step_tolerance <= 0.1))
    rule("fixed_step_tolerance", fixed_step_tolerance, "0 < fixed_step_tolerance <= 0.1");
  if (!(max_time_s >= 0) || !std::isfinite(max_time_s))
    rule("max_time_s", max_time_s, "max_time_s >= 0 and finite (0: no bound)");
}

namespace {

// The mechanical form's parameters from the fit's full vector (m, c, k, alpha, beta, gamma,
// delta, nu: the order of the layout's names).
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

// The piezo form's parameters from the fit's vector (d, alpha, beta, gamma, offset).
PiezoBoucWenParameters PiezoParameters(const Eigen::VectorXd& p) {
  PiezoBoucWenParameters z;
  z.d_m_per_v = p[0];
  z.alpha = p[1];
  z.beta_per_v = p[2];
  z.gamma_per_v = p[3];
  z.offset_m = p[4];
  return z;
}

struct Series {
  Eigen::VectorXd u, x;
  double dt_s;
  // The benchmark chain's upsampled input (internal::ChainInput) or the fixed step's
  // (internal::FixedStepInput), when the fit simulates by one of them: it does not depend on the
  // parameters, and recomputing it (for the chain an FFT of 20 n points) was a fifth of every
  // simulation. Empty otherwise.
  Eigen::VectorXd fine_u;
};

// The parameters as one vector: mechanical m, c, k, alpha, beta, gamma, delta, nu; piezo d,
// alpha, beta, gamma, offset.
struct Layout {
  BoucWenForm form;
  Eigen::VectorXd all;        // every parameter, fixed ones at their value
  std::vector<int> free;      // indices into all
  std::vector<double> scale;  // free parameter i = scale[i] * x[i]
  std::vector<double> lower;  // bounds on x (scaled), -inf when none
  std::vector<double> upper;
  BoucWenSimulationOptions sim;

  Eigen::VectorXd Full(const double* x) const {
    Eigen::VectorXd p = all;
    for (size_t i = 0; i < free.size(); ++i) p[free[i]] = scale[i] * x[i];
    return p;
  }
  std::unique_ptr<HysteresisModel> Model(const Eigen::VectorXd& p,
                                         std::vector<double> errors = {}) const {
    if (form == BoucWenForm::kMechanical) {
      return std::make_unique<MechanicalBoucWen>(MechanicalParameters(p), sim, std::move(errors));
    }
    return std::make_unique<PiezoBoucWen>(PiezoParameters(p), sim, std::move(errors));
  }
};

// The model's y at a recording's samples, from its fine input when the fit keeps one.
Eigen::VectorXd SimulateSeries(const Layout& l, const HysteresisModel& model, const Series& s) {
  if (s.fine_u.size() == 0) return model.Simulate(s.u, s.dt_s);
  const auto& p = static_cast<const MechanicalBoucWen&>(model).values();
  if (l.sim.integrator == BoucWenIntegrator::kBenchmarkChain)
    return internal::ChainOutput(p, s.fine_u, s.x.size(), s.dt_s, l.sim.upsampling);
  return internal::FixedStepOutput(p, s.fine_u, s.dt_s, l.sim.upsampling);
}

// y_model - x over every recording, stacked; false when the simulation fails.
bool Residuals(const Layout& l, const std::vector<Series>& data, const double* x, double* r) {
  try {
    const auto model = l.Model(l.Full(x));
    Eigen::Index at = 0;
    for (const auto& s : data) {
      const Eigen::VectorXd y = SimulateSeries(l, *model, s);
      Eigen::Map<Eigen::VectorXd>(r + at, s.x.size()) = y - s.x;
      at += s.x.size();
    }
    for (Eigen::Index i = 0; i < at; ++i)
      if (!std::isfinite(r[i])) return false;
    return true;
  } catch (const Error&) {
    return false;  // an invalid trial model or a failed simulation: Ceres shrinks the step
  }
}

// Ceres evaluates one point up to three times: bounded problems take the trust-region step by
// a projected line search, which asks for the gradient (the Jacobian) at the full step, then the
// candidate's cost, then — the step accepted — residuals and Jacobian there again. The last
// evaluation is kept and answered from: 13 simulations per iteration instead of 27, with
// identical numbers (a simulation is a deterministic function of the parameters). The cache can
// outlive its cost function: the final fit starts with the best start's, whose last evaluation
// is usually its last point.
// What the fit computed: plain simulations, and passes of the chain with its sensitivities.
struct Work {
  long simulations = 0;
  long sensitivity_passes = 0;
};

struct EvaluationCache {
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  std::vector<double> x;
  Eigen::VectorXd r;
  RowMajor j;
  bool ok = false;
  bool has_jacobian = false;
};

class OutputError : public ceres::CostFunction {
 public:
  OutputError(const Layout* l, const std::vector<Series>* data, Eigen::Index n, int threads,
              BoucWenJacobian jacobian, Work* work, std::shared_ptr<EvaluationCache> cache)
      : l_(l), data_(data), threads_(threads), work_(work), c_(std::move(cache)) {
    // The exact Jacobian where the simulation is a discrete recursion: the mechanical form's
    // chain and fixed step (a fine input kept), the piezo form's closed-form step.
    sensitivities_ = jacobian == BoucWenJacobian::kSensitivities && !data->empty();
    if (l->form == BoucWenForm::kPiezo)
      sensitivities_ = sensitivities_ && l->sim.input != InputInterpolation::kBandLimited;
    else
      for (const auto& s : *data) sensitivities_ = sensitivities_ && s.fine_u.size() > 0;
    mutable_parameter_block_sizes()->push_back(static_cast<int>(l->free.size()));
    set_num_residuals(static_cast<int>(n));
  }
  bool Evaluate(double const* const* x, double* residuals, double** jacobians) const override {
    const int np = static_cast<int>(l_->free.size());
    const Eigen::Index n = num_residuals();
    const bool want_jacobian = jacobians != nullptr && jacobians[0] != nullptr;
    const bool same =
        c_->x.size() == static_cast<size_t>(np) && std::equal(c_->x.begin(), c_->x.end(), x[0]);
    if (same && (!c_->ok || !want_jacobian || c_->has_jacobian)) {
      if (!c_->ok) return false;
      Eigen::Map<Eigen::VectorXd>(residuals, n) = c_->r;
      if (want_jacobian) Jacobian(jacobians[0], n, np) = c_->j;
      return true;
    }
    c_->x.assign(x[0], x[0] + np);
    c_->has_jacobian = false;
    if (!want_jacobian) {
      ++work_->simulations;
      c_->ok = Residuals(*l_, *data_, x[0], residuals);
      c_->r = Eigen::Map<const Eigen::VectorXd>(residuals, n);
      return c_->ok;
    }
    if (sensitivities_) {
      ++work_->sensitivity_passes;
      c_->ok = ResidualsAndSensitivities(x[0], residuals, jacobians[0]);
      if (!c_->ok) return false;
      c_->r = Eigen::Map<const Eigen::VectorXd>(residuals, n);
      c_->j = Jacobian(jacobians[0], n, np);
      c_->has_jacobian = true;
      return true;
    }
    // Residuals (unless kept) and 2 np perturbed simulations, in parallel.
    std::vector<Eigen::VectorXd> r(static_cast<size_t>(2 * np + 1), Eigen::VectorXd(n));
    std::vector<char> ok(r.size(), 0);
    if (same) {
      r[0] = c_->r;
      ok[0] = 1;
    }
    std::vector<double> step(static_cast<size_t>(np));
    for (int i = 0; i < np; ++i)
      // The simulations are exact to rounding (Newmark, closed form) or to rtol (CVODE): a step
      // of 1e-6 of the parameter's scale keeps the difference error near 1e-10 relative.
      step[static_cast<size_t>(i)] = 1e-6 * std::max(std::abs(x[0][i]), 1e-3);
    const long first = same ? 1 : 0;
    internal::ParallelFor(static_cast<long>(r.size()) - first, threads_, [&](long job) {
      const long j = job + first;
      std::vector<double> xj(x[0], x[0] + np);
      if (j > 0) {
        const int i = static_cast<int>((j - 1) / 2);
        xj[static_cast<size_t>(i)] += (j % 2 == 1 ? 1 : -1) * step[static_cast<size_t>(i)];
      }
      ok[static_cast<size_t>(j)] =
          Residuals(*l_, *data_, xj.data(), r[static_cast<size_t>(j)].data());
    });
    work_->simulations += static_cast<long>(r.size()) - first;
    c_->ok = ok[0] != 0;
    if (!c_->ok) return false;
    c_->r = r[0];
    Eigen::Map<Eigen::VectorXd>(residuals, n) = r[0];
    auto J = Jacobian(jacobians[0], n, np);
    for (int i = 0; i < np; ++i) {
      const auto& rp = r[static_cast<size_t>(2 * i + 1)];
      const auto& rm = r[static_cast<size_t>(2 * i + 2)];
      const double hi = step[static_cast<size_t>(i)];
      const bool okp = ok[static_cast<size_t>(2 * i + 1)], okm = ok[static_cast<size_t>(2 * i + 2)];
      if (okp && okm)
        J.col(i) = (rp - rm) / (2 * hi);
      else if (okp)
        J.col(i) = (rp - r[0]) / hi;  // at a bound: one-sided
      else if (okm)
        J.col(i) = (r[0] - rm) / hi;
      else
        return false;
    }
    c_->j = J;
    c_->has_jacobian = true;
    return true;
  }

 private:
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  static Eigen::Map<RowMajor> Jacobian(double* j, Eigen::Index n, int np) {
    return Eigen::Map<RowMajor>(j, n, np);
  }

  // The residuals and their exact Jacobian (ChainOutputSensitivity, FixedStepOutputSensitivity,
  // PiezoOutputSensitivity), the recordings in parallel; false when the parameters are invalid or
  // a simulation fails.
  bool ResidualsAndSensitivities(const double* x, double* residuals, double* jacobian) const {
    const int np = static_cast<int>(l_->free.size());
    const Eigen::VectorXd p = l_->Full(x);
    const MechanicalBoucWenParameters m = l_->form == BoucWenForm::kMechanical
                                              ? MechanicalParameters(p)
                                              : MechanicalBoucWenParameters{};
    const PiezoBoucWenParameters z =
        l_->form == BoucWenForm::kPiezo ? PiezoParameters(p) : PiezoBoucWenParameters{};
    try {
      m.Validate();
      z.Validate();
    } catch (const Error&) {
      return false;
    }
    const bool with_nu = std::find(l_->free.begin(), l_->free.end(), 7) != l_->free.end();
    auto J = Jacobian(jacobian, num_residuals(), np);
    std::vector<Eigen::Index> first(data_->size() + 1, 0);
    for (size_t k = 0; k < data_->size(); ++k) first[k + 1] = first[k] + (*data_)[k].x.size();
    std::vector<char> ok(data_->size(), 0);
    internal::ParallelFor(static_cast<long>(data_->size()), threads_, [&](long job) {
      const Series& s = (*data_)[static_cast<size_t>(job)];
      const Eigen::Index at = first[static_cast<size_t>(job)], len = s.x.size();
      Eigen::VectorXd y;
      Eigen::MatrixXd dy;
      try {
        if (l_->form == BoucWenForm::kPiezo)
          internal::PiezoOutputSensitivity(z, s.u, &y, &dy);
        else if (l_->sim.integrator == BoucWenIntegrator::kBenchmarkChain)
          internal::ChainOutputSensitivity(m, s.fine_u, len, s.dt_s, l_->sim.upsampling, with_nu,
                                           &y, &dy);
        else
          internal::FixedStepOutputSensitivity(m, s.fine_u, s.dt_s, l_->sim.upsampling, with_nu, &y,
                                               &dy);
      } catch (const Error&) {
        return;
      }
      Eigen::Map<Eigen::VectorXd>(residuals + at, len) = y - s.x;
      for (int i = 0; i < np; ++i)
        J.col(i).segment(at, len) =
            dy.col(l_->free[static_cast<size_t>(i)]) * l_->scale[static_cast<size_t>(i)];
      ok[static_cast<size_t>(job)] = y.allFinite() && dy.allFinite();
    });
    return std::all_of(ok.begin(), ok.end(), [](char c) { return c != 0; });
  }

  const Layout* l_;
  const std::vector<Series>* data_;
  bool sensitivities_ = false;
  int threads_;
  Work* work_;
  // The last point evaluated and what was computed there (Ceres evaluates serially).
  std::shared_ptr<EvaluationCache> c_;
};

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

struct Solved {
  std::vector<double> x;
  ceres::Solver::Summary summary;
  bool timed_out = false;  // stopped by BoucWenFitOptions::max_time_s
  // The problem's cost function while the problem is kept (Solve's `keep`): its last
  // evaluation answers the standard errors' Jacobian at the optimum when it was there.
  const OutputError* cost = nullptr;
  std::shared_ptr<EvaluationCache> cache;  // the cost function's, kept after the problem
};

// The fit's clock and its bound, shared by the starts and the final fit.
struct FitClock {
  std::chrono::steady_clock::time_point start;
  double max_time_s = 0;  // 0: none
  double Elapsed() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  bool Bounded() const { return max_time_s > 0; }
  double Remaining() const { return std::max(0.0, max_time_s - Elapsed()); }
};

class ProgressCallback final : public ceres::IterationCallback {
 public:
  ProgressCallback(const BoucWenFitOptions& o, const FitClock& clock, int start, Eigen::Index n)
      : o_(o), clock_(clock), start_(start), n_(n) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& s) override {
    BoucWenFitProgress p;
    p.start = start_;
    p.starts = o_.starts;
    p.iteration = s.iteration;
    p.rms_m = std::sqrt(2 * s.cost / static_cast<double>(n_));  // Ceres' cost is sse / 2
    p.elapsed_s = clock_.Elapsed();
    o_.on_iteration(p);
    return ceres::SOLVER_CONTINUE;
  }

 private:
  const BoucWenFitOptions& o_;
  const FitClock& clock_;
  int start_;
  Eigen::Index n_;
};

Solved Solve(const Layout& l, const std::vector<Series>& data, Eigen::Index n,
             std::vector<double> x, int iterations, const BoucWenFitOptions& o,
             const FitClock& clock, int start, Work* work, std::shared_ptr<EvaluationCache> cache,
             ceres::Problem** keep = nullptr) {
  Solved s;
  s.x = std::move(x);
  s.cache = cache;
  auto* problem = new ceres::Problem;
  auto* cost = new OutputError(&l, &data, n, o.threads, o.jacobian, work, cache);
  problem->AddResidualBlock(cost, nullptr, s.x.data());
  for (size_t i = 0; i < l.free.size(); ++i) {
    if (std::isfinite(l.lower[i]))
      problem->SetParameterLowerBound(s.x.data(), static_cast<int>(i), l.lower[i]);
    if (std::isfinite(l.upper[i]))
      problem->SetParameterUpperBound(s.x.data(), static_cast<int>(i), l.upper[i]);
  }
  ceres::Solver::Options so;
  so.max_num_iterations = iterations;
  so.linear_solver_type = ceres::DENSE_QR;
  so.function_tolerance = 1e-12;
  so.parameter_tolerance = 1e-12;
  so.gradient_tolerance = 1e-14;
  so.logging_type = ceres::SILENT;
  if (clock.Bounded()) so.max_solver_time_in_seconds = clock.Remaining();
  ProgressCallback progress(o, clock, start, n);
  if (o.on_iteration) so.callbacks.push_back(&progress);
  ceres::Solve(so, problem, &s.summary);
  // Ceres says NO_CONVERGENCE for both of its limits: short of the iteration limit, the clock.
  s.timed_out = clock.Bounded() && s.summary.termination_type == ceres::NO_CONVERGENCE &&
                static_cast<int>(s.summary.iterations.size()) - 1 < iterations &&
                clock.Remaining() == 0;
  if (keep != nullptr) {
    *keep = problem;
    s.cost = cost;
  } else {
    delete problem;
  }
  return s;
}

// The recordings' inputs and sample times, as the fixed step's helpers take them.
internal::SampledRecordings Inputs(const std::vector<Series>& data) {
  internal::SampledRecordings r;
  for (const auto& s : data) {
    r.u.push_back(&s.u);
    r.dt_s.push_back(s.dt_s);
  }
  return r;
}

// The final model's fixed step against CVODE (rtol 1e-9, the same input): the RMS difference
// [m] over every sample. Where CVODE refuses the input (its band-limited work bound), step
// doubling at m instead; *how says which.
double FixedStepCheck(const MechanicalBoucWenParameters& p, const std::vector<Series>& data,
                      const BoucWenSimulationOptions& sim, std::string* how) {
  BoucWenSimulationOptions cv = sim;
  cv.integrator = BoucWenIntegrator::kCvode;
  cv.rtol = 1e-9;
  const MechanicalBoucWen reference(p, cv);
  double sum = 0, count = 0;
  try {
    for (const auto& s : data) {
      const Eigen::VectorXd y = internal::FixedStepOutput(p, s.fine_u, s.dt_s, sim.upsampling);
      sum += (y - reference.Simulate(s.u, s.dt_s)).squaredNorm();
      count += static_cast<double>(s.u.size());
    }
    *how = "against CVODE rtol 1e-9";
    return std::sqrt(sum / count);
  } catch (const InputError& e) {
    *how = fmt::format("by step doubling (CVODE refused the input: {})", e.what());
  }
  const internal::SampledRecordings in = Inputs(data);
  return internal::StepDoublingError(
      internal::FixedStepStacked(p, in, sim.input, sim.upsampling),
      internal::FixedStepStacked(p, in, sim.input, 2 * sim.upsampling));
}

}  // namespace

std::unique_ptr<HysteresisModel> FitBoucWen(BoucWenForm form,
                                            const std::vector<Recording>& recordings,
                                            const BoucWenFitOptions& options,
                                            HysteresisFitSummary* summary) {
  FitClock clock{std::chrono::steady_clock::now(), options.max_time_s};
  options.Validate();
  if (recordings.empty()) throw OptionsError("FitBoucWen: no recordings given", "recordings");
  if (form == BoucWenForm::kPiezo && options.simulation.integrator != BoucWenIntegrator::kCvode)
    internal::FailOption("BoucWenFitOptions", "simulation.integrator",
                         options.simulation.integrator == BoucWenIntegrator::kFixedStep
                             ? "fixed-step"
                             : "benchmark-chain",
                         "the chain and the fixed step are the mechanical form's");
  std::vector<Series> data;
  Eigen::Index n = 0;
  for (const auto& r : recordings) {
    if (r.rows() < 3)
      throw InputError(fmt::format("{}: {} samples: a fit needs at least 3", r.source, r.rows()));
    Series s{r.column("u"), r.column("x"), UniformSampleInterval(r, 1e-3), {}};
    for (Eigen::Index i = 0; i < s.u.size(); ++i)
      if (!std::isfinite(s.u[i]) || !std::isfinite(s.x[i]))
        throw InputError(fmt::format("{}:{}: column '{}': expected a finite number", r.source,
                                     i + 2, std::isfinite(s.u[i]) ? "x" : "u"));
    if (form == BoucWenForm::kMechanical &&
        options.simulation.integrator == BoucWenIntegrator::kBenchmarkChain) {
      try {
        internal::CheckChainWork(s.u.size(), options.simulation.upsampling, 1, "bouc-wen");
      } catch (const InputError& e) {
        throw InputError(r.source + ": " + e.what());
      }
      s.fine_u = internal::ChainInput(s.u, options.simulation.upsampling);
    }
    n += s.u.size();
    data.push_back(std::move(s));
  }
  // A constant input excites no hysteresis (and makes every start's residuals fail, which
  // Ceres writes to stderr): refused with the reason, as the Prandtl-Ishlinskii fit does.
  double u_min = HUGE_VAL, u_max = -HUGE_VAL;
  for (const Series& s : data) {
    u_min = std::min(u_min, s.u.minCoeff());
    u_max = std::max(u_max, s.u.maxCoeff());
  }
  if (!(u_max > u_min))
    throw InputError(
        fmt::format("{}: column 'u' is constant ({} V): nothing to fit a hysteresis to",
                    recordings.front().source, u_min));
  Layout layout = MakeLayout(form, data, options);
  std::string input_note;
  // The chain takes its input band-limited whatever `input` says.
  if (options.choose_input && form == BoucWenForm::kMechanical &&
      layout.sim.integrator != BoucWenIntegrator::kBenchmarkChain) {
    bool band_limited = true;
    double worst_wrap = 0, worst_high = 0;
    for (const auto& s : data) {
      double wrap = 0, high = 0;
      band_limited = internal::PeriodicBandLimited(s.u, &wrap, &high) && band_limited;
      worst_wrap = std::max(worst_wrap, wrap / std::max(s.u.cwiseAbs().maxCoeff(), 1e-300));
      worst_high = std::max(worst_high, high);
    }
    layout.sim.input =
        band_limited ? InputInterpolation::kBandLimited : InputInterpolation::kLinear;
    input_note = fmt::format(
        "; input {} between samples (chosen: {}; largest wrap step {:.3g} of max|u|, power above "
        "a quarter of the sampling rate {:.3g} of the variance, band-limited at most {:g})",
        band_limited ? "band-limited" : "linear",
        band_limited ? "every recording is whole periods of a band-limited signal"
                     : "not every recording is whole periods of a band-limited signal",
        worst_wrap, worst_high, internal::kBandLimitedPower);
  }
  const bool fixed_step = form == BoucWenForm::kMechanical &&
                          options.simulation.integrator == BoucWenIntegrator::kFixedStep;
  const bool exact =
      options.jacobian == BoucWenJacobian::kSensitivities &&
      (form == BoucWenForm::kMechanical ? layout.sim.integrator != BoucWenIntegrator::kCvode
                                        : layout.sim.input != InputInterpolation::kBandLimited);
  const char* jacobian_how = exact ? "forward sensitivities" : "central differences";
  // The fixed step's tolerance [m] and the steps per sample it needs at the start.
  double step_tolerance_m = 0, start_estimate_m = 0;
  auto set_substeps = [&](int m) {
    layout.sim.upsampling = m;
    for (auto& s : data) {
      // The work bound before the allocation (a doubled m was not checked by the choice).
      internal::CheckFixedStepWork(s.u.size(), m, layout.sim.input, "bouc-wen");
      s.fine_u = internal::FixedStepInput(s.u, layout.sim.input, m);
    }
  };
  if (fixed_step) {
    double sum = 0;
    for (const auto& s : data) sum += (s.x.array() - s.x.mean()).square().sum();
    step_tolerance_m = options.fixed_step_tolerance * std::sqrt(sum / static_cast<double>(n));
    set_substeps(internal::ChooseFixedSteps(MechanicalParameters(layout.all), Inputs(data),
                                            layout.sim.input, step_tolerance_m, &start_estimate_m));
  }
  const int np = static_cast<int>(layout.free.size());
  if (n <= np)
    throw InputError(fmt::format("FitBoucWen: {} samples for {} free parameters", n, np));
  Work work;
  // Starting points: the initial values, then perturbed copies; each gets a few iterations and
  // the cheapest continues.
  std::vector<double> best(static_cast<size_t>(np), 1.0);
  auto best_cache = std::make_shared<EvaluationCache>();
  for (int i = 0; i < np; ++i)
    best[static_cast<size_t>(i)] =
        layout.all[layout.free[static_cast<size_t>(i)]] / layout.scale[static_cast<size_t>(i)];
  if (options.starts > 1) {
    internal::PortableRandom random(options.seed);
    double best_cost = std::numeric_limits<double>::infinity();
    const std::vector<double> x0 = best;
    double iterations_so_far = 0;  // Ceres' iterations 0 included: each evaluates a Jacobian
    for (int k = 0; k < options.starts; ++k) {
      // A start begins only with one iteration's time (the mean so far) left: Ceres checks the
      // bound between iterations, so a start begun later overruns it by its first Jacobian.
      if (clock.Bounded() &&
          clock.Remaining() <= (iterations_so_far > 0 ? clock.Elapsed() / iterations_so_far : 0))
        break;  // the final fit says so
      std::vector<double> x = x0;
      if (k > 0)
        for (int i = 0; i < np; ++i) {
          auto& v = x[static_cast<size_t>(i)];
          v *= std::exp(options.start_spread * random.Normal());
          v = std::clamp(v, layout.lower[static_cast<size_t>(i)],
                         layout.upper[static_cast<size_t>(i)]);
        }
      const Solved s = Solve(layout, data, n, x, options.start_iterations, options, clock, k + 1,
                             &work, std::make_shared<EvaluationCache>());
      iterations_so_far += static_cast<double>(s.summary.iterations.size());
      if (s.summary.final_cost < best_cost && std::isfinite(s.summary.final_cost)) {
        best_cost = s.summary.final_cost;
        best = s.x;
        best_cache = s.cache;
      }
    }
  }
  ceres::Problem* problem = nullptr;
  Solved s = Solve(layout, data, n, best, options.max_iterations, options, clock, 0, &work,
                   best_cache, &problem);
  std::unique_ptr<ceres::Problem> owner(problem);
  if (s.summary.termination_type == ceres::FAILURE || !std::isfinite(s.summary.final_cost))
    throw NumericalError("bouc-wen fit failed: " + s.summary.message);
  // The fixed step checked on the final model: past its tolerance, twice the steps and the fit
  // continues from where it is (a fresh evaluation cache: the residuals changed with m).
  std::string fixed_step_note;
  while (fixed_step) {
    std::string how;
    const double error_m =
        FixedStepCheck(MechanicalParameters(layout.Full(s.x.data())), data, layout.sim, &how);
    fixed_step_note = fmt::format(
        "; fixed step: {} steps per sample (step doubling at the start: {:.3g} m RMS), the final "
        "model {}: {:.3g} m RMS, tolerance {:.3g} m ({:g} of rms(x))",
        layout.sim.upsampling, start_estimate_m, how, error_m, step_tolerance_m,
        options.fixed_step_tolerance);
    if (error_m <= step_tolerance_m) break;
    if (2 * layout.sim.upsampling > 512)
      throw NumericalError(fmt::format(
          "bouc-wen: the fitted model's fixed step at {} steps per sample differs from CVODE by "
          "{:.3g} m RMS, above its tolerance {:.3g} m; fit with --integrator cvode, or a larger "
          "--step-tolerance",
          layout.sim.upsampling, error_m, step_tolerance_m));
    set_substeps(2 * layout.sim.upsampling);
    problem = nullptr;
    s = Solve(layout, data, n, s.x, options.max_iterations, options, clock, 0, &work,
              std::make_shared<EvaluationCache>(), &problem);
    owner.reset(problem);
    if (s.summary.termination_type == ceres::FAILURE || !std::isfinite(s.summary.final_cost))
      throw NumericalError("bouc-wen fit failed: " + s.summary.message);
  }
  // Standard errors from s^2 (J^T J)^-1 at the optimum, in physical units (as refine).
  const Eigen::VectorXd p = layout.Full(s.x.data());
  std::vector<double> errors(static_cast<size_t>(p.size()),
                             std::numeric_limits<double>::quiet_NaN());
  {
    std::vector<double> r(static_cast<size_t>(n));
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> J(n, np);
    double* jac[] = {J.data()};
    const double* xs[] = {s.x.data()};
    if (s.cost->Evaluate(xs, r.data(), jac)) {
      const Eigen::MatrixXd JtJ = J.transpose() * J;
      Eigen::FullPivLU<Eigen::MatrixXd> lu(JtJ);
      if (lu.isInvertible()) {
        const double s2 = 2 * s.summary.final_cost / static_cast<double>(n - np);
        const Eigen::MatrixXd cov = s2 * lu.inverse();
        for (int i = 0; i < np; ++i)
          errors[static_cast<size_t>(layout.free[static_cast<size_t>(i)])] =
              std::sqrt(cov(i, i)) * layout.scale[static_cast<size_t>(i)];
      }
    }
  }
  auto model = layout.Model(p, errors);
  if (summary != nullptr) {
    summary->kind = model->kind();
    summary->samples = static_cast<int>(n);
    summary->training_rms = std::sqrt(2 * s.summary.final_cost / static_cast<double>(n));
    summary->converged = s.summary.termination_type == ceres::CONVERGENCE;
    std::string fixed;
    if (form == BoucWenForm::kMechanical) {
      if (!options.fit_nu) fixed += fmt::format("nu fixed at {:g}", layout.all[7]);
      if (!options.fit_beta)
        fixed += fmt::format(
            "{}beta fixed at {:g} 1/m (with nu fixed, only beta*gamma and "
            "beta*delta are identifiable)",
            fixed.empty() ? "" : "; ", layout.all[4]);
    }
    const std::string why = s.timed_out
                                ? fmt::format(
                                      "stopped at the time bound max_time_s = {:g} s with the best "
                                      "parameters so far (not converged)",
                                      options.max_time_s)
                                : s.summary.message;
    summary->message =
        fmt::format("{} ({} Ceres iterations, {} simulations{}, {} starts, Jacobian by {}){}{}",
                    why, s.summary.iterations.size() - 1, work.simulations,
                    work.sensitivity_passes > 0
                        ? fmt::format(" and {} with sensitivities", work.sensitivity_passes)
                        : std::string(),
                    options.starts, jacobian_how, fixed.empty() ? "" : "; ", fixed) +
        input_note + fixed_step_note;
    summary->fit_time_s = clock.Elapsed();
  }
  return model;
}

}  // namespace sysid
