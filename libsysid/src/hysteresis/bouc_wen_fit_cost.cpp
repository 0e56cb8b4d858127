// The Bouc–Wen fit's cost function: the residuals y_model - x and their Jacobian, by forward
// sensitivities (one pass per recording) or by central differences (2 p + 1 simulations, in
// parallel).
#include <algorithm>
#include <cmath>
#include <utility>

#include "core/parallel_for.hpp"
#include "hysteresis/bouc_wen_fit_problem.hpp"
#include "sysid/error.hpp"

namespace sysid::internal::bouc_wen_fit {

namespace {

// The model's y at a recording's samples, from its fine input or its CVODE input when the fit
// keeps one (Simulate's result to the bit).
Eigen::VectorXd SimulateSeries(const Layout& l, const HysteresisModel& model, const Series& s) {
  if (s.input && l.form == BoucWenForm::kPiezo)
    return internal::PiezoCvode(static_cast<const PiezoBoucWen&>(model).values(), *s.input,
                                l.sim.rtol);
  if (s.input) {
    Eigen::VectorXd y;
    internal::MechanicalCvode(static_cast<const MechanicalBoucWen&>(model).values(), *s.input,
                              l.sim, {}, &y, nullptr);
    return y;
  }
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

}  // namespace

OutputError::OutputError(const Layout* l, const std::vector<Series>* data, Eigen::Index n,
                         int threads, BoucWenJacobian jacobian, Work* work,
                         std::shared_ptr<EvaluationCache> cache)
    : l_(l), data_(data), threads_(threads), work_(work), c_(std::move(cache)) {
  // The exact Jacobian: the mechanical form's chain and fixed step (a fine input kept) and
  // CVODE (CVODES), the piezo form's closed-form step (not its CVODE, for a band-limited input).
  sensitivities_ = jacobian == BoucWenJacobian::kSensitivities && !data->empty();
  if (l->form == BoucWenForm::kPiezo)
    sensitivities_ = sensitivities_ && l->sim.input != InputInterpolation::kBandLimited;
  mutable_parameter_block_sizes()->push_back(static_cast<int>(l->free.size()));
  set_num_residuals(static_cast<int>(n));
}

bool OutputError::Evaluate(double const* const* x, double* residuals, double** jacobians) const {
  const int np = static_cast<int>(l_->free.size());
  const Eigen::Index n = num_residuals();
  const bool want_jacobian = jacobians != nullptr && jacobians[0] != nullptr;
  auto at = [&](const std::vector<double>& y) {
    return y.size() == static_cast<size_t>(np) && std::equal(y.begin(), y.end(), x[0]);
  };
  if (!at(c_->x) && c_->before_has_jacobian && at(c_->x_before)) {
    // The point before the last, with its Jacobian: it becomes the last (and the last, when it
    // has its Jacobian, the one before).
    const bool keep_last = c_->ok && c_->has_jacobian;
    std::swap(c_->x, c_->x_before);
    c_->r.swap(c_->r_before);
    c_->j.swap(c_->j_before);
    c_->ok = c_->has_jacobian = true;
    c_->before_has_jacobian = keep_last;
  }
  const bool same = at(c_->x);
  if (same && (!c_->ok || !want_jacobian || c_->has_jacobian)) {
    if (!c_->ok) return false;
    Eigen::Map<Eigen::VectorXd>(residuals, n) = c_->r;
    if (want_jacobian) Jacobian(jacobians[0], n, np) = c_->j;
    return true;
  }
  if (c_->ok && c_->has_jacobian && !same) {
    std::swap(c_->x, c_->x_before);
    c_->r.swap(c_->r_before);
    c_->j.swap(c_->j_before);
    c_->before_has_jacobian = true;
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
  } else if (!CentralDifferences(x[0], same, residuals, jacobians[0])) {
    return false;  // the residuals, when they were computed, are in the cache
  }
  c_->j = Jacobian(jacobians[0], n, np);
  c_->has_jacobian = true;
  return true;
}

// Residuals (unless the cache has them: have_residuals) and 2 np perturbed simulations, in
// parallel; the residuals go to the cache. False when the residuals or a column fail.
bool OutputError::CentralDifferences(const double* x, bool have_residuals, double* residuals,
                                     double* jacobian) const {
  const int np = static_cast<int>(l_->free.size());
  const Eigen::Index n = num_residuals();
  std::vector<Eigen::VectorXd> r(static_cast<size_t>(2 * np + 1), Eigen::VectorXd(n));
  std::vector<char> ok(r.size(), 0);
  if (have_residuals) {
    r[0] = c_->r;
    ok[0] = 1;
  }
  std::vector<double> step(static_cast<size_t>(np));
  for (int i = 0; i < np; ++i)
    // The simulations are exact to rounding (Newmark, closed form) or to rtol (CVODE): a step
    // of 1e-6 of the parameter's scale keeps the difference error near 1e-10 relative.
    step[static_cast<size_t>(i)] = 1e-6 * std::max(std::abs(x[i]), 1e-3);
  const long first = have_residuals ? 1 : 0;
  internal::ParallelFor(static_cast<long>(r.size()) - first, threads_, [&](long job) {
    const long j = job + first;
    std::vector<double> xj(x, x + np);
    if (j > 0) {
      const int i = static_cast<int>((j - 1) / 2);
      xj[static_cast<size_t>(i)] += (j % 2 == 1 ? 1 : -1) * step[static_cast<size_t>(i)];
    }
    ok[static_cast<size_t>(j)] = Residuals(*l_, *data_, xj.data(), r[static_cast<size_t>(j)].data());
  });
  work_->simulations += static_cast<long>(r.size()) - first;
  c_->ok = ok[0] != 0;
  if (!c_->ok) return false;
  c_->r = r[0];
  Eigen::Map<Eigen::VectorXd>(residuals, n) = r[0];
  auto J = Jacobian(jacobian, n, np);
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
  return true;
}

// The residuals and their exact Jacobian (ChainOutputSensitivity, FixedStepOutputSensitivity,
// MechanicalCvode, PiezoOutputSensitivity), the recordings in parallel; false when the parameters are invalid or
// a simulation fails.
bool OutputError::ResidualsAndSensitivities(const double* x, double* residuals,
                                            double* jacobian) const {
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
      else if (l_->sim.integrator == BoucWenIntegrator::kCvode && s.input)
        internal::MechanicalCvode(m, *s.input, l_->sim, l_->free, &y, &dy);
      else if (l_->sim.integrator == BoucWenIntegrator::kCvode)
        internal::MechanicalCvode(m, s.u, s.dt_s, l_->sim, l_->free, &y, &dy);
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

}  // namespace sysid::internal::bouc_wen_fit
