// One Ceres solve of the Bouc–Wen fit (its bounds, tolerances, time bound and progress), and the
// fixed step's check of the fitted model.
#include <fmt/format.h>

#include <Eigen/Cholesky>
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

// Stops the solve once the Gauss–Newton step from the current point is shorter than
// kNoiseFloorStep standard errors (s^2 = g' (J'J)^-1 g / sigma^2 with g = J'r and sigma^2 =
// r'r / (n - p), from the cached exact Jacobian at that point): CVODE's cost is exact to its
// rtol only, and there the trust region's steps are rejected or accepted on its noise until the
// parameter tolerance, each an exact Jacobian (measured: 7 of 10 final iterations on the
// benchmark, none moving a parameter by 0.01 standard errors).
class NoiseFloorCallback final : public ceres::IterationCallback {
 public:
  NoiseFloorCallback(const std::vector<double>* x, const EvaluationCache* cache)
      : x_(x), cache_(cache) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary&) override {
    const EvaluationCache& c = *cache_;
    const Eigen::VectorXd* r = nullptr;
    const EvaluationCache::RowMajor* j = nullptr;
    if (c.ok && c.has_jacobian && c.x == *x_) {
      r = &c.r;
      j = &c.j;
    } else if (c.before_has_jacobian && c.x_before == *x_) {
      r = &c.r_before;
      j = &c.j_before;
    } else {
      return ceres::SOLVER_CONTINUE;
    }
    const double dof = static_cast<double>(j->rows() - j->cols());
    if (!(dof > 0)) return ceres::SOLVER_CONTINUE;
    const Eigen::MatrixXd jtj = j->transpose() * *j;
    const Eigen::VectorXd g = j->transpose() * *r;
    const Eigen::LDLT<Eigen::MatrixXd> ldlt(jtj);
    if (ldlt.info() != Eigen::Success) return ceres::SOLVER_CONTINUE;
    const double sigma2 = r->squaredNorm() / dof;
    const double s2 = g.dot(ldlt.solve(g)) / sigma2;
    if (!(s2 < kNoiseFloorStep * kNoiseFloorStep)) return ceres::SOLVER_CONTINUE;
    step_se = std::sqrt(s2);
    return ceres::SOLVER_TERMINATE_SUCCESSFULLY;
  }
  double step_se = -1;  ///< the step that stopped the solve [standard errors]; < 0: none did

 private:
  const std::vector<double>* x_;
  const EvaluationCache* cache_;
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
  NoiseFloorCallback noise_floor(&s.x, cache.get());
  if (l.SimulatedByCvode() && o.jacobian == BoucWenJacobian::kSensitivities && cache) {
    so.update_state_every_iteration = true;  // the callback reads the current point in s.x
    so.callbacks.push_back(&noise_floor);
  }
  ceres::Solve(so, problem, &s.summary);
  if (noise_floor.step_se >= 0)
    s.summary.message = fmt::format(
        "the Gauss-Newton step is {:.2g} standard errors (< {:g}: CVODE's noise from here)",
        noise_floor.step_se, kNoiseFloorStep);
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
