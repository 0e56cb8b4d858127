// Identification of the friction model (model.hpp) from recordings.
//
//  - Pulse-test least squares (the paper's method): every settled voltage pulse gives one
//    steady-state equation  a1p v + a2p = a3 u  (u > 0)  or  a1n |v| + a2n = a3 |u|  (u < 0);
//    all pulses are solved together with a column-pivoted QR (a3 given).
//  - Trajectory (inverse-model) least squares, as robotics IDIM-LS: every moving sample gives
//      u = (1/a3) x'' + (a1/a3) v(t - tau) + (a2/a3) sgn(v)  [+ offset]
//    with direction-split regressors, so a3 is identified too.
// Output-error refinement of all six parameters lives beside delay tuning (delay.hpp): both fit
// simulations to recordings.
// Units are SI: t [s], u [V], x [m], v [m/s], a [m/s^2], a1 [1/s], a2 [m/s^2], a3 [m/(s^2 V)].
#ifndef SYSID_IDENTIFY_HPP_
#define SYSID_IDENTIFY_HPP_

#include <Eigen/Core>
#include <limits>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "sysid/io.hpp"
#include "sysid/model.hpp"
#include "sysid/motion.hpp"
#include "sysid/serialize.hpp"
#include "sysid/signal.hpp"

namespace sysid {

// ----------------------------------------------------------------------------------------------
// The voltage-velocity loop of a slow open-loop sweep (the paper's triangle test)
// ----------------------------------------------------------------------------------------------

struct VoltageLoopOptions {
  /// [V] signed voltages at which to read the loop; empty: six per direction, evenly from just
  /// past the start voltage (by 2 % of the peak) to 95 % of the recording's peak in that
  /// direction (from 50 % of the peak when the stage never starts that way).
  std::vector<double> levels_v;
  int half_window = 10;               ///< v at a crossing: mean over +-half_window samples
  double moving_speed_mps = 1e-3;     ///< [m/s] |v| above this is motion (start / stop)
  /// Whole periods of u the recording holds (1 to 10000): the loop areas are per period.
  int cycles = 1;
  void Validate() const;
};

/// The loop at one voltage: the mean velocity where |u| passes |level| going up (the stage
/// accelerating) and going down, averaged over every such crossing.
struct VoltageLoopLevel {
  double level_v = 0;                                        ///< [V]
  double v_rising_mps = std::numeric_limits<double>::quiet_NaN();   ///< [m/s] |u| increasing
  double v_falling_mps = std::numeric_limits<double>::quiet_NaN();  ///< [m/s] |u| decreasing
  int rising_crossings = 0, falling_crossings = 0;
  /// [m/s] v_falling - v_rising in the level's direction (> 0: the stage is faster on the way
  /// down, the loop of a lagging response); NaN without both branches.
  double WidthMps() const;
};

struct VoltageLoop {
  std::string source;
  std::vector<VoltageLoopLevel> levels;
  /// [V] mean u at which the stage starts to move forward / backward (|v| first exceeds
  /// moving_speed_mps after rest, in the direction of u) and stops again (|v| falls back below
  /// it); NaN when it never happens. start != stop is the loop's static width.
  double start_forward_v = std::numeric_limits<double>::quiet_NaN();
  double start_backward_v = std::numeric_limits<double>::quiet_NaN();
  double stop_forward_v = std::numeric_limits<double>::quiet_NaN();
  double stop_backward_v = std::numeric_limits<double>::quiet_NaN();
  double peak_forward_v = 0, peak_backward_v = 0;  ///< [V] max u, min u
  /// [V m/s] the area the loop encloses in each direction, per period:
  /// -(1 / cycles) sum of v du (trapezoid) over the steps on which the stage moves that way
  /// (|v| > moving_speed_mps at both ends, same sign). Positive when |v| is larger while |u|
  /// falls (a lagging loop), negative for the opposite sense; 0 for any static map u -> v,
  /// whatever its shape. Over whole periods of a periodic response a lobe cut by the record's
  /// ends still counts whole (its two pieces add up).
  double area_forward_v_mps = 0, area_backward_v_mps = 0;
  /// [V] the range of u over those steps (max u - min u); 0 when the stage never moves that way.
  double span_forward_v = 0, span_backward_v = 0;
  /// [m/s] area / span: the loop's mean width over the voltages where the stage moves that
  /// way (for a band of constant width w, w); NaN when the span is 0.
  double MeanWidthForwardMps() const;
  double MeanWidthBackwardMps() const;
  Eigen::VectorXd u_v, v_mps;  ///< [V], [m/s] the traces it was read from (not in the JSON)
};

/// Reads the voltage-velocity loop of a recording with t, u and x (or v) columns, e.g.
/// `sysid generate triangle`'s loop_triangle.csv or the same test on a rig: u should sweep
/// slowly through both directions. Throws InputError for a recording without u or without
/// motion columns, OptionsError for bad options.
VoltageLoop AnalyzeVoltageLoop(const Recording& recording, const VoltageLoopOptions& options = {},
                               const MotionOptions& motion = {});
/// {"source", "peak_forward_v", "peak_backward_v", "start_forward_v", "start_backward_v",
///  "stop_forward_v", "stop_backward_v", "area_forward_v_mps", "area_backward_v_mps",
///  "span_forward_v", "span_backward_v", "mean_width_forward_mps", "mean_width_backward_mps",
///  "levels": [{"level_v", "v_rising_mps", "v_falling_mps", "width_mps", "rising_crossings",
///  "falling_crossings"}]}; NaN as null.
std::string ToJson(const VoltageLoop& loop, int indent = 2);

// ----------------------------------------------------------------------------------------------
// Pulses and their steady-state velocities
// ----------------------------------------------------------------------------------------------

struct PulseDetectionOptions {
  double min_duration_s = 0.2;     ///< [s] a pulse holds u for at least this long
  double u_tolerance_v = 1e-3;     ///< [V] |u_k - u_first| <= this counts as "held"
  double zero_tolerance_v = 1e-3;  ///< [V] |u| <= this is "off" (no pulse)
  /// The fields, in file order (sysid/serialize.hpp).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(min_duration_s));
    a->Visit(SYSID_NVP(u_tolerance_v));
    a->Visit(SYSID_NVP(zero_tolerance_v));
  }
  void Validate() const;
};

/// A segment where u holds a constant non-zero value, bounded by other values of u (or by the
/// start / end of the recording, which is flagged).
struct Pulse {
  std::string source;
  Eigen::Index first_row = 0;    ///< first sample of the pulse
  Eigen::Index end_row = 0;      ///< one past the last sample
  double t_start_s = 0;          ///< [s]
  double duration_s = 0;         ///< [s] until the next different u (or last sample + dt)
  double amplitude_v = 0;        ///< [V] mean u over the pulse
  bool at_record_start = false;  ///< no sample before the pulse
  bool at_record_end = false;    ///< no sample after the pulse
  /// The fields an identification's "pulses" entries hold, in file order
  /// (sysid/serialize.hpp); the rows and the record-end flags are not written.
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(source));
    a->Visit(SYSID_NVP(t_start_s));
    a->Visit(SYSID_NVP(duration_s).Minimum(0));
    a->Visit(SYSID_NVP(amplitude_v));
  }
};

/// Finds the pulses in a voltage record.
std::vector<Pulse> DetectPulses(const Eigen::VectorXd& t_s, const Eigen::VectorXd& u_v,
                                const PulseDetectionOptions& options = {},
                                const std::string& source = "");

enum class PulseStatus {
  kOk,
  kUnsettled,
  kStuck,
  kWrongDirection,
  kVelocityLimit,
  kTravelLimit,
  kTooFewSamples
};
std::string ToString(PulseStatus status);  ///< "ok", "unsettled", "stuck", ...

struct PlateauOptions {
  /// The plateau is the last window_fraction of the pulse (excludes the transient), (0, 1].
  double window_fraction = 0.5;
  /// Settled when the drift of a straight-line fit across the window, |c1| T_w, is at most
  /// settle_tolerance |v_mean| (+ 3 standard errors of the drift) [dimensionless].
  double settle_tolerance = 0.02;
  double min_speed_mps = 1e-4;  ///< [m/s] |v_mean| below this: the stage is stuck
  double max_speed_mps = std::numeric_limits<double>::infinity();  ///< [m/s] stage limit
  double travel_min_m = -std::numeric_limits<double>::infinity();  ///< [m] travel limits; a
  double travel_max_m = std::numeric_limits<double>::infinity();   ///< pulse reaching them fails
  int min_window_samples = 8;  ///< fewer samples in the plateau window: excluded
  /// The fields, in file order (sysid/serialize.hpp).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(window_fraction));
    a->Visit(SYSID_NVP(settle_tolerance));
    a->Visit(SYSID_NVP(min_speed_mps));
    a->Visit(SYSID_NVP(max_speed_mps).UpperLimit());
    a->Visit(SYSID_NVP(travel_min_m).LowerLimit());
    a->Visit(SYSID_NVP(travel_max_m).UpperLimit());
    a->Visit(SYSID_NVP(min_window_samples));
  }
  void Validate() const;
};

struct PulseEstimate {
  Pulse pulse;
  double v_mps = 0;         ///< [m/s] mean velocity over the plateau window (signed)
  double v_stderr_mps = 0;  ///< [m/s] its standard error (batch means: robust to correlation)
  double drift_mps = 0;     ///< [m/s] change across the window of a straight-line fit
  int window_samples = 0;
  PulseStatus status = PulseStatus::kOk;
  std::string reason;  ///< why excluded, in words (empty when ok)
  bool usable() const { return status == PulseStatus::kOk; }
  /// The fields of an identification's "pulses" entry, the pulse's first, in file order
  /// (sysid/serialize.hpp); window_samples is not written.
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(pulse).Inline());
    a->Visit(SYSID_NVP(v_mps).NaNAsNull());
    a->Visit(SYSID_NVP(v_stderr_mps).NaNAsNull());
    a->Visit(SYSID_NVP(drift_mps).NaNAsNull());
    a->Visit(SYSID_NVP(status));
    a->Visit(SYSID_NVP(reason));
  }
};

/// Steady-state velocity of each pulse, with the checks of PlateauOptions.
std::vector<PulseEstimate> EstimatePlateaus(const MotionSignals& motion,
                                            const std::vector<Pulse>& pulses,
                                            const PlateauOptions& options = {});

// ----------------------------------------------------------------------------------------------
// Least-squares diagnostics (shared by the pulse and trajectory methods)
// ----------------------------------------------------------------------------------------------

/// A linear least-squares fit y ~ X theta solved by column-pivoted Householder QR.
struct LinearFit {
  std::vector<std::string> names;  ///< parameter names, column order
  Eigen::VectorXd theta;           ///< estimates
  Eigen::VectorXd std_error;       ///< sqrt(diag(covariance)); NaN when dof == 0
  Eigen::MatrixXd covariance;      ///< s^2 (X^T X)^-1, s^2 = |r|^2 / dof
  Eigen::VectorXd residuals;       ///< y - X theta, one per row
  Eigen::Index rows = 0;
  int rank = 0;
  int dof = 0;                  ///< rows - parameters
  double rms_residual = 0;      ///< sqrt(|r|^2 / rows)
  double relative_error = 0;    ///< |r| / |y|
  double condition_number = 0;  ///< sigma_max / sigma_min of X
  /// |R_ii| of the pivoted QR with the parameter of each pivot, largest first: the
  /// identifiability ranking (small entries are poorly identified).
  std::vector<std::pair<std::string, double>> r_diagonal;
  /// The fit's statistics as an identification's diagnostics hold them, in file order
  /// (sysid/serialize.hpp); the estimates are written by parameter name beside them.
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(rows).Minimum(0));
    a->Visit(SYSID_NVP(rank).Minimum(0).Maximum(1000));
    a->Visit(SYSID_NVP(dof).Minimum(-1000));
    a->Visit(SYSID_NVP(condition_number).NaNAsNull());
    a->Visit(SYSID_NVP(rms_residual).NaNAsNull());
    a->Visit(SYSID_NVP(relative_error).NaNAsNull());
    a->Visit(SYSID_NVP(r_diagonal).PairKeys("parameter", "abs_r"));
  }
};

// ----------------------------------------------------------------------------------------------
// Pulse-test least squares
// ----------------------------------------------------------------------------------------------

/// One row of a pulse table.
struct PulsePoint {
  double u_v = 0;     ///< [V] pulse amplitude (signed)
  double v_mps = 0;   ///< [m/s] steady-state velocity (signed)
  std::string label;  ///< where it came from ("table.csv:3", "rec.csv pulse 2")
  /// The fields of a pulse fit's "equations" entry, in file order (sysid/serialize.hpp).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(label));
    a->Visit(SYSID_NVP(u_v));
    a->Visit(SYSID_NVP(v_mps));
  }
};

/// Reads a pulse table: CSV with columns u [V] and v [m/s] (or MAT/HDF5 through `mapping`).
/// Throws InputError.
std::vector<PulsePoint> ReadPulseTable(const std::string& path,
                                       const SourceMapping& mapping = {});

struct PulseFitOptions {
  double a3 = 6.0;  ///< [m/(s^2 V)] actuator gain (steady states cannot separate it)
  /// Whether a3 is the user's (CLI --a3, Python's a3=, an options file's "a3") or the default,
  /// the paper's HR-8 data-sheet value, which another stage does not share: a1 and a2 scale with
  /// a3, so the report says which it is.
  bool a3_given = false;
  /// The fields, in file order (sysid/serialize.hpp).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(a3));
  }
  void Validate() const;
};

/// How every report names the pulse fit's a3 [m/(s^2 V)]: "a3 = 5 (given)" or "a3 = 6 (default:
/// the paper's HR-8 data sheet; give --a3 for your stage)".
std::string DescribeA3(double a3, bool given);

struct PulseIdentificationResult {
  FrictionModel model;                ///< a1p, a1n, a2p, a2n identified; a3 given; tau_s = 0
  bool a3_given = false;              ///< PulseFitOptions::a3_given of the fit
  LinearFit fit;                      ///< theta = [a1p, a2p, a1n, a2n]; residuals in [m/s^2]
  std::vector<PulsePoint> points;     ///< the equations used, in row order
  std::vector<PulseEstimate> pulses;  ///< every detected pulse, excluded ones with reasons
  /// The plain fields of the pulse fit's diagnostics, in file order (sysid/serialize.hpp): the
  /// fit's statistics and the pulses (none from a pulse table); the estimates are written by
  /// name, the points with their residuals as "equations".
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(fit).Inline());
    a->Visit(SYSID_NVP(pulses).OmitEmpty());
  }
  std::string BriefReport() const;
  /// BriefReport plus every diagnostic: the fit (rank, dof, condition number, R diagonal,
  /// residuals) and every pulse with its status and reason.
  std::string FullReport() const;
};

/// Least squares of the pulse equations. Throws NumericalError naming the parameters that
/// cannot be identified ("a1n, a2n: no negative pulses"), OptionsError for bad a3.
PulseIdentificationResult FitPulseTable(const std::vector<PulsePoint>& points,
                                        const PulseFitOptions& options = {});

struct PulseIdentificationOptions {
  MotionOptions motion;
  PulseDetectionOptions detection;
  PlateauOptions plateau;
  PulseFitOptions fit;
  /// The fields, in file order (sysid/serialize.hpp).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(motion));
    a->Visit(SYSID_NVP(detection));
    a->Visit(SYSID_NVP(plateau));
    a->Visit(SYSID_NVP(fit));
  }
  void Validate() const;
};

/// Detects the pulses of every recording, estimates their plateaus and fits the model.
PulseIdentificationResult IdentifyFromPulses(const std::vector<Recording>& recordings,
                                             const PulseIdentificationOptions& options = {});

// ----------------------------------------------------------------------------------------------
// Trajectory (inverse-model) least squares
// ----------------------------------------------------------------------------------------------

struct TrajectoryOptions {
  /// Default: zero-phase Butterworth (order 4, 50 Hz) then central differences.
  MotionOptions motion = DefaultMotion();
  double tau_s = 0.0;           ///< [s] delay of the viscous term (when tune_delay is false)
  bool tune_delay = false;      ///< minimise the residual over tau in [tau_min_s, tau_max_s]
  double tau_min_s = 0.0;       ///< [s]
  double tau_max_s = 0.02;      ///< [s]
  int decimation = 1;           ///< keep every n-th sample after an anti-alias filter (>= 1)
  double min_speed_mps = 1e-3;  ///< [m/s] samples with |v| or |v(t - tau)| below this are
                                ///< stuck or reversing (static friction): excluded
  int trim_samples = 20;        ///< samples dropped at each end of a record (filter start-up)
  /// Adds a constant offset: a3 u = x'' + a1 v(t-tau) + a2 sgn v + c0. The Coulomb term is then
  /// symmetric (a2 sgn v + c0 spans the same space as a2p, a2n); the model gets the
  /// equivalent a2p = a2 + c0, a2n = a2 - c0.
  bool offset = false;
  /// One viscous coefficient a1 = a1p = a1n for both directions (as the EMPS reference model).
  bool symmetric_viscous = false;
  /// The fields, in file order (sysid/serialize.hpp).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(motion));
    a->Visit(SYSID_NVP(tau_s));
    a->Visit(SYSID_NVP(tune_delay));
    a->Visit(SYSID_NVP(tau_min_s));
    a->Visit(SYSID_NVP(tau_max_s));
    a->Visit(SYSID_NVP(decimation));
    a->Visit(SYSID_NVP(min_speed_mps));
    a->Visit(SYSID_NVP(trim_samples));
    a->Visit(SYSID_NVP(offset));
    a->Visit(SYSID_NVP(symmetric_viscous));
  }
  void Validate() const;
  static MotionOptions DefaultMotion();
};

struct TrajectoryIdentificationResult {
  FrictionModel model;  ///< all of a1p, a1n, a2p, a2n, a3 and tau
  LinearFit fit;        ///< the linear fit in u-space (theta = coefficients / a3)
  /// Physical parameters with delta-method standard errors, in the order of `names`:
  /// a3, then a1p, a1n (or a1 when symmetric_viscous), then a2p, a2n (or a2, c0 with offset).
  std::vector<std::string> names;
  Eigen::VectorXd estimate;
  Eigen::VectorXd std_error;
  Eigen::MatrixXd covariance;
  double offset_mps2 = 0;  ///< [m/s^2] c0 (0 without offset)
  Eigen::Index samples_used = 0;
  double relative_error = 0;  ///< |u - u_fit| / |u| over the samples used
  /// Delay search (tune_delay only): evaluated (tau [s], residual sum of squares [V^2]).
  std::vector<std::pair<double, double>> tau_curve;
  /// The velocity filter used (TrajectoryOptions::motion), recorded for the diagnostics.
  DerivativeMethod derivative = DerivativeMethod::kButterworthCentral;
  /// The plain fields of the trajectory fit's diagnostics, in file order
  /// (sysid/serialize.hpp); the estimates are written by name, the fit as "linear_fit".
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(derivative));
    a->Visit(SYSID_NVP(offset_mps2));
    a->Visit(SYSID_NVP(samples_used).Minimum(0));
    a->Visit(SYSID_NVP(relative_error).NaNAsNull());
    a->Visit(SYSID_NVP(tau_curve).OmitEmpty());
  }
  std::string BriefReport() const;
  /// BriefReport plus every diagnostic: estimates with standard errors, the fit (rank, dof,
  /// condition number, R diagonal), the velocity filter and the delay curve.
  std::string FullReport() const;
};

/// Identifies the model from any recordings with enough excitation. Throws NumericalError for
/// rank deficiency (naming the parameters) or too few moving samples.
TrajectoryIdentificationResult IdentifyFromTrajectory(const std::vector<Recording>& recordings,
                                                      const TrajectoryOptions& options = {});

// ----------------------------------------------------------------------------------------------
// JSON (the text `sysid identify --json` prints and -o writes)
// ----------------------------------------------------------------------------------------------

/// The options as JSON, every field (nested options as objects; PlateauOptions' infinite
/// limits as null), and their readers: every key optional, the result validated, InputError
/// "SOURCE:LINE:COL: NAME: expected ..., found ..." otherwise (as MotionOptionsFromJson).
std::string ToJson(const PulseDetectionOptions& options, int indent = 2);
std::string ToJson(const PlateauOptions& options, int indent = 2);
std::string ToJson(const PulseFitOptions& options, int indent = 2);
std::string ToJson(const PulseIdentificationOptions& options, int indent = 2);
std::string ToJson(const TrajectoryOptions& options, int indent = 2);
PulseDetectionOptions PulseDetectionOptionsFromJson(std::string_view text,
                                                    const std::string& source_name);
PlateauOptions PlateauOptionsFromJson(std::string_view text, const std::string& source_name);
PulseFitOptions PulseFitOptionsFromJson(std::string_view text, const std::string& source_name);
PulseIdentificationOptions PulseIdentificationOptionsFromJson(std::string_view text,
                                                              const std::string& source_name);
TrajectoryOptions TrajectoryOptionsFromJson(std::string_view text, const std::string& source_name);

/// The model file's text (ModelToJson: parameters and units) followed by a "diagnostics"
/// object: method, parameters with standard errors, covariance, the fit's statistics, every
/// equation and every detected pulse with its status. Any model reader accepts this text. NaN
/// (a standard error with no degrees of freedom) is written as null.
std::string ToJson(const PulseIdentificationResult& result, int indent = 2);
/// As above; diagnostics hold the physical parameters, the linear fit in u-space and the delay
/// curve (tune_delay only).
std::string ToJson(const TrajectoryIdentificationResult& result, int indent = 2);
/// Read ToJson's text back. Throws InputError "SOURCE:LINE:COL: NAME: expected ..., found ...".
/// Fields ToJson does not write (pulse rows, window sizes, the u-space covariance and
/// residuals of the trajectory fit) keep their defaults.
PulseIdentificationResult PulseIdentificationResultFromJson(std::string_view text,
                                                            const std::string& source_name);
TrajectoryIdentificationResult TrajectoryIdentificationResultFromJson(
    std::string_view text, const std::string& source_name);

}  // namespace sysid

#endif  // SYSID_IDENTIFY_HPP_
