// sysid::Simulate: the delayed friction model with stick–slip on SUNDIALS CVODE.
//
// The run is a sequence of segments. Inside a segment the friction mode (stuck, sliding +,
// sliding -) and the viscous branch (a1p or a1n, the sign of v(t - tau)) are frozen, so the
// right-hand side is smooth and CVODE's high-order methods apply. A segment ends
//  - at a stop time (CVodeSetStopTime): an input edge, t0 + k tau, or an event time + k tau
//    (a jump of v' at t_e reappears in v'' at t_e + tau, in v''' at t_e + 2 tau, ...);
//  - at a root (CVodeRootInit, with directions): v = 0 while sliding, F = a2p or F = -a2n
//    while stuck, v(t - tau) = 0 where a1 switches.
// The next mode is chosen from the right-hand limit and CVODE is re-initialised. Delayed
// values come from DelayHistory (our own store of every accepted step's polynomial); steps are
// bounded by tau so that t - tau never lies beyond the last accepted step.
#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunnonlinsol/sunnonlinsol_fixedpoint.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <limits>
#include <queue>
#include <string>
#include <vector>

#include "simulate/delay_history.hpp"
#include "sysid/error.hpp"
#include "sysid/simulate.hpp"

namespace sysid {
namespace {

using internal::DelayHistory;

constexpr int kNumRoots = 4;  // v = 0, F - a2p, F + a2n, v(t - tau)
constexpr int kMaxOrder = 12;

/// Times closer than this are one instant: CVODE locates roots to ~100 ulp of t, far below it.
double TimeEps(double t) { return 1e-12 * std::max(1.0, std::abs(t)); }

int Sign(double x) { return (x > 0) - (x < 0); }

/// Everything the CVODE callbacks need; one per Simulate call (no globals: thread-safe).
struct Problem {
  const FrictionModel& model;
  const InputSignal& input;
  double tau;
  DelayHistory history;
  int mode = 0;    // friction mode: +1 sliding forward, -1 backward, 0 stuck
  int branch = 0;  // sign of v(t - tau) on this segment: selects a1 (0: v(t - tau) = 0)
  double a1 = 0;   // [1/s] the frozen viscous coefficient
  double a2 = 0;   // [m/s^2] signed Coulomb term: a2p (mode +1), -a2n (mode -1)
  // The segment's input. CVODE evaluates f at the segment's end point, where a right-continuous
  // u has already jumped: inside a segment u is read at most just left of its end.
  bool u_held = false;       // u constant on the segment (zero-order hold): u_seg
  double u_seg = 0;          // [V]
  double t_last_inside = 0;  // [s] largest double below the segment's end
  std::string cvode_message;

  Problem(const FrictionModel& m, const InputSignal& in, const SimulationOptions& o)
      : model(m), input(in), tau(m.tau_s), history(o.t0_s, o.history_v_mps, o.v0_mps) {}

  /// v(t - tau); with tau = 0 that is the current velocity.
  double DelayedV(double t, double v) const { return tau > 0 ? history.Value(t - tau) : v; }

  /// Driving force per mass F = a3 u(t) - a1 v(t - tau) [m/s^2], a1 by the actual sign.
  double Force(double t, double v) const {
    const double vd = DelayedV(t, v);
    return model.a3 * input.Value(t) - (vd > 0 ? model.a1p : model.a1n) * vd;
  }

  /// The stick–slip rule at v = 0.
  int Decide(double force) const {
    if (force > model.a2p) return 1;
    if (force < -model.a2n) return -1;
    return 0;
  }

  /// u inside the current segment (left limit at its end).
  double SegmentU(double t) const {
    return u_held ? u_seg : input.Value(std::min(t, t_last_inside));
  }

  /// v' in the frozen mode and branch.
  double Acceleration(double t, double v) const {
    if (mode == 0) return 0.0;
    return model.a3 * SegmentU(t) - a1 * DelayedV(t, v) - a2;
  }

  void Freeze() {
    a1 = branch < 0 ? model.a1n : model.a1p;
    a2 = mode > 0 ? model.a2p : (mode < 0 ? -model.a2n : 0.0);
  }
};

int Rhs(sunrealtype t, N_Vector y, N_Vector ydot, void* user_data) {
  auto* p = static_cast<Problem*>(user_data);
  const sunrealtype* yv = N_VGetArrayPointer(y);
  sunrealtype* d = N_VGetArrayPointer(ydot);
  // Stuck: x' = v = 0 exactly, not the solver's v (which may carry round-off).
  d[0] = p->mode == 0 ? 0.0 : yv[1];
  d[1] = p->Acceleration(t, yv[1]);
  return std::isfinite(d[1]) ? 0 : -1;
}

int Roots(sunrealtype t, N_Vector y, sunrealtype* g, void* user_data) {
  auto* p = static_cast<Problem*>(user_data);
  const double v = N_VGetArrayPointer(y)[1];
  const double vd = p->DelayedV(t, v);
  const double force = p->model.a3 * p->SegmentU(t) - p->a1 * vd;
  // Inactive functions are a nonzero constant: CVODE then never reports them.
  g[0] = p->mode != 0 ? v : 1.0;
  g[1] = p->mode == 0 ? force - p->model.a2p : 1.0;
  g[2] = p->mode == 0 ? force + p->model.a2n : 1.0;
  g[3] = p->branch != 0 ? vd : 1.0;
  return 0;
}

int Jacobian(sunrealtype, N_Vector, N_Vector, SUNMatrix J, void* user_data, N_Vector, N_Vector,
             N_Vector) {
  auto* p = static_cast<Problem*>(user_data);
  SUNMatZero(J);
  if (p->mode != 0) {
    SM_ELEMENT_D(J, 0, 1) = 1.0;
    // Only with tau = 0 does v' depend on the current v; otherwise v(t - tau) is history.
    SM_ELEMENT_D(J, 1, 1) = p->tau > 0 ? 0.0 : -p->a1;
  }
  return 0;
}

void ErrorHandler(int error_code, const char* module, const char* function, char* msg,
                  void* eh_data) {
  if (error_code >= 0) return;  // warnings (e.g. t + h = t) do not stop the run
  auto* p = static_cast<Problem*>(eh_data);
  p->cvode_message = std::string(module) + "::" + function + ": " + msg;
}

/// Owns the SUNDIALS objects of one run.
struct Cvode {
  SUNContext ctx = nullptr;
  N_Vector y = nullptr, work = nullptr;
  void* mem = nullptr;
  SUNMatrix matrix = nullptr;
  SUNLinearSolver linear = nullptr;
  SUNNonlinearSolver fixed_point = nullptr;
  ~Cvode() {
    if (mem) CVodeFree(&mem);
    if (fixed_point) SUNNonlinSolFree(fixed_point);
    if (linear) SUNLinSolFree(linear);
    if (matrix) SUNMatDestroy(matrix);
    if (work) N_VDestroy(work);
    if (y) N_VDestroy(y);
    if (ctx) SUNContext_Free(&ctx);
  }
};

/// CVODE's name for a return flag (CVodeGetReturnFlagName allocates; the caller frees).
std::string FlagName(int flag) {
  char* name = CVodeGetReturnFlagName(flag);
  std::string result = name ? name : "CV_UNKNOWN";
  std::free(name);
  return result;
}

void Check(int flag, const char* call) {
  if (flag < 0) throw InternalError(std::string(call) + " failed: " + FlagName(flag));
}

std::vector<double> OutputTimes(const SimulationOptions& o) {
  if (!o.output_times_s.empty()) return o.output_times_s;
  const auto n = static_cast<long>(std::floor((o.t_end_s - o.t0_s) / o.dt_out_s * (1 + 1e-12)));
  std::vector<double> t(static_cast<size_t>(n + 1));
  for (long k = 0; k <= n; ++k)
    t[static_cast<size_t>(k)] = std::min(o.t0_s + static_cast<double>(k) * o.dt_out_s, o.t_end_s);
  return t;
}

/// The times where CVODE must stop. Hard stops (input edges, t_end) are jumps of u: CVODE
/// restarts there. Soft stops (breakpoints t_e + k tau) are kinks of f or of its derivatives:
/// landing a step exactly on them is enough, CVODE's error control handles the rest.
class StopTimes {
 public:
  StopTimes(std::vector<double> hard, std::vector<double> soft)
      : hard_(std::move(hard)), soft_(std::move(soft)) {
    std::sort(hard_.begin(), hard_.end());
    std::sort(soft_.begin(), soft_.end());
  }
  void AddSoft(double t) { dynamic_.push(t); }
  bool IsHard(double t) const { return std::binary_search(hard_.begin(), hard_.end(), t); }
  /// Smallest stop time > t (+inf when none is left).
  double Next(double t) {
    while (next_hard_ < hard_.size() && hard_[next_hard_] <= t) ++next_hard_;
    while (next_soft_ < soft_.size() && soft_[next_soft_] <= t) ++next_soft_;
    while (!dynamic_.empty() && dynamic_.top() <= t) dynamic_.pop();
    double next = std::numeric_limits<double>::infinity();
    if (next_hard_ < hard_.size()) next = hard_[next_hard_];
    if (next_soft_ < soft_.size()) next = std::min(next, soft_[next_soft_]);
    if (!dynamic_.empty()) next = std::min(next, dynamic_.top());
    return next;
  }

 private:
  std::vector<double> hard_, soft_;
  size_t next_hard_ = 0, next_soft_ = 0;
  std::priority_queue<double, std::vector<double>, std::greater<>> dynamic_;
};

/// Sign of v on the right of each time (history before t0, then one entry per mode change).
class SignTimeline {
 public:
  SignTimeline(double t0, int history_sign)
      : t_{-std::numeric_limits<double>::infinity()}, sign_{history_sign} {
    (void)t0;
  }
  void Set(double t, int sign) {
    if (sign == sign_.back()) return;
    t_.push_back(t);
    sign_.push_back(sign);
  }
  /// Sign of v just right of s (entries within TimeEps of s count as reached).
  int RightOf(double s) const {
    const auto it = std::upper_bound(t_.begin(), t_.end(), s + TimeEps(s));
    return sign_[static_cast<size_t>(it - t_.begin()) - 1];
  }
  /// True when v = 0 throughout [a, b].
  bool ZeroOn(double a, double b) const {
    const auto first = std::upper_bound(t_.begin(), t_.end(), a + TimeEps(a));
    const auto last = std::upper_bound(t_.begin(), t_.end(), b);
    if (sign_[static_cast<size_t>(first - t_.begin()) - 1] != 0) return false;
    for (auto it = first; it != last; ++it)
      if (sign_[static_cast<size_t>(it - t_.begin())] != 0) return false;
    return true;
  }

 private:
  std::vector<double> t_;
  std::vector<int> sign_;
};

}  // namespace

SimulationResult Simulate(const FrictionModel& model, const InputSignal& input,
                          const SimulationOptions& options) {
  model.Validate();
  options.Validate();
  const auto wall_start = std::chrono::steady_clock::now();
  const SimulationOptions& o = options;
  const double tau = model.tau_s;
  const double t_end = o.t_end_s;

  SimulationResult result;
  SimulationSummary& summary = result.summary;
  const std::vector<double> t_out = OutputTimes(o);
  const Eigen::Index n_out = static_cast<Eigen::Index>(t_out.size());
  Trajectory& tr = result.trajectory;
  tr.t_s.resize(n_out);
  tr.u_v.resize(n_out);
  tr.x_m.resize(n_out);
  tr.v_mps.resize(n_out);
  tr.a_mps2.resize(n_out);
  Eigen::Index next_out = 0;

  Problem p(model, input, o);
  // Steps are at most tau long and rarely shorter than tau / 4 on long runs.
  if (tau > 0) p.history.Reserve(static_cast<size_t>(std::min(1e6, 4 * (t_end - o.t0_s) / tau)));

  // Stop times: input edges and t_end (hard); every source of a v' jump (edges, t0) + k tau.
  std::vector<double> hard = input.Edges(o.t0_s, t_end);
  hard.push_back(t_end);
  std::vector<double> soft;
  if (tau > 0) {
    std::vector<double> sources = hard;
    sources.back() = o.t0_s;
    for (double ts : sources)
      for (int k = 1; k <= o.breakpoint_order; ++k)
        if (ts + k * tau < t_end) soft.push_back(ts + k * tau);
  }
  StopTimes stops(std::move(hard), std::move(soft));

  // Step bound: tau keeps v(t - tau) in the accepted past; the input may ask for less.
  double h_max = std::numeric_limits<double>::infinity();
  if (tau > 0) h_max = tau;
  if (o.max_step_s > 0) h_max = std::min(h_max, o.max_step_s);
  h_max = std::min(h_max, input.MaxStepHint());

  Cvode cv;
  Check(SUNContext_Create(nullptr, &cv.ctx), "SUNContext_Create");
  cv.y = N_VNew_Serial(2, cv.ctx);
  // Fused vector operations: one call per linear combination instead of one per term (CVODE's
  // Nordsieck updates and CVodeGetDky are linear combinations of up to 13 vectors).
  Check(N_VEnableFusedOps_Serial(cv.y, SUNTRUE), "N_VEnableFusedOps_Serial");
  cv.work = N_VClone(cv.y);
  sunrealtype* y = N_VGetArrayPointer(cv.y);
  y[0] = o.x0_m;
  y[1] = o.v0_mps;
  cv.mem = CVodeCreate(o.method == IntegratorMethod::kBdf ? CV_BDF : CV_ADAMS, cv.ctx);
  if (!cv.mem) throw InternalError("CVodeCreate failed");
  Check(CVodeInit(cv.mem, Rhs, o.t0_s, cv.y), "CVodeInit");
  Check(CVodeSetErrHandlerFn(cv.mem, ErrorHandler, &p), "CVodeSetErrHandlerFn");
  Check(CVodeSStolerances(cv.mem, o.rtol, o.atol), "CVodeSStolerances");
  Check(CVodeSetUserData(cv.mem, &p), "CVodeSetUserData");
  Check(CVodeRootInit(cv.mem, kNumRoots, Roots), "CVodeRootInit");
  Check(CVodeSetNoInactiveRootWarn(cv.mem), "CVodeSetNoInactiveRootWarn");
  if (o.max_order > 0 || o.method == IntegratorMethod::kAdams)
    Check(CVodeSetMaxOrd(cv.mem, o.max_order > 0 ? o.max_order : 6), "CVodeSetMaxOrd");
  if (std::isfinite(h_max)) Check(CVodeSetMaxStep(cv.mem, h_max), "CVodeSetMaxStep");
  if (o.method == IntegratorMethod::kBdf) {
    cv.matrix = SUNDenseMatrix(2, 2, cv.ctx);
    cv.linear = SUNLinSol_Dense(cv.y, cv.matrix, cv.ctx);
    Check(CVodeSetLinearSolver(cv.mem, cv.linear, cv.matrix), "CVodeSetLinearSolver");
    Check(CVodeSetJacFn(cv.mem, Jacobian), "CVodeSetJacFn");
  } else {
    // Adams is for nonstiff problems: fixed-point iteration, no Jacobian.
    cv.fixed_point = SUNNonlinSol_FixedPoint(cv.y, 0, cv.ctx);
    Check(CVodeSetNonlinearSolver(cv.mem, cv.fixed_point), "CVodeSetNonlinearSolver");
  }

  double t = o.t0_s;
  double x = o.x0_m;
  double v = o.v0_mps;

  // Sample at ts (labelled t_label: the snap onto a stop may have moved ts by < TimeEps).
  auto emit = [&](double t_label, double ts, double xs, double vs) {
    tr.t_s[next_out] = t_label;
    tr.u_v[next_out] = input.Value(ts);
    tr.x_m[next_out] = xs;
    tr.v_mps[next_out] = vs;
    tr.a_mps2[next_out] = p.Acceleration(ts, vs);
    ++next_out;
  };
  auto log_event = [&](double te, EventKind kind) { result.events.push_back({te, kind}); };
  auto add_breakpoints = [&](double te) {
    if (tau > 0)
      for (int k = 1; k <= o.breakpoint_order; ++k)
        if (te + k * tau < t_end) stops.AddSoft(te + k * tau);
  };

  // Initial mode: the sign of v0, or the stick–slip rule at rest.
  SignTimeline signs(o.t0_s, Sign(o.history_v_mps));
  p.mode = v != 0 ? Sign(v) : p.Decide(p.Force(t, v));
  if (v == 0 && p.mode != 0)
    log_event(t, p.mode > 0 ? EventKind::kSlipForward : EventKind::kSlipBackward);
  signs.Set(t, p.mode);
  int last_branch = Sign(o.history_v_mps);
  int events_here = 0;  // mode changes at one instant: guards against chattering
  double last_event_t = -std::numeric_limits<double>::infinity();

  long steps = 0, nfe = 0, nge = 0;
  bool first_segment = true;
  bool restart = true;  // CVODE must be re-initialised at the next segment start
  long cvode_steps = 0;
  // CVodeReInit zeroes CVODE's counters: add them up before each restart and at the end.
  auto collect_counters = [&] {
    long n_steps = 0, n_fe = 0, n_ge = 0, n_fe_ls = 0;
    CVodeGetNumSteps(cv.mem, &n_steps);
    CVodeGetNumRhsEvals(cv.mem, &n_fe);
    CVodeGetNumGEvals(cv.mem, &n_ge);
    if (o.method == IntegratorMethod::kBdf) CVodeGetNumLinRhsEvals(cv.mem, &n_fe_ls);
    cvode_steps += n_steps;
    nfe += n_fe + n_fe_ls;
    nge += n_ge;
  };
  std::vector<double> cx(kMaxOrder + 1), cvv(kMaxOrder + 1);
  N_Vector dky_v = cv.work;

  auto fail = [&](const std::string& flag, const std::string& message, double t_fail) {
    summary.termination =
        flag == "CV_TOO_MUCH_WORK" ? Termination::kBudgetExhausted : Termination::kFailure;
    summary.cvode_flag = flag;
    summary.failure_time_s = t_fail;
    summary.message = message;
  };

  // A mode change at t: log it, remember the new sign of v, propagate the v' jump by tau.
  auto change_mode = [&](int new_mode) {
    if (new_mode == p.mode) return;
    EventKind kind = EventKind::kStick;
    if (new_mode != 0)
      kind = p.mode != 0 ? EventKind::kReverse
                         : (new_mode > 0 ? EventKind::kSlipForward : EventKind::kSlipBackward);
    log_event(t, kind);
    events_here = t - last_event_t <= TimeEps(t) ? events_here + 1 : 0;
    last_event_t = t;
    if (events_here > 8)
      fail("CHATTERING", "more than 8 stick/slip mode changes at one instant (Zeno behaviour)", t);
    p.mode = new_mode;
    signs.Set(t, new_mode);
    add_breakpoints(t);
  };

  while (summary.IsSolutionUsable()) {
    // Stops within TimeEps are this instant: move onto them exactly (Taylor step of < 1e-12 s)
    // so that u is read on the right side of an edge.
    double next_stop = stops.Next(t);
    while (next_stop <= t + TimeEps(t)) {
      const double dt = next_stop - t;
      x += dt * v + 0.5 * dt * dt * p.Acceleration(t, v);
      v += dt * p.Acceleration(t, v);
      t = next_stop;
      next_stop = stops.Next(t);
      restart = true;
      if (p.mode == 0) {  // an input edge may release the stage right here
        change_mode(p.Decide(p.Force(t, 0.0)));
        next_stop = stops.Next(t);
      }
    }
    if (!summary.IsSolutionUsable()) break;
    if (p.mode == 0) v = 0.0;

    // Viscous branch from the right-hand limit of v(t - tau).
    p.branch = signs.RightOf(t - tau);
    if (p.branch != 0) {
      if (last_branch != 0 && p.branch != last_branch) log_event(t, EventKind::kViscousSwitch);
      last_branch = p.branch;
    }
    p.Freeze();
    p.u_held = input.ConstantBetweenEdges();
    p.u_seg = input.Value(t);
    p.t_last_inside = std::nextafter(next_stop, -std::numeric_limits<double>::infinity());

    while (next_out < n_out && t_out[static_cast<size_t>(next_out)] <= t)
      emit(t_out[static_cast<size_t>(next_out)], t, x, v);
    if (t >= t_end - TimeEps(t_end)) break;

    // Stuck under a held input with v(t - tau) = 0 all along: F is constant, so nothing can
    // happen before the next stop time. Skip there exactly (x, v = 0 do not change).
    if (p.mode == 0 && input.ConstantBetweenEdges() &&
        (tau == 0 || signs.ZeroOn(t - tau, next_stop - tau))) {
      p.history.AppendConstant(next_stop, 0.0);
      while (next_out < n_out && t_out[static_cast<size_t>(next_out)] < next_stop)
        emit(t_out[static_cast<size_t>(next_out)], t_out[static_cast<size_t>(next_out)], x, 0.0);
      t = next_stop;
      restart = true;
      change_mode(p.Decide(p.Force(t, 0.0)));
      continue;
    }

    y[0] = x;
    y[1] = v;
    if (restart) {
      if (!first_segment) collect_counters();
      Check(CVodeReInit(cv.mem, t, cv.y), "CVodeReInit");
      if (!first_segment) ++summary.reinitialisations;
      first_segment = false;
    }
    Check(CVodeSetStopTime(cv.mem, next_stop), "CVodeSetStopTime");
    int directions[kNumRoots] = {-p.mode, 1, -1, -p.branch};
    Check(CVodeSetRootDirection(cv.mem, directions), "CVodeSetRootDirection");

    // One segment, step by step.
    int flag = CV_SUCCESS;
    double t_ret = t;
    while (true) {
      if (steps >= o.max_steps) {
        fail("CV_TOO_MUCH_WORK",
             "step budget SimulationOptions::max_steps = " + std::to_string(o.max_steps) +
                 " exhausted",
             t_ret);
        break;
      }
      flag = CVode(cv.mem, next_stop, cv.y, &t_ret, CV_ONE_STEP);
      if (flag < 0) {
        double t_now = t_ret;
        CVodeGetCurrentTime(cv.mem, &t_now);
        fail(FlagName(flag), p.cvode_message.empty() ? "CVODE failed" : p.cvode_message, t_now);
        break;
      }
      ++steps;
      double tn = 0, hu = 0;
      int q = 0;
      CVodeGetCurrentTime(cv.mem, &tn);
      CVodeGetLastStep(cv.mem, &hu);
      CVodeGetLastOrder(cv.mem, &q);
      const double piece_end = std::min(t_ret, tn);
      // Taylor coefficients of x and v at tn in the scaled variable theta = (t - tn) / hu: the
      // step's own interpolant, for the delay history and for the outputs inside the step.
      if (p.mode == 0) {
        q = 0;
        cx[0] = N_VGetArrayPointer(cv.y)[0];
        cvv[0] = 0.0;
        p.history.AppendConstant(piece_end, 0.0);
      } else {
        double scale = 1.0;
        for (int k = 0; k <= q; ++k) {
          CVodeGetDky(cv.mem, tn, k, dky_v);
          const sunrealtype* d = N_VGetArrayPointer(dky_v);
          cx[static_cast<size_t>(k)] = d[0] * scale;
          cvv[static_cast<size_t>(k)] = d[1] * scale;
          scale *= hu / (k + 1);
        }
        p.history.AppendPolynomial(piece_end, tn, hu, cvv.data(), q);
      }
      const bool final_piece = t_ret >= t_end - TimeEps(t_end);
      while (next_out < n_out) {
        const double ts = t_out[static_cast<size_t>(next_out)];
        if (!(ts < t_ret || (final_piece && ts <= t_ret))) break;
        const double theta = (ts - tn) / hu;
        double xs = cx[static_cast<size_t>(q)], vs = cvv[static_cast<size_t>(q)];
        for (int k = q - 1; k >= 0; --k) {
          xs = xs * theta + cx[static_cast<size_t>(k)];
          vs = vs * theta + cvv[static_cast<size_t>(k)];
        }
        emit(ts, ts, xs, vs);
      }
      if (flag == CV_ROOT_RETURN || flag == CV_TSTOP_RETURN || t_ret >= next_stop) break;
    }
    if (!summary.IsSolutionUsable()) break;

    // Segment end: right-hand limit and the next mode.
    t = t_ret;
    x = y[0];
    v = p.mode == 0 ? 0.0 : y[1];
    int found[kNumRoots] = {0, 0, 0, 0};
    if (flag == CV_ROOT_RETURN) Check(CVodeGetRootInfo(cv.mem, found), "CVodeGetRootInfo");
    int new_mode = p.mode;
    if (found[0] != 0) {  // a sliding stage reached v = 0: stick, or slide on (reverse)
      v = 0.0;
      new_mode = p.Decide(p.Force(t, 0.0));
    } else if (found[1] != 0) {  // the root's direction says F crossed a2p upwards
      new_mode = 1;
    } else if (found[2] != 0) {
      new_mode = -1;
    } else if (p.mode == 0) {  // a stop time: the input's right-hand value may release it
      new_mode = p.Decide(p.Force(t, 0.0));
    }
    // Only a soft stop with nothing changed lets CVODE go on with its history and order.
    restart = flag == CV_ROOT_RETURN || new_mode != p.mode || stops.IsHard(t);
    change_mode(new_mode);
  }

  if (!first_segment) collect_counters();
  summary.steps = steps;
  summary.rhs_evaluations = nfe;
  summary.root_evaluations = nge;
  summary.events = static_cast<long>(result.events.size());
  if (next_out < n_out) {  // a failure: keep the samples reached
    tr.t_s.conservativeResize(next_out);
    tr.u_v.conservativeResize(next_out);
    tr.x_m.conservativeResize(next_out);
    tr.v_mps.conservativeResize(next_out);
    tr.a_mps2.conservativeResize(next_out);
  }
  if (!summary.IsSolutionUsable())
    summary.message = "at t = " + std::to_string(summary.failure_time_s) + " s: " + summary.message;
  else
    summary.message = "reached t_end";
  summary.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  return result;
}

}  // namespace sysid
