// Simulation of the delayed friction model (model.hpp) with stick–slip, on SUNDIALS CVODE.
//
//   x' = v,  v' = -a1 v(t - tau) - a2 sgn(v) + a3 u(t)
//
// While v = 0 the stage is stuck: with F = a3 u(t) - a1 v(t - tau) it breaks away forward when
// F > a2p (v' = F - a2p), backward when F < -a2n (v' = F + a2n), else v' = 0 exactly. Input
// edges are hit exactly, breakpoints propagate by tau, and every sign change is an event
// located by root finding. v(t) = history_v_mps for t < t0.
#ifndef SYSID_SIMULATE_HPP_
#define SYSID_SIMULATE_HPP_

#include <Eigen/Core>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "sysid/input.hpp"
#include "sysid/model.hpp"
#include "sysid/serialize.hpp"
#include "sysid/termination.hpp"

namespace sysid {

struct Recording;

enum class IntegratorMethod { kAdams, kBdf };
/// "adams" / "bdf"; ParseIntegratorMethod throws OptionsError for anything else.
std::string ToString(IntegratorMethod method);
IntegratorMethod ParseIntegratorMethod(const std::string& name);

struct SimulationOptions {
  double t0_s = 0.0;       ///< [s] start time
  double t_end_s = 1.0;    ///< [s] end time, > t0_s
  double dt_out_s = 1e-3;  ///< [s] output sample interval (ignored if output_times_s given)
  std::vector<double> output_times_s;  ///< [s] explicit ascending output times in [t0, t_end]
  double x0_m = 0.0;                   ///< [m] position at t0
  double v0_mps = 0.0;                 ///< [m/s] velocity at t0
  double history_v_mps = 0.0;          ///< [m/s] constant velocity history for t < t0
  double rtol = 1e-10;                 ///< CVODE relative tolerance
  double atol = 1e-12;                 ///< CVODE absolute tolerance (both states, SI units)
  IntegratorMethod method = IntegratorMethod::kAdams;
  long max_steps = 10'000'000;  ///< total step budget over the run
  /// [s] upper bound on a step; 0 = automatic: min(tau, input.MaxStepHint()). A step never
  /// exceeds tau > 0 whatever this says (the delayed value must lie in the accepted past).
  double max_step_s = 0.0;
  /// Discontinuities of v' (input edges, stick/slip events, t0) recur in higher derivatives at
  /// t + k tau; the integrator lands a step exactly on t + k tau for k = 1..breakpoint_order.
  /// In [1, 8]: k = 1 is required, since v(t - tau) leaving an exact 0 (tau after a release) is
  /// no sign change a root function could see.
  int breakpoint_order = 2;
  /// Largest method order; 0 = automatic: 6 for Adams (each step's history polynomial costs
  /// O(q^2) to extract, and orders above 6 save almost no steps when steps are capped at tau),
  /// 5 for BDF. In [0, 12] for Adams, [0, 5] for BDF.
  int max_order = 0;
  void Validate() const;  ///< throws OptionsError naming the field and the rule
  /// The fields, in file order (sysid/serialize.hpp); the rules are Validate()'s.
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(t0_s));
    a->Visit(SYSID_NVP(t_end_s));
    a->Visit(SYSID_NVP(dt_out_s));
    a->Visit(SYSID_NVP(output_times_s));
    a->Visit(SYSID_NVP(x0_m));
    a->Visit(SYSID_NVP(v0_mps));
    a->Visit(SYSID_NVP(history_v_mps));
    a->Visit(SYSID_NVP(rtol));
    a->Visit(SYSID_NVP(atol));
    a->Visit(SYSID_NVP(method));
    a->Visit(SYSID_NVP(max_steps).Minimum(1));
    a->Visit(SYSID_NVP(max_step_s));
    a->Visit(SYSID_NVP(breakpoint_order).Minimum(-1000).Maximum(1000));
    a->Visit(SYSID_NVP(max_order).Minimum(-1000).Maximum(1000));
  }
};

/// Sampled trajectory; all vectors have the same length.
struct Trajectory {
  Eigen::VectorXd t_s;     ///< [s]
  Eigen::VectorXd u_v;     ///< [V] input (right limit)
  Eigen::VectorXd x_m;     ///< [m]
  Eigen::VectorXd v_mps;   ///< [m/s]
  Eigen::VectorXd a_mps2;  ///< [m/s^2] v' (right limit)
};

enum class EventKind { kStick, kSlipForward, kSlipBackward, kReverse, kViscousSwitch };
std::string ToString(EventKind kind);  ///< "stick", "slip+", "slip-", "reverse", "a1-switch"

struct SimulationEvent {
  double t_s = 0;  ///< [s]
  EventKind kind = EventKind::kStick;
  /// The fields, in file order (sysid/serialize.hpp).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(t_s).Required());
    a->Visit(SYSID_NVP(kind).Required());
  }
};

struct SimulationSummary {
  /// kConverged: reached t_end; kBudgetExhausted: max_steps spent (CV_TOO_MUCH_WORK);
  /// kFailure: any other CVODE failure (cvode_flag names it).
  Termination termination = Termination::kConverged;
  /// A trajectory is usable only when complete: samples after a stop are missing.
  bool IsSolutionUsable() const { return termination == Termination::kConverged; }
  std::string message;        ///< why it stopped, in words
  std::string cvode_flag;     ///< CVODE flag name on failure ("CV_TOO_MUCH_WORK", ...)
  double failure_time_s = 0;  ///< [s] time reached when it failed
  long steps = 0;
  long rhs_evaluations = 0;
  long root_evaluations = 0;
  long events = 0;
  long reinitialisations = 0;
  double wall_time_s = 0;
  /// One line: success, steps, rhs evaluations, events, reinitialisations, wall time.
  std::string BriefReport() const;
  /// BriefReport plus the stop's details: message, CVODE flag and failure time.
  std::string FullReport() const;
  /// The fields, in file order (sysid/serialize.hpp). ToJson(SimulationResult) writes the
  /// integrator's method and tolerances after the termination, and the stop's details (message,
  /// cvode_flag, failure_time_s) only for a run that stopped short of t_end.
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(termination).Required());
    a->Visit(SYSID_NVP(steps).Minimum(0).Required());
    a->Visit(SYSID_NVP(rhs_evaluations).Minimum(0).Required());
    a->Visit(SYSID_NVP(root_evaluations).Minimum(0).Required());
    a->Visit(SYSID_NVP(events).Minimum(0).Required());
    a->Visit(SYSID_NVP(reinitialisations).Minimum(0).Required());
    a->Visit(SYSID_NVP(wall_time_s).Minimum(0).Required());
    a->Visit(SYSID_NVP(message));
    a->Visit(SYSID_NVP(cvode_flag));
    a->Visit(SYSID_NVP(failure_time_s));
  }
};

struct SimulationResult {
  Trajectory trajectory;
  std::vector<SimulationEvent> events;
  SimulationSummary summary;
};

/// Simulates `model` driven by `input`. Never throws for numerical failure: the summary says
/// where and why (the trajectory then holds the samples reached). Throws OptionsError for
/// invalid options or model.
SimulationResult Simulate(const FrictionModel& model, const InputSignal& input,
                          const SimulationOptions& options);

/// The delayed friction model as the plant of a sampled control loop: Step(u) holds u [V] for
/// one period Ts (zero-order hold) and returns x [m] at the next sample. The same simulator as
/// Simulate (stick-slip events, the dense delay history, CVODE restarted at each sample where u
/// jumps), continued sample by sample: the input from t_k on is known only when Step gives it,
/// so the stick/slip decision at t_k waits for it. Stepping u_0, u_1, ... gives the x of
/// Simulate on the zero-order hold of those voltages. Uses options' x0_m, v0_mps, history_v_mps,
/// t0_s, tolerances, method, breakpoint_order, max_order, max_steps (over the whole run);
/// t_end_s, dt_out_s and output_times_s are not used. No encoder: x is exact.
class FrictionModelPlant {
 public:
  /// Throws OptionsError for an invalid model or options, or sample_time_s not finite > 0.
  FrictionModelPlant(const FrictionModel& model, double sample_time_s,
                     const SimulationOptions& options = {});
  ~FrictionModelPlant();
  FrictionModelPlant(FrictionModelPlant&&) noexcept;
  FrictionModelPlant& operator=(FrictionModelPlant&&) noexcept;
  FrictionModelPlant(const FrictionModelPlant&) = delete;
  FrictionModelPlant& operator=(const FrictionModelPlant&) = delete;

  /// x(t_{k+1}) [m] after u_v [V] held over [t_k, t_{k+1}). Throws NumericalError (the
  /// simulator's sentence) when the integration fails, OptionsError for a non-finite u.
  double Step(double u_v);
  double position_m() const;    ///< [m] x at time_s()
  double velocity_mps() const;  ///< [m/s] v at time_s() (left limit)
  double time_s() const;        ///< [s] t0 + k Ts
  long events() const;          ///< stick/slip events so far

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
};

/// The options as JSON (every field; method as "adams"/"bdf").
std::string ToJson(const SimulationOptions& options, int indent = 2);
/// Reads options written by ToJson; absent keys keep their defaults, the result is validated.
/// Throws InputError "SOURCE:LINE:COL: NAME: expected ..., found ...".
SimulationOptions SimulationOptionsFromJson(std::string_view text,
                                            const std::string& source_name);
/// A run as `sysid simulate --json` reports it: samples, events [{t_s, kind}] and "summary"
/// (termination, the integrator of `options`, counts, wall time; on a stop short of t_end also
/// message, cvode_flag and failure_time_s).
std::string ToJson(const SimulationResult& result, const SimulationOptions& options,
                   int indent = 2);
/// The run as `sysid simulate --json` prints it: "model" (the model file's fields and units,
/// keys sorted as in the trajectory's metadata), "input" (`input_description`), "t_end_s"
/// (options'), "samples", "output" and "events_file" (the paths written, null when empty),
/// then ToJson(result, options)'s "events" and "summary".
std::string SimulationReportJson(const SimulationResult& result, const FrictionModel& model,
                                 const std::string& input_description,
                                 const SimulationOptions& options,
                                 const std::string& output_path, const std::string& events_path,
                                 int indent = 2);

/// A trajectory's columns t [s], u [V], x [m], v [m/s], a [m/s^2] as a recording named
/// `source`, without metadata.
Recording TrajectoryRecording(const Trajectory& trajectory, const std::string& source);
/// The trajectory of a run as a recording: the columns above;
/// metadata model (the model's JSON), input (`input_description`) and simulator (CVODE method
/// and tolerances of `options`). `sysid simulate` writes it.
Recording TrajectoryRecording(const SimulationResult& result, const FrictionModel& model,
                              const std::string& input_description,
                              const SimulationOptions& options);
/// The events as CSV: a header "t,kind", then one row per event (t [s] with 17 digits).
std::string EventsToCsv(const std::vector<SimulationEvent>& events);

}  // namespace sysid

#endif  // SYSID_SIMULATE_HPP_
