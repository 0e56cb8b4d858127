// Measured motion of a recording: uniformly sampled u, x, v and a, with v and a from the
// position (a differentiating filter) or from a measured-velocity column. Every analysis of a
// recording (identification, delay tuning, dominance, comparison) starts here.
// Units are SI: t [s], u [V], x [m], v [m/s], a [m/s^2].
#ifndef SYSID_MOTION_HPP_
#define SYSID_MOTION_HPP_

#include <Eigen/Core>
#include <string>
#include <string_view>

#include "sysid/io.hpp"
#include "sysid/serialize.hpp"
#include "sysid/signal.hpp"

namespace sysid {

/// How velocity and acceleration are obtained from a recording.
struct MotionOptions {
  /// Filter used to differentiate the position x (default: central differences, as the paper).
  DerivativeOptions derivative;
  /// Name of a measured-velocity column [m/s].
  std::string velocity_column = "v";
  /// The one rule for a recording's own velocity and acceleration columns, in every command
  /// and in Python. true (the default): a recording's velocity_column [m/s] and its
  /// column a [m/s^2] are used as they are when present (they were made with the filter chosen
  /// when the data set was built, e.g. by `sysid derive`); with v but no a, a is v's derivative
  /// by `derivative`. false (the CLI's --derivative): v and a come from x by `derivative`
  /// whenever x is present. Without x the velocity column is used either way.
  bool prefer_velocity_column = true;
  /// Sampling must be uniform: max |dt_k - dt| / dt must not exceed this [dimensionless].
  double max_relative_jitter = 0.01;
  /// The fields, in file order (sysid/serialize.hpp).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(derivative));
    a->Visit(SYSID_NVP(velocity_column));
    a->Visit(SYSID_NVP(prefer_velocity_column));
    a->Visit(SYSID_NVP(max_relative_jitter));
  }
  void Validate() const;  ///< throws OptionsError naming the field and the rule
};

/// The options as JSON: {"derivative": {"method", "cutoff_hz", "butterworth_order",
/// "savgol_window", "savgol_order"}, "velocity_column", "prefer_velocity_column",
/// "max_relative_jitter"}. Every options struct's ToJson writes all of its fields this way.
std::string ToJson(const MotionOptions& options, int indent = 2);
/// Reads that text back. Every key is optional (an absent one keeps its default), so a file
/// names only what it changes; the result is validated. Throws InputError
/// "SOURCE:LINE:COL: NAME: expected ..., found ..." for an unknown key, a wrong type or a
/// violated rule. Every options struct's ...FromJson reads this way.
MotionOptions MotionOptionsFromJson(std::string_view text, const std::string& source_name);

/// Uniformly sampled signals of one recording, all of the same length.
struct MotionSignals {
  std::string source;         ///< the recording's source (file path)
  double dt_s = 0;            ///< [s] nominal sample interval
  Eigen::VectorXd t_s;        ///< [s]
  Eigen::VectorXd u_v;        ///< [V]
  Eigen::VectorXd x_m;        ///< [m] position (empty when the recording has only velocity)
  Eigen::VectorXd v_mps;      ///< [m/s] velocity
  Eigen::VectorXd a_mps2;     ///< [m/s^2] acceleration
  std::string velocity_from;  ///< MotionSource: "x (central)", "columns v, a", ... (reports)
};

/// Where ExtractMotion takes v and a from under `options`, in words: "columns v, a",
/// "column v (a: central)" or "x (butterworth)". Throws InputError when there is neither x nor
/// the velocity column.
std::string MotionSource(const Recording& recording, const MotionOptions& options);

/// Velocity and acceleration of a recording (t, u and x or a velocity column). Throws
/// InputError when the sampling is irregular or there are fewer than 3 samples.
MotionSignals ExtractMotion(const Recording& recording, const MotionOptions& options = {});
/// ExtractMotion into `out`, reusing its vectors' storage: with central differences (the
/// default) nothing is allocated once the sizes match (a batch of recordings of one length).
/// Same values and errors.
void ExtractMotion(const Recording& recording, const MotionOptions& options, MotionSignals* out);

/// The nominal (median) sample interval [s] of the recording's t column, after checking the
/// sampling is uniform: max |dt_k - dt| / dt <= max_relative_jitter, else InputError
/// "SOURCE:LINE: irregular sampling: ..." naming the worst interval. Needs >= 2 samples.
double UniformSampleInterval(const Recording& recording, double max_relative_jitter);

/// Adds the columns v [m/s] and a [m/s^2] (replaced if present) to `recording`, from its x
/// column [m] differentiated by `derivative`, after decimating every column by `decimate`
/// (DecimateRecording; 1 keeps every sample). dt_s [s] is the recording's sample interval.
/// Returns the new sample interval dt_s * decimate. Throws OptionsError naming the field
/// (DerivativeOptions' fields, "factor" for decimate) and InputError when x is too short.
/// `sysid derive` calls it.
double AddDerivatives(Recording& recording, double dt_s, const DerivativeOptions& derivative,
                      int decimate = 1);

/// The settings of AddDerivatives as text: "method=central", "method=butterworth cutoff_hz=50
/// order=4" or "method=savgol window=21 order=3", plus " decimate=K" when K > 1.
std::string DescribeDerivative(const DerivativeOptions& derivative, int decimate = 1);

/// The summary `sysid derive --json` prints of a recording AddDerivatives has extended:
/// {"method", "settings" (its "derive" metadata, else DescribeDerivative), "rows", "columns",
/// "dt_s" [s], "sample_rate_hz" [Hz], "v_mps" and "a_mps2": {"min", "max", "rms"}}. Throws
/// InputError when the recording has no rows or no v or a column.
std::string DerivedRecordingToJson(const Recording& recording, double dt_s,
                                   const DerivativeOptions& derivative, int indent = 2);

}  // namespace sysid

#endif  // SYSID_MOTION_HPP_
