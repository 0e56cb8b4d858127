// The virtual piezo stack (sysid/stack.hpp): the DAC and the hysteresis are exact on the
// samples, the creep and the mechanics a linear ODE in x, x', c_1..c_m that CVODE integrates
// (Adams: the fastest eigenvalues, -zeta w_n +- j w_n ~ 6e3 1/s by default, are not stiff at
// the control period). The ODE's input y jumps at every sample, so the integrator is restarted
// there (CVodeReInit) and stopped exactly at the next sample (tstop): each integrated piece has a
// constant input and a smooth solution.
#include <fmt/format.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <unsupported/Eigen/MatrixFunctions>
#include <vector>

#include "core/cvode_solver.hpp"
#include "core/portable_random.hpp"
#include "sysid/error.hpp"
#include "sysid/stack.hpp"

namespace sysid {

class PiezoStack::Impl {
 public:
  Impl(const StackParameters& p, std::uint64_t seed) : p_(p), noise_(seed) {
    p_.Validate();
    ts_ = p_.sample_time_s();
    wn_ = 2 * M_PI * p_.mechanics.resonance_hz;
    m_ = static_cast<int>(p_.creep.time_constants_s.size());
    z_.assign(p_.hysteresis.thresholds_v.size(), 0.0);  // the operators at rest at 0 V
    dac_step_ =
        (p_.rig.voltage_max_v - p_.rig.voltage_min_v) / (std::ldexp(1.0, p_.rig.dac_bits) - 1);
    std::vector<double> y0(static_cast<size_t>(2 + m_), 0.0);
    exact_state_ = Eigen::VectorXd::Zero(2 + m_);
    if (p_.integrator.method == StackMethod::kExact) {
      Discretise();
      reading_ = Read(0.0);
      return;
    }
    cv_.emplace(2 + m_, internal::CvodeSolver::Method::kAdams, &Impl::Rhs, this, 0.0, y0.data(),
                "virtual piezo stack", "try a larger integrator.relative_tolerance");
    std::vector<double> atol(y0.size(), p_.integrator.position_tolerance_m);
    atol[1] = p_.integrator.position_tolerance_m * wn_;
    cv_->SetTolerances(p_.integrator.relative_tolerance, atol.data());
    cv_->SetMaxNumSteps(100000);
    reading_ = Read(0.0);
  }

  double DacOutput(double u) const {
    if (!std::isfinite(u))
      throw OptionsError(fmt::format("PiezoStack::Step: command {} V is not finite", u));
    const double lo = p_.rig.voltage_min_v, hi = p_.rig.voltage_max_v;
    const double c = std::clamp(u, lo, hi);
    return std::min(hi, lo + std::round((c - lo) / dac_step_) * dac_step_);
  }

  double Step(double command) {
    const double u = DacOutput(command);
    if (command < p_.rig.voltage_min_v || command > p_.rig.voltage_max_v) {
      if (clipped_ == 0) first_clip_s_ = Time();
      ++clipped_;
    }
    // The rate of the previous step (sysid/hysteresis.hpp's rdpi), 0 for the first two samples.
    const double rho = k_ >= 2 ? std::abs(u_prev_ - u_prev2_) / ts_ : 0.0;
    const auto& h = p_.hysteresis;
    double y = (h.linear_gain_m_per_v + h.rate_weights_m_s_per_v2[0] * rho) * u;
    for (size_t i = 0; i < z_.size(); ++i) {
      z_[i] = PlayStep(u, h.thresholds_v[i], z_[i]);
      y += (h.weights_m_per_v[i] + h.rate_weights_m_s_per_v2[i + 1] * rho) * z_[i];
    }
    y_ = y;
    u_prev2_ = u_prev_;
    u_prev_ = u;

    if (!cv_) {
      exact_state_ = phi_ * exact_state_ + gamma_ * y;
      ++k_;
      reading_ = Read(exact_state_[0]);
      return reading_;
    }
    const double t0 = Time(), t1 = static_cast<double>(k_ + 1) * ts_;
    cv_->ReInit(t0);
    cv_->SetStopTime(t1);
    double reached = t0;
    while (reached < t1) {
      const int flag = cv_->Advance(t1, &reached, CV_NORMAL);
      cv_->Check(flag, "CVode");
      if (flag == CV_TSTOP_RETURN) break;
    }
    ++k_;
    reading_ = Read(cv_->state()[0]);
    return reading_;
  }

  double Read(double x) {
    const double n =
        p_.rig.sensor_noise_m > 0 ? p_.rig.sensor_noise_m * noise_.IrwinHallGaussian() : 0.0;
    const double q = p_.rig.sensor_resolution_m;
    return std::round((x + n) / q) * q;
  }

  double Time() const { return static_cast<double>(k_) * ts_; }

  StackState State() const {
    const double* st = cv_ ? cv_->state() : exact_state_.data();
    StackState s;
    s.x_m = st[0];
    s.v_mps = st[1];
    s.hysteresis_m = y_;
    s.creep_m.assign(st + 2, st + 2 + m_);
    return s;
  }

  // s' = A s + B y over one held sample: exp([[A, B], [0, 0]] Ts) = [[Phi, Gamma], [0, 1]].
  void Discretise() {
    const int n = 2 + m_;
    Eigen::MatrixXd aug = Eigen::MatrixXd::Zero(n + 1, n + 1);
    const double zeta = p_.mechanics.damping_ratio;
    aug(0, 1) = 1;
    aug(1, 0) = -wn_ * wn_;
    aug(1, 1) = -2 * zeta * wn_;
    aug(1, n) = wn_ * wn_;
    for (int j = 0; j < m_; ++j) {
      const double tau = p_.creep.time_constants_s[static_cast<size_t>(j)];
      aug(1, 2 + j) = wn_ * wn_;
      aug(2 + j, 2 + j) = -1 / tau;
      aug(2 + j, n) = p_.creep.fractions[static_cast<size_t>(j)] / tau;
    }
    const Eigen::MatrixXd e = (aug * ts_).exp();
    phi_ = e.topLeftCorner(n, n);
    gamma_ = e.topRightCorner(n, 1);
    if (!phi_.allFinite() || !gamma_.allFinite())
      throw NumericalError("virtual piezo stack: the exact discretisation is not finite");
  }

  std::string DescribeLimits() const {
    if (clipped_ == 0) return "none";
    return fmt::format("amplifier range [{:g}, {:g}] V clipped {} samples (first at t = {:g} s)",
                       p_.rig.voltage_min_v, p_.rig.voltage_max_v, clipped_, first_clip_s_);
  }

  static int Rhs(double, N_Vector state, N_Vector deriv, void* data) {
    const auto* self = static_cast<const Impl*>(data);
    const double* s = N_VGetArrayPointer(state);
    double* d = N_VGetArrayPointer(deriv);
    const auto& p = self->p_;
    double drive = self->y_;
    for (int j = 0; j < self->m_; ++j) {
      drive += s[2 + j];
      d[2 + j] = (p.creep.fractions[static_cast<size_t>(j)] * self->y_ - s[2 + j]) /
                 p.creep.time_constants_s[static_cast<size_t>(j)];
    }
    const double wn = self->wn_;
    d[0] = s[1];
    d[1] = wn * wn * (drive - s[0]) - 2 * p.mechanics.damping_ratio * wn * s[1];
    return 0;
  }

  StackParameters p_;
  internal::PortableRandom noise_;
  std::optional<internal::CvodeSolver> cv_;  // empty: the exact discretisation
  Eigen::MatrixXd phi_;
  Eigen::VectorXd gamma_, exact_state_;
  double ts_ = 0, wn_ = 0, dac_step_ = 0;
  int m_ = 0;
  std::vector<double> z_;
  double y_ = 0, u_prev_ = 0, u_prev2_ = 0, reading_ = 0;
  long k_ = 0, clipped_ = 0;
  double first_clip_s_ = -1;
};

PiezoStack::PiezoStack(const StackParameters& parameters, std::uint64_t seed)
    : impl_(std::make_unique<Impl>(parameters, seed)) {}
PiezoStack::~PiezoStack() = default;
PiezoStack::PiezoStack(PiezoStack&&) noexcept = default;
PiezoStack& PiezoStack::operator=(PiezoStack&&) noexcept = default;

double PiezoStack::Step(double u_command_v) { return impl_->Step(u_command_v); }
double PiezoStack::measured_position_m() const { return impl_->reading_; }
double PiezoStack::time_s() const { return impl_->Time(); }
StackState PiezoStack::state() const { return impl_->State(); }
const StackParameters& PiezoStack::parameters() const { return impl_->p_; }
double PiezoStack::DacOutput(double u_command_v) const { return impl_->DacOutput(u_command_v); }
long PiezoStack::clipped_samples() const { return impl_->clipped_; }
std::string PiezoStack::DescribeLimits() const { return impl_->DescribeLimits(); }

StackRun RunStackOpenLoop(const StackParameters& parameters, const Eigen::VectorXd& u_v,
                          std::uint64_t seed) {
  PiezoStack stack(parameters, seed);
  const Eigen::Index n = u_v.size();
  StackRun run;
  run.t_s.resize(n);
  run.u_v = u_v;
  run.x_m.resize(n);
  run.x_true_m.resize(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    run.t_s[k] = stack.time_s();
    run.x_m[k] = stack.measured_position_m();
    run.x_true_m[k] = stack.state().x_m;
    stack.Step(u_v[k]);
  }
  run.clipped_samples = stack.clipped_samples();
  return run;
}

}  // namespace sysid
