// The piezo Bouc–Wen model: an exact step for straight input segments, CVODE for band-limited
// inputs, and the per-sample inverse.
#include <ceres/jet.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/cvode_solver.hpp"
#include "core/option_rule.hpp"
#include "hysteresis/bouc_wen_internal.hpp"
#include "sysid/error.hpp"
#include "sysid/hysteresis_stepper.hpp"

namespace sysid {

namespace internal {

void PiezoOutputSensitivity(const PiezoBoucWenParameters& p, const Eigen::VectorXd& u,
                            Eigen::VectorXd* y, Eigen::MatrixXd* dy_dp) {
  using J = ceres::Jet<double, 4>;  // d, alpha, beta, gamma
  const Eigen::Index n = u.size();
  y->resize(n);
  dy_dp->resize(n, 5);
  const J d(p.d_m_per_v, 0), alpha(p.alpha, 1), beta(p.beta_per_v, 2), gamma(p.gamma_per_v, 3);
  double h = 0;
  J hj(0.0);
  for (Eigen::Index k = 0; k < n; ++k) {
    if (k > 0) {
      h = PiezoStep(p, u[k - 1], u[k], h);
      hj = PiezoStepOf<J>(d, alpha, beta, gamma, u[k - 1], u[k], hj);
    }
    (*y)[k] = p.d_m_per_v * u[k] - h + p.offset_m;
    // y = d u - h + offset.
    dy_dp->row(k).head<4>() = -hj.v.transpose();
    (*dy_dp)(k, 0) += u[k];
    (*dy_dp)(k, 4) = 1;
  }
}

}  // namespace internal

namespace {

struct PiezoOde {
  const PiezoBoucWenParameters* p;
  const internal::SampledInput* input;
  Eigen::Index interval = 0;
};

int PiezoRhs(double t, N_Vector x, N_Vector dx, void* data) {
  const auto* ode = static_cast<const PiezoOde*>(data);
  const double h = N_VGetArrayPointer(x)[0];
  double u = 0, du = 0;
  ode->input->Evaluate(t, ode->interval, &u, &du);
  const auto& p = *ode->p;
  N_VGetArrayPointer(dx)[0] = p.alpha * p.d_m_per_v * du - p.beta_per_v * std::abs(du) * h -
                              p.gamma_per_v * du * std::abs(h);
  return 0;
}


}  // namespace

namespace internal {

Eigen::VectorXd PiezoCvode(const PiezoBoucWenParameters& p, const SampledInput& input,
                           double rtol) {
  const Eigen::VectorXd& u = input.samples();
  const double dt_s = input.dt_s();
  const InputInterpolation how = input.how();
  const Eigen::Index n = u.size();
  Eigen::VectorXd y(n);
  if (n == 0) return y;
  PiezoOde ode{&p, &input, 0};
  const double h0 = 0;
  CvodeSolver solver(1, CvodeSolver::Method::kAdams, PiezoRhs, &ode, 0, &h0,
                     "bouc-wen-piezo simulation", "check the parameters");
  const double hs = p.d_m_per_v * std::max(u.cwiseAbs().maxCoeff(), 1e-300);
  const double atol = 1e-3 * rtol * hs;
  solver.SetTolerances(rtol, &atol);
  solver.SetMaxNumSteps(1000000);
  double t = 0;
  y[0] = p.d_m_per_v * u[0] + p.offset_m;
  for (Eigen::Index k = 0; k + 1 < n; ++k) {
    const double t_next = static_cast<double>(k + 1) * dt_s;
    ode.interval = k;
    if (how != InputInterpolation::kBandLimited) solver.SetStopTime(t_next);
    solver.Check(solver.Advance(t_next, &t, CV_NORMAL), "CVode");
    y[k + 1] = p.d_m_per_v * u[k + 1] - solver.state()[0] + p.offset_m;
    // u' jumps at every sample of a linear input, and with it h': restart there.
    if (how != InputInterpolation::kBandLimited) solver.ReInit(t_next);
  }
  return y;
}

}  // namespace internal

PiezoBoucWen::PiezoBoucWen(const PiezoBoucWenParameters& p, const BoucWenSimulationOptions& options,
                           std::vector<double> std_errors)
    : p_(p), options_(options), std_errors_(std::move(std_errors)) {
  p_.Validate();
  internal::CheckModelSimulation(options_);
  if (options_.integrator != BoucWenIntegrator::kCvode)
    internal::FailOption("BoucWenSimulationOptions", "integrator",
                         options_.integrator == BoucWenIntegrator::kFixedStep ? "fixed-step"
                                                                              : "benchmark-chain",
                         "the chain and the fixed step are the mechanical form's (use cvode for "
                         "bouc-wen-piezo: its held or linear input takes the exact closed-form "
                         "step)");
}

Eigen::VectorXd PiezoBoucWen::Simulate(const Eigen::VectorXd& u, double dt_s) const {
  if (options_.input == InputInterpolation::kBandLimited) return SimulateCvode(u, dt_s);
  internal::CheckSamples(u, dt_s, "bouc-wen-piezo", "u");
  const Eigen::Index n = u.size();
  Eigen::VectorXd y(n);
  double h = 0;
  for (Eigen::Index k = 0; k < n; ++k) {
    if (k > 0) h = internal::PiezoStep(p_, u[k - 1], u[k], h);
    y[k] = p_.d_m_per_v * u[k] - h + p_.offset_m;
  }
  return y;
}

Eigen::VectorXd PiezoBoucWen::SimulateCvode(const Eigen::VectorXd& u, double dt_s) const {
  internal::CheckSamples(u, dt_s, "bouc-wen-piezo", "u");
  // A held input moves along the same straight segment as a linear one, only instantly: the
  // rate-independent model cannot tell them apart.
  const InputInterpolation how =
      options_.input == InputInterpolation::kHold ? InputInterpolation::kLinear : options_.input;
  return internal::PiezoCvode(p_, internal::SampledInput(u, dt_s, how), options_.rtol);
}

bool PiezoBoucWen::invertible() const {
  const double d = p_.d_m_per_v, a = p_.alpha, b = p_.beta_per_v, g = p_.gamma_per_v;
  if (!(d > 0) || !(b + g > 0)) return false;
  return d * (1 - a) - std::max(b - g, 0.0) * std::abs(a) * d / (b + g) > 0;
}

BoucWenInverseStepper::BoucWenInverseStepper(const PiezoBoucWen& model) : p_(model.values()) {
  if (!model.invertible())
    throw NumericalError(fmt::format(
        "bouc-wen-piezo: not invertible with d = {:.6g} m/V, alpha = {:.6g}, beta = {:.6g} 1/V, "
        "gamma = {:.6g} 1/V: y is not monotone in u (needs d > 0, beta + gamma > 0 and "
        "(1 - alpha)(beta + gamma) > |alpha| max(beta - gamma, 0))",
        p_.d_m_per_v, p_.alpha, p_.beta_per_v, p_.gamma_per_v));
}

void BoucWenInverseStepper::Reset() {
  u_prev_ = h_ = 0;
  k_ = 0;
  out_of_reach_ = false;
}

double BoucWenInverseStepper::Step(double x_ref_m) {
  const double d = p_.d_m_per_v;
  out_of_reach_ = false;
  if (k_++ == 0) {
    u_prev_ = (x_ref_m - p_.offset_m) / d;  // h = 0 at the start
    return u_prev_;
  }
  const double target = x_ref_m, u0 = u_prev_, h = h_;
  auto g = [&](double v) { return d * v - internal::PiezoStep(p_, u0, v, h) + p_.offset_m - target; };
  // y rises with u: bracket the root by doubling the step from u_{k-1}.
  const double g0 = g(u0);
  double lo = u0, hi = u0;
  const double dir = g0 < 0 ? 1.0 : -1.0;
  double step = std::max(std::abs(g0) / (d * std::max(1 - p_.alpha, 1e-3)), 1e-300);
  double far = u0;
  int expansions = 0;
  for (; expansions < 200; ++expansions) {
    far = u0 + dir * step;
    if ((g(far) < 0) != (g0 < 0) || g(far) == 0) break;
    step *= 2;
  }
  if (expansions == 200) {
    out_of_reach_ = true;
    return u0;
  }
  lo = std::min(u0, far);
  hi = std::max(u0, far);
  // Bisection on the monotone g to the last bit: the inverse is then exact to rounding.
  double glo = g(lo);
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;
    const double gm = g(mid);
    if (gm == 0) {
      lo = hi = mid;
      break;
    }
    if ((gm < 0) == (glo < 0)) {
      lo = mid;
      glo = gm;
    } else {
      hi = mid;
    }
  }
  const double u = std::abs(g(lo)) <= std::abs(g(hi)) ? lo : hi;
  h_ = internal::PiezoStep(p_, u0, u, h);
  u_prev_ = u;
  return u;
}

Eigen::VectorXd PiezoBoucWen::Invert(const Eigen::VectorXd& y_desired, double dt_s) const {
  internal::CheckSamples(y_desired, dt_s, "bouc-wen-piezo", "y_desired");
  BoucWenInverseStepper stepper(*this);  // NumericalError when not invertible
  const Eigen::Index n = y_desired.size();
  Eigen::VectorXd u(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    u[k] = stepper.Step(y_desired[k]);
    if (stepper.out_of_reach())
      throw InputError(fmt::format(
          "bouc-wen-piezo: y_desired[{}] = {:.6g} m is out of the model's reach", k, y_desired[k]));
  }
  return u;
}

std::unique_ptr<HysteresisInverseStepper> PiezoBoucWen::InverseStepper(double) const {
  return std::make_unique<BoucWenInverseStepper>(*this);
}

std::vector<HysteresisParameter> PiezoBoucWen::parameters() const {
  std::vector<HysteresisParameter> v = {{"d", "m/V", p_.d_m_per_v, NAN},
                                        {"alpha", "1", p_.alpha, NAN},
                                        {"beta", "1/V", p_.beta_per_v, NAN},
                                        {"gamma", "1/V", p_.gamma_per_v, NAN},
                                        {"offset", "m", p_.offset_m, NAN}};
  for (size_t i = 0; i < v.size() && i < std_errors_.size(); ++i) v[i].std_error = std_errors_[i];
  return v;
}

}  // namespace sysid
