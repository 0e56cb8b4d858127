// sysid::Simulate: the delayed friction model with stick–slip on SUNDIALS CVODE.
//
// The run is a sequence of segments. Inside a segment the friction mode (stuck, sliding +,
// sliding -) and the viscous branch (a1p or a1n, the sign of v(t - tau)) are frozen, so the
// right-hand side is smooth and CVODE's high-order methods apply (segment_model.hpp). A
// segment ends
//  - at a stop time (timeline.hpp): an input edge, t0 + k tau, or an event time + k tau
//    (a jump of v' at t_e reappears in v'' at t_e + tau, in v''' at t_e + 2 tau, ...);
//  - at a root (CVodeRootInit, with directions): v = 0 while sliding, F = a2p or F = -a2n
//    while stuck, v(t - tau) = 0 where a1 switches.
// The next mode is chosen from the right-hand limit and CVODE is re-initialised. Delayed
// values come from DelayHistory (our own store of every accepted step's polynomial); steps are
// bounded by tau so that t - tau never lies beyond the last accepted step.
//
// Simulator::Run is the segment loop; each of its steps is a member function below, in the
// order a segment goes through them.
// Long file: the segment loop, its stop times and its mode switches share the CVODE state;
// split, each part would reach into the others' internals.
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "core/cvode_solver.hpp"
#include "core/option_rule.hpp"
#include "simulate/output_sampler.hpp"
#include "simulate/segment_model.hpp"
#include "simulate/timeline.hpp"
#include "sysid/error.hpp"
#include "sysid/simulate.hpp"

namespace sysid {
namespace {

using internal::CvodeSolver;
using internal::kNumRoots;
using internal::OutputSampler;
using internal::SegmentModel;
using internal::SignTimeline;
using internal::StepPolynomial;
using internal::StopTimes;
using internal::TimeEps;

int Sign(double x) { return (x > 0) - (x < 0); }

/// Where a segment's integration stopped: CVODE's flag (root, stop time) and the time.
struct SegmentEnd {
  int flag;
  double t_s;
};

/// One Simulate call: the state carried from segment to segment and the named steps of a
/// segment. Everything lives here (no globals), so concurrent simulations are independent.
class Simulator {
 public:
  Simulator(const FrictionModel& model, const InputSignal& input, const SimulationOptions& o)
      : o_(o),
        input_(input),
        tau_(model.tau_s),
        t_end_(o.t_end_s),
        out_(o, &result_.trajectory),
        p_(model, input, o),
        stops_(input, o, tau_),
        signs_(Sign(o.history_v_mps)),
        cv_(2, o.method == IntegratorMethod::kBdf ? CvodeSolver::Method::kBdf
                                                  : CvodeSolver::Method::kAdams,
            &SegmentModel::Rhs, &p_, o.t0_s, std::array<double, 2>{o.x0_m, o.v0_mps}.data(),
            "simulate"),
        t_(o.t0_s),
        x_(o.x0_m),
        v_(o.v0_mps),
        last_branch_(Sign(o.history_v_mps)) {
    // Steps are at most tau long and rarely shorter than tau / 4 on long runs.
    if (tau_ > 0 && std::isfinite(t_end_))
      p_.history.Reserve(static_cast<std::size_t>(std::min(1e6, 4 * (t_end_ - o.t0_s) / tau_)));
    ConfigureCvode();
  }

  SimulationResult Run() {
    StartMode();
    IntegrateToEnd(false);
    Finish();
    return std::move(result_);
  }

  /// The stepped plant (FrictionModelPlant): the run continues to `t_target`, a hard stop
  /// (the next sample), under the input known so far, and returns x there. The decision at
  /// t_target (stick, slip, restart) needs the input from t_target on, which the next sample's
  /// voltage sets: it is deferred to the next call. Throws NumericalError when the run stops.
  double Advance(double t_target) {
    stops_.AddHardStop(t_target);
    t_end_ = t_target;
    if (!started_) {
      StartMode();
      started_ = true;
    } else if (pending_end_) {
      EndSegment(*pending_end_);
      pending_end_.reset();
    } else if (pending_decision_) {
      pending_decision_ = false;
      ChangeMode(p_.Decide(p_.Force(t_, 0.0)));
    }
    IntegrateToEnd(true);
    if (!usable())
      throw NumericalError("the friction model plant: " + result_.summary.message);
    return x_;
  }
  /// A jump of the stepped plant's input at t: its breakpoints t + k tau.
  void AddEdge(double t_s) { stops_.AddBreakpoints(t_s); }
  /// The stepped plant never looks back beyond t - tau: the older history goes.
  void ForgetBefore(double t_s) { p_.history.ForgetBefore(t_s); }
  double velocity_mps() const { return v_; }
  long events() const { return static_cast<long>(result_.events.size()); }

 private:
  bool usable() const { return result_.summary.IsSolutionUsable(); }

  /// Integrates segment by segment up to t_end_ (or a failure). `stepped` (Advance): a segment
  /// ending at t_end_, or a stuck stretch reaching it, leaves its decision to the next call
  /// (pending_end_, pending_decision_), which knows the input from t_end_ on.
  void IntegrateToEnd(bool stepped) {
    while (usable()) {
      SnapOntoStops();
      if (!usable()) break;
      BeginSegment();
      EmitReached();
      if (t_ >= t_end_ - TimeEps(t_end_)) break;
      if (SkipStuckStretch()) {
        if (stepped && pending_decision_) break;
        continue;
      }
      const SegmentEnd end = IntegrateSegment();
      if (!usable()) break;
      if (stepped && end.t_s >= t_end_ - TimeEps(t_end_)) {
        pending_end_ = end;
        t_ = end.t_s;
        x_ = cv_.state()[0];
        v_ = p_.mode == 0 ? 0.0 : cv_.state()[1];
        break;
      }
      EndSegment(end);
    }
  }

  /// Tolerances, the root functions, the method's order cap and the step bound: tau keeps
  /// v(t - tau) in the accepted past (the history never has to extrapolate), the input may
  /// ask for less.
  void ConfigureCvode() {
    cv_.SetTolerances(o_.rtol, o_.atol);
    cv_.SetRoots(kNumRoots, &SegmentModel::Roots);
    if (o_.max_order > 0 || o_.method == IntegratorMethod::kAdams)
      cv_.SetMaxOrder(o_.max_order > 0 ? o_.max_order : 6);
    double h_max = std::numeric_limits<double>::infinity();
    if (tau_ > 0) h_max = tau_;
    if (o_.max_step_s > 0) h_max = std::min(h_max, o_.max_step_s);
    h_max = std::min(h_max, input_.MaxStepHint());
    if (std::isfinite(h_max)) cv_.SetMaxStep(h_max);
    if (o_.method == IntegratorMethod::kBdf) cv_.SetJacobian(&SegmentModel::Jacobian);
  }

  /// The initial mode: the sign of v0, or the stick–slip rule at rest (a release at t0 is an
  /// event like any other).
  void StartMode() {
    p_.mode = v_ != 0 ? Sign(v_) : p_.Decide(p_.Force(t_, v_));
    if (v_ == 0 && p_.mode != 0)
      LogEvent(p_.mode > 0 ? EventKind::kSlipForward : EventKind::kSlipBackward);
    signs_.Set(t_, p_.mode);
  }

  /// Stops within TimeEps are this instant: move onto them exactly (a Taylor step of < 1e-12 s)
  /// so that u is read on the right side of an edge; an edge may release a stuck stage here.
  void SnapOntoStops() {
    next_stop_ = stops_.Next(t_);
    while (next_stop_ <= t_ + TimeEps(t_)) {
      const double dt = next_stop_ - t_;
      x_ += dt * v_ + 0.5 * dt * dt * p_.Acceleration(t_, v_);
      v_ += dt * p_.Acceleration(t_, v_);
      t_ = next_stop_;
      next_stop_ = stops_.Next(t_);
      restart_ = true;
      if (p_.mode == 0) {
        ChangeMode(p_.Decide(p_.Force(t_, 0.0)));
        next_stop_ = stops_.Next(t_);
      }
    }
  }

  /// Freezes the segment's mode, viscous branch (from the right-hand limit of v(t - tau): a
  /// change of branch is the a1-switch event) and input.
  void BeginSegment() {
    if (p_.mode == 0) v_ = 0.0;
    p_.branch = signs_.RightOf(t_ - tau_);
    if (p_.branch != 0) {
      if (last_branch_ != 0 && p_.branch != last_branch_) LogEvent(EventKind::kViscousSwitch);
      last_branch_ = p_.branch;
    }
    p_.Freeze();
    p_.u_held = input_.ConstantBetweenEdges();
    p_.u_seg = input_.Value(t_);
    p_.t_last_inside = std::nextafter(next_stop_, -std::numeric_limits<double>::infinity());
  }

  /// Samples at or before the segment's start take its state (they were not inside a step).
  void EmitReached() {
    while (out_.pending() && out_.next() <= t_) Emit(out_.next(), t_, x_, v_);
  }

  /// Stuck under a held input with v(t - tau) = 0 all along: F is constant, so nothing can
  /// happen before the next stop time. Skips there exactly (x and v = 0 do not change) and
  /// returns true; false when the segment must be integrated.
  bool SkipStuckStretch() {
    if (!(p_.mode == 0 && input_.ConstantBetweenEdges() &&
          (tau_ == 0 || signs_.ZeroOn(t_ - tau_, next_stop_ - tau_))))
      return false;
    p_.history.AppendConstant(next_stop_, 0.0);
    while (out_.pending() && out_.next() < next_stop_) Emit(out_.next(), out_.next(), x_, 0.0);
    t_ = next_stop_;
    restart_ = true;
    if (stepping_ && t_ >= t_end_ - TimeEps(t_end_))
      pending_decision_ = true;  // the input from t_ on is the next sample's (Advance)
    else
      ChangeMode(p_.Decide(p_.Force(t_, 0.0)));
    return true;
  }

  /// Integrates the segment step by step up to its stop time or a root. Each step goes into the
  /// delay history and gives the samples inside it. A failure is recorded (Fail), not thrown.
  SegmentEnd IntegrateSegment() {
    double* y = cv_.state();
    y[0] = x_;
    y[1] = v_;
    if (restart_) {
      cv_.ReInit(t_);
      if (!first_segment_) ++result_.summary.reinitialisations;
      first_segment_ = false;
    }
    cv_.SetStopTime(next_stop_);
    int directions[kNumRoots] = {-p_.mode, 1, -1, -p_.branch};
    cv_.SetRootDirections(directions);

    SegmentEnd end{CV_SUCCESS, t_};
    while (true) {
      if (steps_ >= o_.max_steps) {
        Fail("CV_TOO_MUCH_WORK",
             fmt::format("step budget SimulationOptions::max_steps = {} exhausted at t = {:.9g} s",
                         o_.max_steps, end.t_s),
             end.t_s);
        break;
      }
      end.flag = cv_.Advance(next_stop_, &end.t_s, CV_ONE_STEP);
      if (end.flag < 0) {
        Fail(CvodeSolver::FlagName(end.flag), cv_.Describe(end.flag, "CVode"), cv_.CurrentTime());
        break;
      }
      ++steps_;
      StoreStep(end);
      EmitInsideStep(end.t_s);
      if (end.flag == CV_ROOT_RETURN || end.flag == CV_TSTOP_RETURN || end.t_s >= next_stop_)
        break;
    }
    return end;
  }

  /// The accepted step's polynomial (Taylor coefficients at tn in theta = (t - tn) / hu) into
  /// the delay history; a stuck step is an exact zero piece.
  void StoreStep(const SegmentEnd& end) {
    double tn = 0, hu = 0;
    int q = 0;
    CVodeGetCurrentTime(cv_.mem(), &tn);
    CVodeGetLastStep(cv_.mem(), &hu);
    CVodeGetLastOrder(cv_.mem(), &q);
    step_.tn = tn;
    step_.hu = hu;
    const double piece_end = std::min(end.t_s, tn);
    if (p_.mode == 0) {
      step_.order = 0;
      step_.x[0] = cv_.state()[0];
      step_.v[0] = 0.0;
      p_.history.AppendConstant(piece_end, 0.0);
      return;
    }
    step_.order = q;
    // The step's Taylor coefficients hu^k / k! y^(k)(tn) are CVODE's Nordsieck vectors z_k (its
    // h is hu until the next step starts): read them directly instead of calling CVodeGetDky
    // q + 1 times (each a linear combination of up to q + 1 vectors and a power; together
    // about a fifth of the batch's profile). They are formed with Dky's arithmetic,
    // (k! z_k) / hu^k * hu^k / k!, so that results stay bit-identical: a rounding change in
    // the history moves CVODE's step choices downstream (2498 -> 2501 steps on the paper's
    // pulse train, same accuracy).
    const double* const* z = cv_.Nordsieck(q);
    double scale = 1.0, factorial = 1.0, power = 1.0;  // hu^k / k!, k!, hu^k
    for (int k = 0; k <= q; ++k) {
      if (k > 0) {
        factorial *= k;
        power *= hu;
      }
      if (z) {
        const double inverse_power = 1.0 / power;
        step_.x[k] = factorial * z[k][0] * inverse_power * scale;
        step_.v[k] = factorial * z[k][1] * inverse_power * scale;
      } else {
        const double* d = cv_.Dky(tn, k);
        step_.x[k] = d[0] * scale;
        step_.v[k] = d[1] * scale;
      }
      scale *= hu / (k + 1);
    }
    p_.history.AppendPolynomial(piece_end, tn, hu, step_.v, q);
  }

  /// Samples inside the step just taken (and at its end when it ends the run).
  void EmitInsideStep(double t_reached) {
    const bool final_piece = t_reached >= t_end_ - TimeEps(t_end_);
    while (out_.pending()) {
      const double ts = out_.next();
      if (!(ts < t_reached || (final_piece && ts <= t_reached))) break;
      double xs = 0, vs = 0;
      step_.Evaluate(ts, &xs, &vs);
      Emit(ts, ts, xs, vs);
    }
  }

  /// At the segment's end: the right-hand limit and the next mode. A sliding stage at v = 0
  /// sticks or slides on (reverse); a stuck one is released by the root that fired (its
  /// direction says which, so round-off in F cannot undo it) or by the input's new value at a
  /// stop time. Only a soft stop with nothing changed lets CVODE keep its history and order.
  void EndSegment(const SegmentEnd& end) {
    const double* y = cv_.state();
    t_ = end.t_s;
    x_ = y[0];
    v_ = p_.mode == 0 ? 0.0 : y[1];
    int found[kNumRoots] = {0, 0, 0, 0};
    if (end.flag == CV_ROOT_RETURN) cv_.GetRootInfo(found);
    int new_mode = p_.mode;
    if (found[0] != 0) {
      v_ = 0.0;
      new_mode = p_.Decide(p_.Force(t_, 0.0));
    } else if (found[1] != 0) {
      new_mode = 1;
    } else if (found[2] != 0) {
      new_mode = -1;
    } else if (p_.mode == 0) {
      new_mode = p_.Decide(p_.Force(t_, 0.0));
    }
    restart_ = end.flag == CV_ROOT_RETURN || new_mode != p_.mode || stops_.IsHard(t_);
    ChangeMode(new_mode);
  }

  /// A mode change at t: log it, remember the new sign of v, and make t + k tau breakpoints
  /// (the jump of v' recurs in higher derivatives there). Many changes at one instant are
  /// chattering (Zeno behaviour): the run stops rather than loop.
  void ChangeMode(int new_mode) {
    if (new_mode == p_.mode) return;
    EventKind kind = EventKind::kStick;
    if (new_mode != 0)
      kind = p_.mode != 0 ? EventKind::kReverse
                          : (new_mode > 0 ? EventKind::kSlipForward : EventKind::kSlipBackward);
    LogEvent(kind);
    events_here_ = t_ - last_event_t_ <= TimeEps(t_) ? events_here_ + 1 : 0;
    last_event_t_ = t_;
    if (events_here_ > 8)
      Fail("CHATTERING",
           fmt::format("more than 8 stick/slip mode changes at t = {:.9g} s (Zeno behaviour)", t_),
           t_);
    p_.mode = new_mode;
    signs_.Set(t_, new_mode);
    stops_.AddBreakpoints(t_);
  }

  void LogEvent(EventKind kind) { result_.events.push_back({t_, kind}); }

  /// One output sample at ts (labelled t_label); a is the model's v', the right limit.
  void Emit(double t_label, double ts, double xs, double vs) {
    out_.Add(t_label, input_.Value(ts), xs, vs, p_.Acceleration(ts, vs));
  }

  /// The run stops: kBudgetExhausted for CV_TOO_MUCH_WORK, kFailure for anything else.
  void Fail(const std::string& flag, const std::string& message, double t_fail) {
    SimulationSummary& s = result_.summary;
    s.termination =
        flag == "CV_TOO_MUCH_WORK" ? Termination::kBudgetExhausted : Termination::kFailure;
    s.cvode_flag = flag;
    s.failure_time_s = t_fail;
    s.message = message;
  }

  /// Counters into the summary; after a failure only the samples reached are kept.
  void Finish() {
    SimulationSummary& s = result_.summary;
    const internal::CvodeCounters c = cv_.Counters();
    s.steps = steps_;
    s.rhs_evaluations = c.rhs_evaluations;
    s.root_evaluations = c.root_evaluations;
    s.events = static_cast<long>(result_.events.size());
    out_.KeepReached();
    if (usable()) s.message = "reached t_end";
  }

  const SimulationOptions& o_;
  const InputSignal& input_;
  const double tau_;
  double t_end_;  // [s] the run's end; the stepped plant's next sample
  SimulationResult result_;
  OutputSampler out_;
  SegmentModel p_;
  StopTimes stops_;
  SignTimeline signs_;
  CvodeSolver cv_;
  StepPolynomial step_;
  double t_, x_, v_;                  // [s], [m], [m/s] the state at the segment boundary
  double next_stop_ = 0;              // [s] the current segment's end
  bool restart_ = true;               // CVODE must be re-initialised at the next segment start
  bool first_segment_ = true;         // the first ReInit is no restart
  int last_branch_;                   // last nonzero viscous branch (for a1-switch events)
  int events_here_ = 0;               // mode changes at one instant: guards against chattering
  double last_event_t_ = -std::numeric_limits<double>::infinity();
  long steps_ = 0;
  // The stepped plant (Advance): its state between samples.
  bool stepping_ = !std::isfinite(o_.t_end_s);
  bool started_ = false;
  bool pending_decision_ = false;
  std::optional<SegmentEnd> pending_end_;
};

/// The stepped plant's input: a zero-order hold whose rows arrive one sample at a time.
class GrowingHoldInput final : public InputSignal {
 public:
  void Append(double t_s, double u_v) {
    t_.push_back(t_s);
    u_.push_back(u_v);
  }
  double Value(double t_s) const override {
    if (u_.empty()) return 0.0;
    if (t_s >= t_.back()) return u_.back();
    const auto it = std::upper_bound(t_.begin(), t_.end(), t_s);
    return it == t_.begin() ? u_.front() : u_[static_cast<std::size_t>(it - t_.begin()) - 1];
  }
  std::vector<double> Edges(double, double) const override { return {}; }
  bool ConstantBetweenEdges() const override { return true; }
  /// Drops the rows before the one in force at t (nothing reads u before the current sample),
  /// once they outnumber the kept ones.
  void ForgetBefore(double t_s) {
    const auto it = std::upper_bound(t_.begin(), t_.end(), t_s);
    const std::size_t keep_from = it == t_.begin() ? 0 : static_cast<std::size_t>(it - t_.begin()) - 1;
    if (keep_from < 1024 || 2 * keep_from < t_.size()) return;
    t_.erase(t_.begin(), t_.begin() + static_cast<std::ptrdiff_t>(keep_from));
    u_.erase(u_.begin(), u_.begin() + static_cast<std::ptrdiff_t>(keep_from));
  }

 private:
  std::vector<double> t_, u_;
};

/// The options of a stepped run: t_end = +inf marks it (the stops are added sample by sample),
/// one output sample at t0 (the plant reads the state, not a trajectory).
SimulationOptions SteppedOptions(SimulationOptions o) {
  o.t_end_s = o.t0_s + 1;  // for Validate only
  o.output_times_s.clear();
  o.Validate();
  o.t_end_s = std::numeric_limits<double>::infinity();
  o.output_times_s = {o.t0_s};
  return o;
}

}  // namespace

class FrictionModelPlant::Impl {
 public:
  Impl(const FrictionModel& model, double sample_time_s, const SimulationOptions& options)
      : model_(Checked(model, sample_time_s)),
        options_(SteppedOptions(options)),
        ts_(sample_time_s),
        simulator_(model_, input_, options_),
        x_(options.x0_m) {}

  double Step(double u_v) {
    if (!std::isfinite(u_v))
      throw OptionsError("FrictionModelPlant::Step: u = " + std::to_string(u_v) +
                         " V is not finite");
    const double t_k = time_s();
    if (k_ > 0 && u_v != last_u_) simulator_.AddEdge(t_k);
    input_.Append(t_k, u_v);
    last_u_ = u_v;
    ++k_;
    x_ = simulator_.Advance(time_s());
    // Bounded memory on long runs: v(t - tau) is read at t_k - tau at the earliest.
    simulator_.ForgetBefore(t_k - model_.tau_s - ts_);
    input_.ForgetBefore(t_k);
    return x_;
  }
  double time_s() const { return options_.t0_s + static_cast<double>(k_) * ts_; }
  double position_m() const { return x_; }
  double velocity_mps() const { return simulator_.velocity_mps(); }
  long events() const { return simulator_.events(); }

 private:
  static const FrictionModel& Checked(const FrictionModel& model, double sample_time_s) {
    model.Validate();
    if (!(sample_time_s > 0) || !std::isfinite(sample_time_s))
      internal::FailOption("FrictionModelPlant", "sample_time_s",
                           fmt::format("{} s", sample_time_s), "finite, > 0");
    return model;
  }

  FrictionModel model_;
  SimulationOptions options_;
  double ts_;
  GrowingHoldInput input_;
  Simulator simulator_;
  long k_ = 0;
  double x_ = 0, last_u_ = 0;
};

FrictionModelPlant::FrictionModelPlant(const FrictionModel& model, double sample_time_s,
                                       const SimulationOptions& options)
    : impl_(std::make_unique<Impl>(model, sample_time_s, options)) {}
FrictionModelPlant::~FrictionModelPlant() = default;
FrictionModelPlant::FrictionModelPlant(FrictionModelPlant&&) noexcept = default;
FrictionModelPlant& FrictionModelPlant::operator=(FrictionModelPlant&&) noexcept = default;
double FrictionModelPlant::Step(double u_v) { return impl_->Step(u_v); }
double FrictionModelPlant::position_m() const { return impl_->position_m(); }
double FrictionModelPlant::velocity_mps() const { return impl_->velocity_mps(); }
double FrictionModelPlant::time_s() const { return impl_->time_s(); }
long FrictionModelPlant::events() const { return impl_->events(); }

SimulationResult Simulate(const FrictionModel& model, const InputSignal& input,
                          const SimulationOptions& options) {
  const auto wall_start = std::chrono::steady_clock::now();
  model.Validate();
  options.Validate();
  SimulationResult result = Simulator(model, input, options).Run();
  result.summary.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  return result;
}

}  // namespace sysid
