// The mechanical Bouc–Wen oscillator: CVODE, the benchmark's chain, or the fixed step.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "hysteresis/bouc_wen_internal.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"

namespace sysid {

namespace {

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
  internal::CheckModelSimulation(options_);
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
  internal::MechanicalCvode(p_, u, dt_s, options_, {}, &y, nullptr);
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
