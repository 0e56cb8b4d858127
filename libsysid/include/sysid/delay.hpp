// Fitting simulations to recordings.
//
// Delay tuning: the delay tau of the viscous term that makes simulated and measured velocity
// agree best,
//   tau* = argmin_{tau in [tau_min, tau_max]} sum_k (v_sim(t_k; tau) - v_meas(t_k))^2,
// over all samples of all recordings (transients included), the other parameters fixed. The
// cost is not smooth in tau, so the search is derivative-free and bounded (NLopt DIRECT-L over
// the interval, then BOBYQA). Recordings are split at pulse starts where the stage is at rest
// and the pieces are simulated in parallel threads.
//
// Output-error refinement: all six parameters (Ceres) by the same velocity cost, from a starting
// model (usually the pulse least squares), on the same segments.
#ifndef SYSID_DELAY_HPP_
#define SYSID_DELAY_HPP_

#include <Eigen/Core>
#include <limits>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "sysid/identify.hpp"
#include "sysid/io.hpp"
#include "sysid/model.hpp"
#include "sysid/serialize.hpp"
#include "sysid/termination.hpp"

namespace sysid {

/// How recordings are cut into independently simulated segments (shared by TuneDelay and
/// RefineOutputError).
struct SegmentOptions {
  /// Cut points are the starts of the pulses found with these options.
  PulseDetectionOptions detection;
  /// A cut is made only where the stage is at rest: mean |v_meas| over the 10 samples before
  /// the cut below this [m/s]. The piece then starts from v = 0 with zero velocity history.
  double rest_speed_mps = 2e-3;
  /// Pieces with the same input pattern, start state and relative sample times (the repeats of
  /// a pulse train) are simulated once: the model is time-invariant, so this is exact.
  bool reuse_identical_segments = true;
  /// The fields, in file order (sysid/serialize.hpp).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(detection));
    a->Visit(SYSID_NVP(rest_speed_mps));
    a->Visit(SYSID_NVP(reuse_identical_segments));
  }
  void Validate() const;
};

struct DelayTuningOptions {
  double tau_min_s = 0.0;       ///< [s] lower bound of the search
  double tau_max_s = 0.02;      ///< [s] upper bound; must exceed tau_min_s, at most kMaxTau_s
  double x_tolerance_s = 1e-7;  ///< [s] BOBYQA stops when steps are below this
  int coarse_evaluations = 12;  ///< DIRECT-L budget (coarse resolution (max-min)/budget)
  int max_evaluations = 40;     ///< total cost evaluations
  int curve_points = 0;  ///< extra cost samples on a uniform tau grid (plotting), <= kMaxCurvePoints
  MotionOptions motion;         ///< measured velocity: v column, or x with this filter
  SegmentOptions segments;
  double sim_rtol = 1e-6;  ///< CVODE relative tolerance of each simulation
  double sim_atol = 1e-9;  ///< CVODE absolute tolerance [m, m/s]
  int threads = 0;         ///< simulation threads (0: hardware concurrency)
  /// The fields, in file order (sysid/serialize.hpp).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(tau_min_s));
    a->Visit(SYSID_NVP(tau_max_s));
    a->Visit(SYSID_NVP(x_tolerance_s));
    a->Visit(SYSID_NVP(coarse_evaluations));
    a->Visit(SYSID_NVP(max_evaluations));
    a->Visit(SYSID_NVP(curve_points));
    a->Visit(SYSID_NVP(motion));
    a->Visit(SYSID_NVP(segments));
    a->Visit(SYSID_NVP(sim_rtol));
    a->Visit(SYSID_NVP(sim_atol));
    a->Visit(SYSID_NVP(threads));
  }
  void Validate() const;   ///< throws OptionsError naming the field and the rule
  /// [s] Largest delay searched: a viscous-term delay of more than a second is no actuator's,
  /// and each simulation keeps tau of velocity history.
  static constexpr double kMaxTau_s = 1.0;
  /// Largest cost curve (each point is one simulation of every segment, as one search
  /// evaluation: about 10 ms on the bundled pulse test, so 1000 points take about 15 s and
  /// 10000 over two minutes).
  static constexpr int kMaxCurvePoints = 1000;
};

struct DelayTuningResult {
  /// kConverged: the search met its tolerance; kBudgetExhausted: max evaluations reached.
  Termination termination = Termination::kConverged;
  std::string message;       ///< why it stopped, in words
  FrictionModel model;       ///< the input model with tau_s = the optimum
  double tau_s = 0;          ///< [s]
  double cost = 0;           ///< [m^2/s^2] sum of squared velocity errors at tau_s
  double rms_error_mps = 0;  ///< [m/s] sqrt(cost / samples)
  int evaluations = 0;       ///< cost evaluations of the search (one per tau)
  long simulations = 0;      ///< segment simulations in total (search + curve)
  int segments = 0;          ///< simulated pieces per evaluation
  Eigen::Index samples = 0;  ///< velocity samples compared per evaluation
  /// (tau [s], cost [m^2/s^2]) of every evaluation and curve point, sorted by tau.
  std::vector<std::pair<double, double>> curve;
  /// Doubts about the result in words: tau at a search bound (the optimum may lie outside the
  /// interval, or the recordings do not determine tau).
  std::vector<std::string> warnings;
  double wall_time_s = 0;
  /// The fields of tune-delay's JSON, in file order (sysid/serialize.hpp); the model is a model
  /// file's object.
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(tau_s).Renamed("tau").Minimum(0));
    a->Visit(SYSID_NVP(cost).Minimum(0));
    a->Visit(SYSID_NVP(rms_error_mps).Minimum(0));
    a->Visit(SYSID_NVP(evaluations).Minimum(0).Maximum(1 << 30));
    a->Visit(SYSID_NVP(simulations).Minimum(0));
    a->Visit(SYSID_NVP(segments).Minimum(0).Maximum(1 << 30));
    a->Visit(SYSID_NVP(samples).Minimum(0));
    a->Visit(SYSID_NVP(termination));
    a->Visit(SYSID_NVP(message));
    a->Visit(SYSID_NVP(wall_time_s).Minimum(0));
    a->Visit(SYSID_NVP(warnings));
    a->Visit(SYSID_NVP(curve).PairKeys("tau", "cost"));
    a->Visit(SYSID_NVP(model));
  }
  std::string BriefReport() const;
  /// BriefReport plus every diagnostic: the model, the search bounds' warnings and the cost
  /// curve (tau [s], cost [m^2/s^2]).
  std::string FullReport() const;
};

/// Tunes the delay of `model` on `recordings` (t, u and x or a velocity column).
DelayTuningResult TuneDelay(const FrictionModel& model, const std::vector<Recording>& recordings,
                            const DelayTuningOptions& options = {});

// ----------------------------------------------------------------------------------------------
// Output-error refinement (Ceres)
// ----------------------------------------------------------------------------------------------

struct RefineOptions {
  MotionOptions motion;
  PulseDetectionOptions detection;  ///< recordings are split at pulse starts (parallel sims)
  bool refine_a3 = true;            ///< otherwise a3 stays at the initial value
  bool refine_tau = true;           ///< otherwise tau stays at the initial value
  double tau_max_s = 0.05;          ///< [s] upper bound for tau
  int max_iterations = 50;
  int threads = 0;         ///< simulation threads (0: hardware concurrency)
  double sim_rtol = 1e-7;  ///< CVODE relative tolerance of each simulation
  /// The fields, in file order (sysid/serialize.hpp).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(motion));
    a->Visit(SYSID_NVP(detection));
    a->Visit(SYSID_NVP(refine_a3));
    a->Visit(SYSID_NVP(refine_tau));
    a->Visit(SYSID_NVP(tau_max_s));
    a->Visit(SYSID_NVP(max_iterations));
    a->Visit(SYSID_NVP(threads));
    a->Visit(SYSID_NVP(sim_rtol));
  }
  void Validate() const;
};

struct RefineResult {
  FrictionModel initial;
  FrictionModel model;
  std::vector<std::string> names;  ///< refined parameters: a1p, a1n, a2p, a2n[, a3][, tau]
  Eigen::VectorXd std_error;       ///< from s^2 (J^T J)^-1 at the optimum; NaN if singular
  double initial_cost = 0;         ///< [m^2/s^2] sum of squared velocity errors
  double final_cost = 0;           ///< [m^2/s^2]
  double rms_error_mps = 0;        ///< [m/s] at the optimum
  int iterations = 0;  ///< Ceres iterations after the start: at most RefineOptions::max_iterations
  long simulations = 0;
  /// Ceres' CONVERGENCE, NO_CONVERGENCE (iterations) and FAILURE.
  Termination termination = Termination::kFailure;
  std::string message;  ///< Ceres' termination in words
  /// Doubts about the result in words: a parameter far from its given value (moved by more
  /// than 50 % of it and by more than 3 standard errors, or with the error unknown), which
  /// usually means the starting model (a data-sheet a3, a tau at a bound) and the recordings
  /// disagree.
  std::vector<std::string> warnings;
  double wall_time_s = 0;  ///< [s] not serialised (files stay identical run to run)
  /// The fields of refine's "diagnostics" object after its std_error (of `names`), in file order
  /// (sysid/serialize.hpp); `model` is the file's own keys, `initial` is not written.
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(initial_cost).Minimum(0));
    a->Visit(SYSID_NVP(final_cost).Minimum(0));
    a->Visit(SYSID_NVP(rms_error_mps).Minimum(0));
    a->Visit(SYSID_NVP(iterations).Minimum(0).Maximum(1 << 30));
    a->Visit(SYSID_NVP(simulations).Minimum(0));
    a->Visit(SYSID_NVP(termination));
    a->Visit(SYSID_NVP(message));
    a->Visit(SYSID_NVP(warnings));
  }
  std::string BriefReport() const;
  /// BriefReport plus every diagnostic: the initial model, each parameter's change and
  /// relative standard error, and the warnings.
  std::string FullReport() const;
};

/// Refines all parameters by minimising sum (v_sim - v_meas)^2 over every sample of every
/// recording, starting from `initial`. Simulations of different segments run in parallel.
RefineResult RefineOutputError(const FrictionModel& initial,
                               const std::vector<Recording>& recordings,
                               const RefineOptions& options = {});

// ----------------------------------------------------------------------------------------------
// JSON (the text of `sysid tune-delay --json` and `sysid refine --json`)
// ----------------------------------------------------------------------------------------------

/// tau, cost, counts, termination, message, warnings, curve [{tau, cost}] and the tuned model
/// (ModelToJson) under "model".
std::string ToJson(const DelayTuningResult& result, int indent = 2);
/// The refined model file's text (ModelToJson) with a "diagnostics" object: standard errors
/// (null when singular), costs, counts, termination, message and warnings. Any model reader
/// accepts it.
std::string ToJson(const RefineResult& result, int indent = 2);
/// The options as JSON, every field (nested options as objects), and their readers: every
/// key optional, the result validated, InputError "SOURCE:LINE:COL: NAME: expected ...,
/// found ..." otherwise (as MotionOptionsFromJson).
std::string ToJson(const SegmentOptions& options, int indent = 2);
std::string ToJson(const DelayTuningOptions& options, int indent = 2);
std::string ToJson(const RefineOptions& options, int indent = 2);
SegmentOptions SegmentOptionsFromJson(std::string_view text, const std::string& source_name);
DelayTuningOptions DelayTuningOptionsFromJson(std::string_view text,
                                              const std::string& source_name);
RefineOptions RefineOptionsFromJson(std::string_view text, const std::string& source_name);
/// Read ToJson's text back; InputError "SOURCE:LINE:COL: NAME: expected ..., found ..." on bad
/// text. RefineResult::initial is not written and stays default.
DelayTuningResult DelayTuningResultFromJson(std::string_view text,
                                            const std::string& source_name);
RefineResult RefineResultFromJson(std::string_view text, const std::string& source_name);

}  // namespace sysid

#endif  // SYSID_DELAY_HPP_
