// One Ceres solve of the Bouc–Wen fit (its bounds, tolerances, time bound and progress), and the
// fixed step's check of the fitted model.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "hysteresis/bouc_wen_fit_problem.hpp"
#include "sysid/error.hpp"

namespace sysid::internal::bouc_wen_fit {

namespace {

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

}  // namespace

Solved Solve(const Layout& l, const std::vector<Series>& data, Eigen::Index n,
             std::vector<double> x, int iterations, const BoucWenFitOptions& o,
             const FitClock& clock, int start, Work* work, std::shared_ptr<EvaluationCache> cache,
             ceres::Problem** keep) {
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
  if (l.SimulatedByCvode()) {
    // CVODE's simulation is exact to its rtol only: the cost's last digits are its noise, and
    // iterations past it moved nothing but the noise while each cost an exact Jacobian
    // (measured: 10 of the benchmark's 19 final iterations). A relative cost change c is a step
    // of about sqrt(c n) standard errors: 0.02 at c = 1e-8 on n = 4e4 samples.
    so.function_tolerance = std::max(1e-12, 10 * l.sim.rtol);
    so.parameter_tolerance = std::max(1e-12, l.sim.rtol);
  }
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

}  // namespace sysid::internal::bouc_wen_fit
