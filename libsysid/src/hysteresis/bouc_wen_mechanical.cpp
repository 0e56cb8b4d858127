// The mechanical Bouc–Wen oscillator: CVODE, the benchmark's chain, or the fixed step.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/cvode_solver.hpp"
#include "hysteresis/bouc_wen_internal.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"

namespace sysid {

namespace {

struct MechanicalOde {
  const MechanicalBoucWenParameters* p;
  const internal::SampledInput* input;
  Eigen::Index interval = 0;
};

int MechanicalRhs(double t, N_Vector x, N_Vector dx, void* data) {
  const auto* ode = static_cast<const MechanicalOde*>(data);
  const double* s = N_VGetArrayPointer(x);
  double* d = N_VGetArrayPointer(dx);
  double u = 0, du = 0;
  ode->input->Evaluate(t, ode->interval, &u, &du);
  const auto& p = *ode->p;
  d[0] = s[1];
  d[1] = (u - p.c_n_s_per_m * s[1] - p.k_n_per_m * s[0] - s[2]) / p.m_kg;
  d[2] = internal::MechanicalRate(p, s[1], s[2]).f;
  return std::isfinite(d[1]) && std::isfinite(d[2]) ? 0 : 1;  // > 0: CVODE retries smaller
}

[[noreturn]] void ThrowNoInverse() {
  throw NumericalError(
      "bouc-wen: the mechanical form has no inverse here (it needs y'' of the desired output); "
      "use the piezo form (bouc-wen-piezo) for feedforward");
}

}  // namespace

MechanicalBoucWen::MechanicalBoucWen(const MechanicalBoucWenParameters& p,
                                     const BoucWenSimulationOptions& options,
                                     std::vector<double> std_errors)
    : p_(p), options_(options), std_errors_(std::move(std_errors)) {
  p_.Validate();
  options_.Validate();
}

Eigen::VectorXd MechanicalBoucWen::Simulate(const Eigen::VectorXd& u, double dt_s) const {
  internal::CheckSamples(u, dt_s, "bouc-wen", "u");
  const Eigen::Index n = u.size();
  Eigen::VectorXd y = Eigen::VectorXd::Zero(n);
  if (n == 0) return y;
  if (options_.integrator == BoucWenIntegrator::kBenchmarkChain) {
    internal::CheckChainWork(n, options_.upsampling, 1, "bouc-wen");
    return internal::ChainOutput(p_, internal::ChainInput(u, options_.upsampling), n, dt_s,
                                 options_.upsampling);
  }
  if (options_.integrator == BoucWenIntegrator::kFixedStep) {
    internal::CheckFixedStepWork(n, options_.upsampling, options_.input, "bouc-wen");
    return internal::FixedStepOutput(
        p_, internal::FixedStepInput(u, options_.input, options_.upsampling), dt_s,
        options_.upsampling);
  }
  const internal::SampledInput input(u, dt_s, options_.input);
  MechanicalOde ode{&p_, &input, 0};
  const double x0[3] = {0, 0, 0};
  internal::CvodeSolver solver(3, internal::CvodeSolver::Method::kAdams, MechanicalRhs, &ode, 0, x0,
                               "bouc-wen simulation", "check the parameters, or loosen rtol");
  // Absolute tolerances from the static scales: y ~ max|u| / (k + alpha), z ~ max|u|.
  const double umax = std::max(u.cwiseAbs().maxCoeff(), 1e-300);
  const double ys = umax / (p_.k_n_per_m + p_.alpha_n_per_m);
  const double vs = ys * std::sqrt((p_.k_n_per_m + p_.alpha_n_per_m) / p_.m_kg);
  const double atol[3] = {1e-3 * options_.rtol * ys, 1e-3 * options_.rtol * vs,
                          1e-3 * options_.rtol * umax};
  solver.SetTolerances(options_.rtol, atol);
  solver.SetMaxNumSteps(1000000);
  const bool smooth = options_.input == InputInterpolation::kBandLimited;
  double t = 0;
  for (Eigen::Index k = 0; k + 1 < n; ++k) {
    const double t_next = static_cast<double>(k + 1) * dt_s;
    ode.interval = k;
    if (!smooth) solver.SetStopTime(t_next);  // never step past a kink or a jump of u
    solver.Check(solver.Advance(t_next, &t, CV_NORMAL), "CVode");
    y[k + 1] = solver.state()[0];
    // A held input jumps at every sample, a linear one's slope does: CVODE's multistep
    // history would carry the jump into the next interval, so it restarts there.
    if (!smooth) solver.ReInit(t_next);
  }
  return y;
}

Eigen::VectorXd MechanicalBoucWen::SimulatePeriodic(const Eigen::VectorXd& u_period, double dt_s,
                                                    double tolerance, int max_periods) const {
  if (options_.integrator != BoucWenIntegrator::kBenchmarkChain)
    return HysteresisModel::SimulatePeriodic(u_period, dt_s, tolerance, max_periods);
  internal::CheckSamples(u_period, dt_s, "bouc-wen", "u");
  if (!(tolerance >= 0) || max_periods < 3)
    throw OptionsError("SimulatePeriodic: tolerance >= 0 and max_periods >= 3 are required",
                       "tolerance");
  const Eigen::Index n = u_period.size();
  const int up = options_.upsampling;
  // Three periods at least; past kMaxSignalSamples fine samples in all the search stops.
  internal::CheckChainWork(n, up, 3, "bouc-wen");
  max_periods = std::min<double>(max_periods, std::floor(kMaxSignalSamples / (double(n) * up)));
  const std::vector<int> factors = internal::PrimeFactors(up);
  const Eigen::VectorXd uf = UpsampleBandLimited(u_period, up);
  const Eigen::Index nf = uf.size();
  if (n < 1 || internal::FirLookahead(factors) > nf)
    throw InputError(fmt::format(
        "bouc-wen: a period of {} samples is shorter than the decimation filter's reach", n));
  // The last three fine periods: the middle one, decimated with its neighbours, is the steady
  // state as the benchmark's filter sees it.
  Eigen::VectorXd yf(3 * nf);
  internal::NewmarkState s;
  double change = std::numeric_limits<double>::infinity();
  int periods = 0;
  while (periods < max_periods) {
    // Shift: periods 1, 2 become 0, 1; the new one is 2.
    yf.head(2 * nf) = yf.tail(2 * nf).eval();
    internal::NewmarkBoucWen(p_, uf.data(), nf, dt_s / up, &s, yf.data() + 2 * nf);
    ++periods;
    if (periods >= 2) change = (yf.tail(nf) - yf.segment(nf, nf)).cwiseAbs().maxCoeff();
    if (periods >= 3 && change <= tolerance) break;
  }
  if (!(change <= tolerance))
    throw NumericalError(fmt::format(
        "bouc-wen: no periodic steady state within {} periods (at most {:.0e} fine samples "
        "in all, sysid::kMaxSignalSamples): the last two periods still differ by {:.3g} m "
        "(tolerance {:.3g} m)",
        max_periods, kMaxSignalSamples, change, tolerance));
  const Eigen::VectorXd yd = internal::DecimateChain(yf, factors);
  return yd.segment(n, n);
}

Eigen::VectorXd MechanicalBoucWen::Invert(const Eigen::VectorXd&, double) const {
  ThrowNoInverse();
}

std::unique_ptr<HysteresisInverseStepper> MechanicalBoucWen::InverseStepper(double) const {
  ThrowNoInverse();
}

std::vector<HysteresisParameter> MechanicalBoucWen::parameters() const {
  std::vector<HysteresisParameter> v = {
      {"m", "kg", p_.m_kg, NAN},           {"c", "N s/m", p_.c_n_s_per_m, NAN},
      {"k", "N/m", p_.k_n_per_m, NAN},     {"alpha", "N/m", p_.alpha_n_per_m, NAN},
      {"beta", "1/m", p_.beta_per_m, NAN}, {"gamma", "1", p_.gamma, NAN},
      {"delta", "1", p_.delta, NAN},       {"nu", "1", p_.nu, NAN}};
  if (p_.nu != 1) v[4].unit = "N^(1-nu)/m";
  for (size_t i = 0; i < v.size() && i < std_errors_.size(); ++i) v[i].std_error = std_errors_[i];
  return v;
}

}  // namespace sysid
