// Output-error refinement: all parameters by matching simulated and measured velocity (Ceres,
// numeric differentiation through the simulator).
#include <ceres/ceres.h>
#include <fmt/format.h>

#include <Eigen/Dense>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "core/option_rule.hpp"
#include "delay/parameter_names.hpp"
#include "delay/segments.hpp"
#include "sysid/delay.hpp"
#include "sysid/error.hpp"
#include "sysid/identify.hpp"

namespace sysid {

namespace {

// A refined parameter is "far from its prior" (the starting model) when it moved by more than
// kPriorRelativeShift of the prior AND by more than kPriorSigmaShift of its standard error (or
// the error is unknown): a large move that the fit also calls significant. A zero prior has
// no scale and is not tested.
constexpr double kPriorRelativeShift = 0.5;  // [1]
constexpr double kPriorSigmaShift = 3.0;     // [standard errors]


std::vector<std::string> FarFromPriorWarnings(const RefineResult& r) {
  std::vector<std::string> warnings;
  for (size_t i = 0; i < r.names.size(); ++i) {
    const std::string& name = r.names[i];
    const double p0 = internal::ParameterByName(r.initial, name);
    const double p = internal::ParameterByName(r.model, name);
    const double se = r.std_error[static_cast<Eigen::Index>(i)];
    const double shift = std::abs(p - p0);
    if (p0 == 0 || shift <= kPriorRelativeShift * std::abs(p0)) continue;
    if (std::isfinite(se) && shift <= kPriorSigmaShift * se) continue;
    const std::string unit = name == "tau" ? " s" : "";
    std::string w = fmt::format("{} moved from its given value {:.6g}{} to {:.6g}{} ({:+.0f} %",
                                name, p0, unit, p, unit, 100 * (p - p0) / p0);
    w += std::isfinite(se)
             ? fmt::format(", {:.0f} standard errors of {:.2g}{})", shift / se, se, unit)
             : std::string(", standard error unknown)");
    w += ": the recordings disagree with the starting model";
    if (name == "a3")
      w += "; check a3 against the data sheet, or keep it with --fix-a3";
    else if (name == "tau")
      w += "; check the delay (tune-delay), or keep it with --fix-tau";
    warnings.push_back(w);
  }
  return warnings;
}

}  // namespace

void RefineOptions::Validate() const {
  motion.Validate();
  detection.Validate();
  auto rule = [](const char* field, double value, const char* what) {
    internal::FailOption("RefineOptions", field, value, what);
  };
  if (!(tau_max_s > 0) || !std::isfinite(tau_max_s)) rule("tau_max_s", tau_max_s, "tau_max_s > 0");
  if (max_iterations < 1) rule("max_iterations", max_iterations, "max_iterations >= 1");
  if (threads < 0) rule("threads", threads, "threads >= 0");
  if (!(sim_rtol > 0 && sim_rtol < 1)) rule("sim_rtol", sim_rtol, "0 < sim_rtol < 1");
}

namespace {

// The optimiser works on z_i = p_i / s_i with s_i the parameter's typical size, so that one
// relative step size suits a1 ~ 100 1/s and tau ~ 1e-3 s alike.
struct Layout {
  std::vector<std::string> names;
  std::vector<double> scale;
};

Layout MakeLayout(const FrictionModel& m, const RefineOptions& o) {
  Layout l;
  auto add = [&](const char* name, double value, double typical) {
    l.names.emplace_back(name);
    l.scale.push_back(std::max(std::abs(value), typical));
  };
  add("a1p", m.a1p, 1e-6);
  add("a1n", m.a1n, 1e-6);
  add("a2p", m.a2p, 1e-3 * std::max(m.a2p, m.a2n) + 1e-9);
  add("a2n", m.a2n, 1e-3 * std::max(m.a2p, m.a2n) + 1e-9);
  if (o.refine_a3) add("a3", m.a3, 1e-9);
  if (o.refine_tau) add("tau", std::max(m.tau_s, 1e-3), 1e-3);
  return l;
}

// Central differences step across the bounds (tau = 0, a1 = 0, a2 = 0): the model clamps there, so the
// cost is flat outside and the simulator never sees an invalid model.
FrictionModel Apply(FrictionModel m, const Layout& l, const double* z) {
  for (size_t i = 0; i < l.names.size(); ++i) {
    const bool positive = l.names[i] == "a3";  // a1 = 0 is pure Coulomb, a valid model
    const double p = std::max(positive ? 1e-9 * l.scale[i] : 0.0, z[i] * l.scale[i]);
    internal::ParameterByName(m, l.names[i]) = p;
  }
  return m;
}

struct VelocityError {
  const FrictionModel* base;
  const Layout* layout;
  const std::vector<internal::SimSegment>* segments;
  internal::SimulationSettings settings;
  std::atomic<long>* simulations;
  bool operator()(double const* const* z, double* residuals) const {
    const FrictionModel m = Apply(*base, *layout, z[0]);
    Eigen::VectorXd r;
    std::string failure;
    try {
      if (!internal::SegmentResiduals(m, *segments, settings, &r, &failure, simulations))
        return false;  // Ceres shrinks the step
    } catch (const std::exception&) {
      return false;  // never let an exception cross Ceres' frames
    }
    Eigen::Map<Eigen::VectorXd>(residuals, r.size()) = r;
    return true;
  }
};

// Standard errors from s^2 (J^T J)^-1 at the optimum z, in physical units, into r.std_error
// (NaN where J^T J is singular).
void SetStandardErrors(const FrictionModel& initial, const Layout& layout,
                       const std::vector<internal::SimSegment>& segments, const RefineOptions& options,
                       const ceres::NumericDiffOptions& nd, double* z_data, Eigen::Index n,
                       std::atomic<long>* simulations_count, RefineResult& r) {
  const int np = static_cast<int>(layout.names.size());
  std::atomic<long>& simulations = *simulations_count;
  r.std_error = Eigen::VectorXd::Constant(np, std::numeric_limits<double>::quiet_NaN());
  // The Jacobian for the covariance is taken from simulations 1000x tighter than the fit's
  // (at most 1e-10): at the fit's rtol the central differences carry the integrator's noise,
  // which inflates J^T J and made the standard errors ~15 % too small against a Monte-Carlo
  // spread (tests/delay/refine_monte_carlo_test.cpp); at 1e-10 they agree within its error.
  const double covariance_rtol = std::min(options.sim_rtol * 1e-3, 1e-10);
  auto* tight = new ceres::DynamicNumericDiffCostFunction<VelocityError, ceres::CENTRAL>(
      new VelocityError{&initial,
                        &layout,
                        &segments,
                        {covariance_rtol, covariance_rtol * 1e-3, options.threads},
                        &simulations},
      ceres::TAKE_OWNERSHIP, nd);
  tight->AddParameterBlock(np);
  tight->SetNumResiduals(static_cast<int>(n));
  ceres::Problem covariance_problem;
  covariance_problem.AddResidualBlock(tight, nullptr, z_data);
  ceres::CRSMatrix crs;
  double final_cost = 0;
  covariance_problem.Evaluate(ceres::Problem::EvaluateOptions(), &final_cost, nullptr, nullptr,
                              &crs);
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(crs.num_rows, crs.num_cols);
  for (int row = 0; row < crs.num_rows; ++row)
    for (int k = crs.rows[static_cast<size_t>(row)]; k < crs.rows[static_cast<size_t>(row) + 1];
         ++k)
      J(row, crs.cols[static_cast<size_t>(k)]) = crs.values[static_cast<size_t>(k)];
  const Eigen::MatrixXd JtJ = J.transpose() * J;
  Eigen::FullPivLU<Eigen::MatrixXd> lu(JtJ);
  if (lu.isInvertible() && n > np) {
    const double s2 = r.final_cost / static_cast<double>(n - np);
    const Eigen::MatrixXd cov = s2 * lu.inverse();
    for (int i = 0; i < np; ++i)
      r.std_error[i] = std::sqrt(cov(i, i)) * layout.scale[static_cast<size_t>(i)];
  }
}

}  // namespace

RefineResult RefineOutputError(const FrictionModel& initial,
                               const std::vector<Recording>& recordings,
                               const RefineOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  options.Validate();
  initial.Validate();
  if (recordings.empty()) throw OptionsError("RefineOutputError: no recordings given");
  std::vector<MotionSignals> motions;
  for (const auto& r : recordings) motions.push_back(ExtractMotion(r, options.motion));
  SegmentOptions so;
  so.detection = options.detection;
  const auto segments = internal::MakeSegments(motions, so, options.motion);
  const Eigen::Index n = internal::SegmentSamples(segments);
  const Layout layout = MakeLayout(initial, options);
  const int np = static_cast<int>(layout.names.size());
  std::vector<double> z(static_cast<size_t>(np));
  {
    // At tau = 0 the cost is flat below the simulated-delay floor, so the search starts inside.
    const double tau0 = options.refine_tau && initial.tau_s < 2 * internal::kMinSimulatedDelay_s
                            ? std::min(1e-3, 0.5 * options.tau_max_s)
                            : initial.tau_s;
    const double p[] = {initial.a1p, initial.a1n, initial.a2p, initial.a2n, initial.a3, tau0};
    size_t k = 0;
    for (size_t i = 0; i < 6; ++i) {
      if ((i == 4 && !options.refine_a3) || (i == 5 && !options.refine_tau)) continue;
      z[k] = p[i] / layout.scale[k];
      ++k;
    }
  }
  std::atomic<long> simulations{0};
  auto* functor = new VelocityError{&initial,
                                    &layout,
                                    &segments,
                                    {options.sim_rtol, options.sim_rtol * 1e-3, options.threads},
                                    &simulations};
  ceres::NumericDiffOptions nd;
  nd.relative_step_size = 1e-5;  // well above the simulation's rtol, well below the curvature
  auto* cost = new ceres::DynamicNumericDiffCostFunction<VelocityError, ceres::CENTRAL>(
      functor, ceres::TAKE_OWNERSHIP, nd);
  cost->AddParameterBlock(np);
  cost->SetNumResiduals(static_cast<int>(n));
  ceres::Problem problem;
  problem.AddResidualBlock(cost, nullptr, z.data());
  for (int i = 0; i < np; ++i) {
    const std::string& name = layout.names[static_cast<size_t>(i)];
    problem.SetParameterLowerBound(z.data(), i,
                                   name == "a3" ? 1e-6 : 0.0);
    if (name == "tau")
      problem.SetParameterUpperBound(z.data(), i,
                                     options.tau_max_s / layout.scale[static_cast<size_t>(i)]);
  }
  ceres::Solver::Options so_ceres;
  so_ceres.max_num_iterations = options.max_iterations;
  so_ceres.linear_solver_type = ceres::DENSE_QR;
  // The simulations are accurate to ~rtol: tighter tolerances only chase integration noise.
  so_ceres.function_tolerance = 1e-8;
  so_ceres.parameter_tolerance = 1e-8;
  so_ceres.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(so_ceres, &problem, &summary);
  RefineResult r;
  r.initial = initial;
  r.model = Apply(initial, layout, z.data());
  r.names = layout.names;
  r.initial_cost = 2 * summary.initial_cost;  // Ceres' cost is half the sum of squares
  r.final_cost = 2 * summary.final_cost;
  r.rms_error_mps = std::sqrt(r.final_cost / static_cast<double>(n));
  // Ceres lists iteration 0 (the starting point) too; its own count, like the budget, does not.
  r.iterations = static_cast<int>(summary.iterations.size()) - 1;
  r.termination = summary.termination_type == ceres::CONVERGENCE ? Termination::kConverged
                  : summary.termination_type == ceres::NO_CONVERGENCE
                      ? Termination::kBudgetExhausted
                      : Termination::kFailure;
  r.message = summary.message;
  if (summary.termination_type == ceres::FAILURE || !std::isfinite(r.final_cost))
    throw NumericalError("output-error refinement failed: " + summary.message);
  SetStandardErrors(initial, layout, segments, options, nd, z.data(), n, &simulations, r);
  r.simulations = simulations.load();
  r.warnings = FarFromPriorWarnings(r);
  r.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

std::string RefineResult::BriefReport() const {
  std::string s = fmt::format(
      "output-error refinement: cost {:.6g} -> {:.6g} m^2/s^2 (rms {:.4g} m/s), {} iterations, "
      "{} simulations, {:.3g} s; {} ({})\n",
      initial_cost, final_cost, rms_error_mps, iterations, simulations, wall_time_s,
      ToString(termination), message);
  const double p[] = {model.a1p, model.a1n, model.a2p, model.a2n, model.a3, model.tau_s};
  const char* all[] = {"a1p", "a1n", "a2p", "a2n", "a3", "tau"};
  for (size_t i = 0; i < 6; ++i) {
    std::string se = "(fixed)";
    for (size_t k = 0; k < names.size(); ++k)
      if (names[k] == all[i])
        se = fmt::format("+- {:.2g}", std_error[static_cast<Eigen::Index>(k)]);
    s += fmt::format("  {:<4} = {:.7g} {}\n", all[i], p[i], se);
  }
  return s;
}

}  // namespace sysid
