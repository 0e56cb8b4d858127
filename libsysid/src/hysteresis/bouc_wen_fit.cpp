// Output-error fit of the Bouc–Wen models: the recordings read, the input between samples
// chosen, several starts, the final fit (the fixed step checked and refined), standard errors and
// the summary. The problem itself: bouc_wen_fit_problem.hpp.
#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <exception>
#include <functional>
#include <limits>
#include <memory>
#include <mutex>
#include <thread>

#include "core/option_rule.hpp"
#include "core/parallel_for.hpp"
#include "core/portable_random.hpp"
#include "hysteresis/bouc_wen_fit_problem.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"
#include "sysid/motion.hpp"

namespace sysid {

namespace {

using internal::bouc_wen_fit::EvaluationCache;
using internal::bouc_wen_fit::FitClock;
using internal::bouc_wen_fit::Layout;
using internal::bouc_wen_fit::MechanicalParameters;
using internal::bouc_wen_fit::Series;
using internal::bouc_wen_fit::ShareCvodeInputs;
using internal::bouc_wen_fit::Solve;
using internal::bouc_wen_fit::Solved;
using internal::bouc_wen_fit::Work;

// The recordings as the fit's series (the chain's fine input computed once); *n: the samples in
// all. InputError for a recording too short, with a non-finite value, or a constant input.
std::vector<Series> ReadSeries(BoucWenForm form, const std::vector<Recording>& recordings,
                               const BoucWenFitOptions& options, Eigen::Index* n) {
  std::vector<Series> data;
  *n = 0;
  for (const auto& r : recordings) {
    if (r.rows() < 3)
      throw InputError(fmt::format("{}: {} samples: a fit needs at least 3", r.source, r.rows()));
    Series s{r.column("u"), r.column("x"), UniformSampleInterval(r, 1e-3), {}, {}};
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
    *n += s.u.size();
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
  return data;
}

// The mechanical form's input kAuto: band-limited when every recording is whole periods of a
// band-limited signal and the integrator takes it (CVODE has a work bound for it), else linear,
// into layout->sim.input; returns the summary's note.
std::string ChooseInput(const std::vector<Series>& data, Layout* layout) {
  bool band_limited = true;
  double worst_wrap = 0, worst_high = 0;
  for (const auto& s : data) {
    double wrap = 0, high = 0;
    band_limited = internal::PeriodicBandLimited(s.u, &wrap, &high) && band_limited;
    worst_wrap = std::max(worst_wrap, wrap / std::max(s.u.cwiseAbs().maxCoeff(), 1e-300));
    worst_high = std::max(worst_high, high);
  }
  std::string refused;
  if (band_limited && layout->sim.integrator == BoucWenIntegrator::kCvode) {
    try {
      for (const auto& s : data) internal::SampledInput::GridPerSample(s.u, s.dt_s);
    } catch (const InputError& e) {
      refused = fmt::format("; CVODE refuses it: {}", e.what());
      band_limited = false;
    }
  }
  layout->sim.input = band_limited ? InputInterpolation::kBandLimited : InputInterpolation::kLinear;
  return fmt::format(
      "; input {} between samples (chosen: {}; largest wrap step {:.3g} of max|u|, power above "
      "a quarter of the sampling rate {:.3g} of the variance, band-limited at most {:g}{})",
      band_limited ? "band-limited" : "linear",
      band_limited || !refused.empty()
          ? "every recording is whole periods of a band-limited signal"
          : "not every recording is whole periods of a band-limited signal",
      worst_wrap, worst_high, internal::kBandLimitedPower, refused);
}

// BoucWenFitOptions' kAuto resolved (its rules are there); returns the input's note.
std::string ResolveAuto(BoucWenForm form, const std::vector<Series>& data, Layout* layout) {
  std::string note;
  if (layout->sim.input == InputInterpolation::kAuto) {
    // The chain takes its input band-limited whatever `input` says (and records linear).
    if (form == BoucWenForm::kMechanical &&
        layout->sim.integrator != BoucWenIntegrator::kBenchmarkChain)
      note = ChooseInput(data, layout);
    else
      layout->sim.input = InputInterpolation::kLinear;
  }
  if (layout->sim.integrator == BoucWenIntegrator::kAuto)
    layout->sim.integrator =
        form == BoucWenForm::kMechanical && layout->sim.input != InputInterpolation::kHold
            ? BoucWenIntegrator::kFixedStep
            : BoucWenIntegrator::kCvode;
  return note;
}

// The fixed step's steps per sample m: the fine inputs at m (the work bound checked first: a
// doubled m was not checked by the choice).
void SetSubsteps(int m, std::vector<Series>* data, Layout* layout) {
  layout->sim.upsampling = m;
  for (auto& s : *data) {
    internal::CheckFixedStepWork(s.u.size(), m, layout->sim.input, "bouc-wen");
    s.fine_u = internal::FixedStepInput(s.u, layout->sim.input, m);
  }
}

// How many starts run side by side on `threads`: as many as the threads the cost function
// leaves idle. Its exact Jacobian is one pass per recording (parallel over recordings), so one
// recording on 2 threads runs 2 starts at once; central differences fill the threads with their
// 2 np + 1 simulations, so starts run in turn.
int ConcurrentStarts(const BoucWenFitOptions& options, bool exact, size_t recordings, int np) {
  const int threads = internal::ResolveThreads(options.threads, options.starts);
  const long width = exact ? static_cast<long>(recordings) : 2L * np + 1;
  return std::max(1, threads / internal::ResolveThreads(threads, width));
}

// The starts' progress reports, handed to the caller's on_iteration on the calling thread in
// start order (all of start 1's, then start 2's, ...): the starts' threads queue them here.
class StartReports {
 public:
  explicit StartReports(int starts)
      : pending_(static_cast<size_t>(starts)), done_(static_cast<size_t>(starts), false) {}
  void Add(int k, const BoucWenFitProgress& p) {
    std::lock_guard<std::mutex> lock(mutex_);
    pending_[static_cast<size_t>(k)].push_back(p);
    changed_.notify_one();
  }
  void Done(int k) {
    std::lock_guard<std::mutex> lock(mutex_);
    done_[static_cast<size_t>(k)] = true;
    changed_.notify_one();
  }
  // Until every start is done: each report as soon as the earlier starts' are out.
  void Deliver(const std::function<void(const BoucWenFitProgress&)>& to) {
    std::unique_lock<std::mutex> lock(mutex_);
    for (size_t head = 0; head < pending_.size();) {
      changed_.wait(lock, [&] { return !pending_[head].empty() || done_[head]; });
      std::vector<BoucWenFitProgress> out;
      out.swap(pending_[head]);
      const bool finished = done_[head];
      lock.unlock();
      if (to)
        for (const auto& p : out) to(p);
      lock.lock();
      if (finished && pending_[head].empty()) ++head;
    }
  }

 private:
  std::mutex mutex_;
  std::condition_variable changed_;
  std::vector<std::vector<BoucWenFitProgress>> pending_;
  std::vector<bool> done_;
};

// Starting points: the initial values, then perturbed copies; each gets a few iterations and
// the cheapest continues (the first of equals). *best: its scaled parameters, *best_cache: its
// last evaluation. Starts run side by side when the cost leaves threads idle
// (ConcurrentStarts); every start's result is the same as in turn (its point is drawn in start
// order beforehand, its solve does not depend on the thread count).
void RunStarts(const Layout& layout, const std::vector<Series>& data, Eigen::Index n,
               const BoucWenFitOptions& options, bool exact, const FitClock& clock, Work* work,
               std::vector<double>* best, std::shared_ptr<EvaluationCache>* best_cache) {
  const int np = static_cast<int>(layout.free.size());
  const int starts = options.starts;
  internal::PortableRandom random(options.seed);
  std::vector<std::vector<double>> points(static_cast<size_t>(starts), *best);
  for (int k = 1; k < starts; ++k)
    for (int i = 0; i < np; ++i) {
      auto& v = points[static_cast<size_t>(k)][static_cast<size_t>(i)];
      v *= std::exp(options.start_spread * random.Normal());
      v = std::clamp(v, layout.lower[static_cast<size_t>(i)],
                     layout.upper[static_cast<size_t>(i)]);
    }
  const int concurrent = ConcurrentStarts(options, exact, data.size(), np);
  BoucWenFitOptions each = options;
  if (concurrent > 1)
    each.threads = std::max(1, internal::ResolveThreads(options.threads, starts) / concurrent);
  StartReports reports(starts);
  std::mutex mutex;  // guards the rest
  double iterations_so_far = 0;  // Ceres' iterations 0 included: each evaluates a Jacobian
  std::vector<std::unique_ptr<Solved>> solved(static_cast<size_t>(starts));
  std::vector<Work> works(static_cast<size_t>(starts));
  std::vector<std::exception_ptr> errors(static_cast<size_t>(starts));
  std::atomic<int> next{0};
  // No start begins after this (the ones under way finish).
  auto stop = [&] {
    for (int j = next.exchange(starts); j < starts; ++j) reports.Done(j);
  };
  auto run = [&] {
    for (int k; (k = next.fetch_add(1)) < starts;) {
      {
        // A start begins only with one iteration's time (the mean so far) left: Ceres checks
        // the bound between iterations, so a start begun later overruns it by its first
        // Jacobian.
        std::lock_guard<std::mutex> lock(mutex);
        const bool late =
            clock.Bounded() &&
            clock.Remaining() <= (iterations_so_far > 0 ? clock.Elapsed() / iterations_so_far : 0);
        if (late) {
          reports.Done(k);
          stop();  // the final fit says so
          continue;
        }
      }
      BoucWenFitOptions mine = each;
      if (concurrent > 1 && options.on_iteration)
        mine.on_iteration = [&reports, k](const BoucWenFitProgress& p) { reports.Add(k, p); };
      else if (concurrent > 1)
        mine.on_iteration = nullptr;
      try {
        auto s = std::make_unique<Solved>(Solve(layout, data, n, points[static_cast<size_t>(k)],
                                                options.start_iterations, mine, clock, k + 1,
                                                &works[static_cast<size_t>(k)],
                                                std::make_shared<EvaluationCache>()));
        std::lock_guard<std::mutex> lock(mutex);
        iterations_so_far += static_cast<double>(s->summary.iterations.size());
        solved[static_cast<size_t>(k)] = std::move(s);
      } catch (...) {
        errors[static_cast<size_t>(k)] = std::current_exception();
        reports.Done(k);
        stop();
        continue;
      }
      reports.Done(k);
    }
  };
  if (concurrent <= 1) {
    run();
  } else {
    std::vector<std::thread> pool;
    for (int t = 0; t < concurrent; ++t) pool.emplace_back(run);
    reports.Deliver(options.on_iteration);
    for (auto& t : pool) t.join();
  }
  for (int k = 0; k < starts; ++k) {
    const auto& w = works[static_cast<size_t>(k)];
    work->simulations += w.simulations;
    work->sensitivity_passes += w.sensitivity_passes;
  }
  double best_cost = std::numeric_limits<double>::infinity();
  for (int k = 0; k < starts; ++k) {
    if (errors[static_cast<size_t>(k)]) std::rethrow_exception(errors[static_cast<size_t>(k)]);
    const Solved* s = solved[static_cast<size_t>(k)].get();
    if (s && s->summary.final_cost < best_cost && std::isfinite(s->summary.final_cost)) {
      best_cost = s->summary.final_cost;
      *best = s->x;
      *best_cache = s->cache;
    }
  }
}

void ThrowIfFailed(const Solved& s) {
  if (s.summary.termination_type == ceres::FAILURE || !std::isfinite(s.summary.final_cost))
    throw NumericalError("bouc-wen fit failed: " + s.summary.message);
}

// The fixed step's tolerance [m] and the step-doubling estimate at the start [m].
struct FixedStepPlan {
  double tolerance_m = 0;
  double start_estimate_m = 0;
};

// The fixed step checked on the final model: past its tolerance, twice the steps and the fit
// continues from where it is (a fresh evaluation cache: the residuals changed with m). Returns
// the summary's note. The check (a CVODE simulation of every recording) runs only while the
// time bound has not passed: past it, the note says it was skipped (the fit's summary says the
// bound stopped it).
std::string CheckFixedStep(const FixedStepPlan& plan, const BoucWenFitOptions& options,
                           const FitClock& clock, Eigen::Index n, std::vector<Series>* data,
                           Layout* layout, Work* work, Solved* s,
                           std::unique_ptr<ceres::Problem>* owner) {
  for (;;) {
    if (clock.Bounded() && (s->timed_out || clock.Remaining() <= 0))
      return fmt::format(
          "; fixed step: {} steps per sample (step doubling at the start: {:.3g} m RMS, "
          "tolerance {:.3g} m); the final model's check against CVODE skipped: the time bound "
          "max_time_s = {:g} s had passed",
          layout->sim.upsampling, plan.start_estimate_m, plan.tolerance_m, options.max_time_s);
    std::string how;
    const double error_m = internal::bouc_wen_fit::FixedStepCheck(
        MechanicalParameters(layout->Full(s->x.data())), *data, layout->sim, &how);
    const std::string note = fmt::format(
        "; fixed step: {} steps per sample (step doubling at the start: {:.3g} m RMS), the final "
        "model {}: {:.3g} m RMS, tolerance {:.3g} m ({:g} of rms(x))",
        layout->sim.upsampling, plan.start_estimate_m, how, error_m, plan.tolerance_m,
        options.fixed_step_tolerance);
    if (error_m <= plan.tolerance_m) return note;
    if (2 * layout->sim.upsampling > 512)
      throw NumericalError(fmt::format(
          "bouc-wen: the fitted model's fixed step at {} steps per sample differs from CVODE by "
          "{:.3g} m RMS, above its tolerance {:.3g} m; fit with --integrator cvode, or a larger "
          "--step-tolerance",
          layout->sim.upsampling, error_m, plan.tolerance_m));
    SetSubsteps(2 * layout->sim.upsampling, data, layout);
    ceres::Problem* problem = nullptr;
    *s = Solve(*layout, *data, n, s->x, options.max_iterations, options, clock, 0, work,
               std::make_shared<EvaluationCache>(), &problem);
    owner->reset(problem);
    ThrowIfFailed(*s);
  }
}

// Standard errors from s^2 (J^T J)^-1 at the optimum, in physical units (as refine); NaN for
// fixed parameters and when J^T J is singular.
std::vector<double> StandardErrors(const Layout& layout, const Solved& s, Eigen::Index n) {
  const int np = static_cast<int>(layout.free.size());
  std::vector<double> errors(static_cast<size_t>(layout.all.size()),
                             std::numeric_limits<double>::quiet_NaN());
  std::vector<double> r(static_cast<size_t>(n));
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> J(n, np);
  double* jac[] = {J.data()};
  const double* xs[] = {s.x.data()};
  if (!s.cost->Evaluate(xs, r.data(), jac)) return errors;
  const Eigen::MatrixXd JtJ = J.transpose() * J;
  Eigen::FullPivLU<Eigen::MatrixXd> lu(JtJ);
  if (!lu.isInvertible()) return errors;
  const double s2 = 2 * s.summary.final_cost / static_cast<double>(n - np);
  const Eigen::MatrixXd cov = s2 * lu.inverse();
  for (int i = 0; i < np; ++i)
    errors[static_cast<size_t>(layout.free[static_cast<size_t>(i)])] =
        std::sqrt(cov(i, i)) * layout.scale[static_cast<size_t>(i)];
  return errors;
}

// The summary's message: why Ceres stopped, the work done, how the Jacobian was computed, the
// fixed parameters, then `notes`.
std::string FitMessage(BoucWenForm form, const BoucWenFitOptions& options, const Layout& layout,
                       const Solved& s, const Work& work, const char* jacobian_how,
                       const std::string& notes) {
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
  return fmt::format("{} ({} Ceres iterations, {} simulations{}, {} starts, Jacobian by {}){}{}",
                     why, s.summary.iterations.size() - 1, work.simulations,
                     work.sensitivity_passes > 0
                         ? fmt::format(" and {} with sensitivities", work.sensitivity_passes)
                         : std::string(),
                     options.starts, jacobian_how, fixed.empty() ? "" : "; ", fixed) +
         notes;
}

}  // namespace

std::unique_ptr<HysteresisModel> FitBoucWen(BoucWenForm form,
                                            const std::vector<Recording>& recordings,
                                            const BoucWenFitOptions& options,
                                            HysteresisFitSummary* summary) {
  FitClock clock{std::chrono::steady_clock::now(), options.max_time_s};
  options.Validate();
  if (recordings.empty()) throw OptionsError("FitBoucWen: no recordings given", "recordings");
  if (form == BoucWenForm::kPiezo && options.simulation.integrator != BoucWenIntegrator::kCvode &&
      options.simulation.integrator != BoucWenIntegrator::kAuto)
    internal::FailOption("BoucWenFitOptions", "simulation.integrator",
                         options.simulation.integrator == BoucWenIntegrator::kFixedStep
                             ? "fixed-step"
                             : "benchmark-chain",
                         "the chain and the fixed step are the mechanical form's");
  Eigen::Index n = 0;
  std::vector<Series> data = ReadSeries(form, recordings, options, &n);
  Layout layout = internal::bouc_wen_fit::MakeLayout(form, data, options);
  const std::string input_note = ResolveAuto(form, data, &layout);
  ShareCvodeInputs(recordings, layout, &data);
  const bool fixed_step = form == BoucWenForm::kMechanical &&
                          layout.sim.integrator == BoucWenIntegrator::kFixedStep;
  const bool exact = options.jacobian == BoucWenJacobian::kSensitivities &&
                     (form == BoucWenForm::kMechanical ||
                      layout.sim.input != InputInterpolation::kBandLimited);
  FixedStepPlan plan;
  if (fixed_step) {
    double sum = 0;
    for (const auto& s : data) sum += (s.x.array() - s.x.mean()).square().sum();
    plan.tolerance_m = options.fixed_step_tolerance * std::sqrt(sum / static_cast<double>(n));
    SetSubsteps(internal::ChooseFixedSteps(MechanicalParameters(layout.all),
                                           internal::bouc_wen_fit::Inputs(data), layout.sim.input,
                                           plan.tolerance_m, &plan.start_estimate_m),
                &data, &layout);
  }
  const int np = static_cast<int>(layout.free.size());
  if (n <= np)
    throw InputError(fmt::format("FitBoucWen: {} samples for {} free parameters", n, np));
  Work work;
  std::vector<double> best(static_cast<size_t>(np), 1.0);
  auto best_cache = std::make_shared<EvaluationCache>();
  for (int i = 0; i < np; ++i)
    best[static_cast<size_t>(i)] =
        layout.all[layout.free[static_cast<size_t>(i)]] / layout.scale[static_cast<size_t>(i)];
  // Tolerance continuation (BoucWenFitOptions::start_rtol): the starts screen at the looser
  // tolerance; their evaluations are not the final tolerance's, so the final fit begins with a
  // fresh cache. Central differences keep the final tolerance: their step (1e-6 of a parameter)
  // would drown in the looser simulation's error.
  const bool continuation = options.starts > 1 && exact && layout.SimulatedByCvode() &&
                            options.start_rtol > layout.sim.rtol;
  if (options.starts > 1) {
    Layout screen = layout;
    if (continuation) screen.sim.rtol = options.start_rtol;
    RunStarts(screen, data, n, options, exact, clock, &work, &best, &best_cache);
    if (continuation) best_cache = std::make_shared<EvaluationCache>();
  }
  ceres::Problem* problem = nullptr;
  Solved s = Solve(layout, data, n, best, options.max_iterations, options, clock, 0, &work,
                   best_cache, &problem);
  std::unique_ptr<ceres::Problem> owner(problem);
  ThrowIfFailed(s);
  std::string fixed_step_note;
  if (fixed_step)
    fixed_step_note =
        CheckFixedStep(plan, options, clock, n, &data, &layout, &work, &s, &owner);
  const std::string continuation_note =
      continuation ? fmt::format("; the starts screened at CVODE rtol {:g}, the best continued at {:g}",
                                 options.start_rtol, layout.sim.rtol)
                   : std::string();
  const Eigen::VectorXd p = layout.Full(s.x.data());
  auto model = layout.Model(p, StandardErrors(layout, s, n));
  if (summary != nullptr) {
    summary->kind = model->kind();
    summary->samples = static_cast<int>(n);
    summary->training_rms = std::sqrt(2 * s.summary.final_cost / static_cast<double>(n));
    // USER_SUCCESS: the noise floor's stop (bouc_wen_fit_solve.cpp), a convergence.
    summary->converged = s.summary.termination_type == ceres::CONVERGENCE ||
                         s.summary.termination_type == ceres::USER_SUCCESS;
    summary->message = FitMessage(form, options, layout, s, work,
                                  exact ? "forward sensitivities" : "central differences",
                                  input_note + fixed_step_note + continuation_note);
    summary->fit_time_s = clock.Elapsed();
  }
  return model;
}

}  // namespace sysid
