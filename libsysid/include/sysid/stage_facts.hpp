// The paper's measured facts, checked on a stage: runs the paper's experiments on a virtual stage
// and compares what they give with what the paper printed. Ids are fixed:
//
//   F1 pulse plateaus     the ten 0.4 s pulses' steady velocities, each within 2 % of the paper's
//   F2 pulse LS           a1p, a1n, a2p, a2n within 5 % of 104.0154, 117.1441, 3.1023, 6.8216
//   F3 delay              tune-delay on the pulse recording: tau in [2.5, 4.5] ms and
//                         RMS dv(tau) <= 0.8 RMS dv(0)
//   F4 paper gains        PI Kp = 19000 V/m, Ki = 660000 V/(m s) on the 0.5 and 1 Hz references:
//                         no limit cycle (ripple and pinning defined below) and quiet in motion
//   F5 tracking table     max |e|: PI > PI + analytic > PI + NN at both frequencies, each within a
//                         factor 3 of the paper's table
//   F6 dominance          u = 1.5 sin(pi/2 t - pi/2) - 0.3 V open loop: the ratio of peaks
//                         max |x''| / max |a1 x'| over the moving part <= 0.3 (O(10^-1))
//   F7 networks           typical (v, a) 120-unit vs dominant v 24-unit network MSEs; reported,
//                         not required (the paper's contrast: typical fits training, not test)
//   F8 voltage loop       the voltage-velocity loop of the paper's section-3 tests, open loop:
//                         (a) on the 6 s triangle (+1.5 / -2.1 V) a loop, width at stated
//                         voltages of the pulse region >= a fraction of the velocity there;
//                         (b) asymmetric: the start voltages of the two directions differ;
//                         (c) rate: under u = 1.6 sin(2 pi f t - pi/2) - 0.3 V the loop's mean
//                         width grows with f; (d) amplitude: at 1 Hz the mean width changes
//                         with A (criteria below, at FactsOptions' loop_* fields)
//
// F4's criteria, on the PI-alone runs of the smooth profile (control.hpp, MakeSmoothProfile;
// dwell 10 % of the period at each end):
//   ripple  for every dwell after the first cycle, the last half of the dwell (the reference is at
//           rest and the move's transient has had half a dwell to decay); ripple amplitude =
//           max over these windows of (max e - min e) / 2 [m]. Ripple when it exceeds
//           FactsOptions::ripple_tolerance_m (default 1 um = 10 counts of a 0.1 um encoder).
//   pinned  any sample, from the start, at which the PI output was clipped at +-u_max
//           (TrackingResult::saturated_samples > 0).
//   motion  ripple in motion: r_k = e_k - (centred moving average of e over
//           FactsOptions::motion_ripple_window_s, 50 ms), over every sample after the first cycle
//           whose window lies inside the run; RMS of r above
//           FactsOptions::motion_ripple_tolerance_m (5 um) is ringing, and the frequency of the
//           largest peak of r's Hann-windowed periodogram is reported as the ringing frequency.
//
// Every experiment is seeded; the same stage and options give the same numbers.
#ifndef SYSID_STAGE_FACTS_HPP_
#define SYSID_STAGE_FACTS_HPP_

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "sysid/control.hpp"
#include "sysid/delay.hpp"
#include "sysid/identify.hpp"
#include "sysid/nn.hpp"
#include "sysid/stage.hpp"

namespace sysid {

/// The paper's printed numbers the facts compare against.
struct PaperFacts {
  /// The pulse table: (amplitude [V], steady velocity [m/s]), as in datasets/paper.
  static const std::vector<std::pair<double, double>>& PulseTable();
  static FrictionModel PulseModel();         ///< a1p 104.0154, a1n 117.1441, a2p 3.1023, a2n 6.8216
  static constexpr double kTauS = 0.0035;    ///< [s] the paper's delay
  static constexpr double kKpVPerM = 19000;  ///< [V/m]
  static constexpr double kKiVPerMS = 660000;  ///< [V/(m s)]
  /// Max tracking error [m] at 0.5 Hz and 1 Hz for "none", "analytic", "nn".
  static double TrackingMaxErrorM(double frequency_hz, const std::string& scheme);
  static constexpr double kTypicalHidden = 120;
  static constexpr double kDominantHidden = 24;
  static constexpr double kDominantTrainMseV2 = 0.118161;  ///< [V^2] H = 24
  static constexpr double kDominantTestMseV2 = 0.052982;   ///< [V^2] H = 24
};

struct FactsOptions {
  /// Facts to run ("F1".."F8"); empty: all. Prerequisites run as needed.
  std::vector<std::string> facts;
  std::uint64_t seed = 1;  ///< noise seed of every experiment
  int threads = 0;         ///< for delay tuning (0: all cores); training uses one (repeatable)
  PulseProcedure pulse;    ///< the paper's ten pulses
  DelayTuningOptions delay = DefaultDelay();           ///< F3; curve_points >= 2 (includes tau = 0)
  PiOptions pi;                                        ///< F4/F5: the paper's gains
  std::vector<double> track_frequencies_hz{0.5, 1.0};  ///< [Hz]
  double track_amplitude_m = 0.01;                     ///< [m] stroke, as the pipeline
  int track_cycles = 2;                                ///< >= 2 (ripple needs a second cycle)
  double ripple_tolerance_m = 1e-6;                    ///< [m] F4's ripple threshold
  double motion_ripple_tolerance_m = 5e-6;  ///< [m] F4's RMS ripple in motion threshold
  double motion_ripple_window_s = 0.05;     ///< [s] F4's moving average (in motion), > 0
  /// The dominant network (H = 24, the paper's choice) and the typical one, as the pipeline.
  NeuralTrainingOptions training = DefaultTraining();
  int typical_hidden = 120;
  int typical_max_epochs = 60;
  int typical_stride = 2;  ///< typical network trains on every n-th training row
  /// [V/m] > 0: the P gain that collects the networks' training and test sets
  /// (TrackingProcedure::kp_v_per_m; the paper does not print its value).
  double collection_kp_v_per_m = TrackingProcedure{}.kp_v_per_m;
  /// F5: also track with dominant networks trained from this many initial weights (network k
  /// from training.seed + k * training.restarts) and report each one's max |e| and how many
  /// beat the analytic inverse; the verdict stays the first network's. 1 to 100.
  int network_initializations = 1;
  /// F6's open-loop test: u = amplitude sin(omega t - pi/2) + offset for duration_s.
  double dominance_amplitude_v = 1.5;
  double dominance_omega_rad_s = 1.5707963267948966;  ///< pi/2
  double dominance_offset_v = -0.3;
  /// [s] analysed, after a lead-in of the same length (the input starts with a -1.8 V step
  /// from rest, a start-up transient the paper did not plot); default one period.
  double dominance_duration_s = 4.0;
  double dominance_min_speed_mps = 1e-3;  ///< [m/s] the moving part
  /// F8: the triangle of the paper's sections 3 and 4, one period (TriangleProcedure).
  double loop_period_s = 6;           ///< [s] (0, 600]
  double loop_peak_forward_v = 1.5;   ///< [V] (0, 10]
  double loop_peak_backward_v = 2.1;  ///< [V] (0, 10], magnitude of the negative peak
  /// [V] F8 (a): signed voltages at which the triangle's loop width is read (1 to 20 levels,
  /// each inside the triangle's range; default: the pulse region, 1.4 V and -1.9 V).
  std::vector<double> loop_levels_v{1.4, -1.9};
  /// F8 (a): at every level, width >= this fraction of the mean |v| of the two branches.
  double loop_min_relative_width = 0.05;
  /// F8 (b): larger / smaller |start voltage| of the two directions >= this (> 1).
  double loop_min_start_ratio = 1.2;
  /// F8 (c), (d): u = A sin(2 pi f t - pi/2) + loop_sine_offset_v, two periods from rest, the
  /// second analysed (the first starts with a step from rest).
  double loop_sine_offset_v = -0.3;
  double loop_sine_amplitude_v = 1.6;                          ///< [V] A of the rate sweep
  std::vector<double> loop_sine_frequencies_hz{0.25, 0.5, 1, 2};  ///< [Hz] 2 to 10, increasing
  double loop_sine_frequency_hz = 1;                           ///< [Hz] f of the amplitude sweep
  std::vector<double> loop_sine_amplitudes_v{1.6, 1.8, 2.0, 2.2};  ///< [V] 2 to 10, increasing
  /// F8 (c): mean width at the highest frequency >= this x the lowest frequency's (> 1).
  double loop_min_rate_ratio = 1.5;
  /// F8 (d): mean width at the largest amplitude and at the smallest differ by at least this
  /// fraction of the smaller (> 0).
  double loop_min_amplitude_change = 0.1;
  void Validate() const;                  ///< throws OptionsError naming the field and the rule
  static DelayTuningOptions DefaultDelay();
  static NeuralTrainingOptions DefaultTraining();
  /// For tests: the same experiments with small networks and short training (F7 numbers are
  /// then not the paper's experiment; F1-F6 except F5's NN row are unchanged).
  static FactsOptions Reduced();
};

/// The options as JSON, every field (nested options as objects), and the reader: every key
/// optional (absent: the defaults above, e.g. DefaultDelay()), the result validated,
/// InputError "SOURCE:LINE:COL: NAME: expected ..., found ..." otherwise.
std::string ToJson(const FactsOptions& options, int indent = 2);
FactsOptions FactsOptionsFromJson(std::string_view text, const std::string& source_name);

/// One fact: text for the table and JSON, and the numbers behind it.
struct StageFact {
  std::string id;             ///< "F1".."F8"
  std::string fact;           ///< what is checked, one line
  std::string paper;          ///< the paper's value(s)
  std::string virtual_value;  ///< the stage's value(s) (JSON key "virtual")
  std::string tolerance;      ///< the criterion
  bool met = false;
  bool required = true;                                ///< F7: false (reported only)
  std::string note;                                    ///< why not met / what the numbers mean
  std::vector<std::pair<std::string, double>> values;  ///< named numbers (SI units in names)
};

struct FactsTrackingRow {
  double frequency_hz = 0;
  std::string scheme;      ///< "none", "analytic", "nn"
  double max_error_m = 0;  ///< [m]
  double ripple_m = 0;     ///< [m] F4's ripple amplitude (see above)
  double motion_ripple_m = 0;  ///< [m] F4's RMS ripple in motion (see above)
  double ringing_hz = 0;       ///< [Hz] the periodogram peak of that ripple
  long saturated_samples = 0;
  double max_abs_u_v = 0;  ///< [V]
};

/// One open-loop sinusoid of F8: u = amplitude sin(2 pi f t - pi/2) + offset, its second period.
struct FactsLoopSine {
  double amplitude_v = 0;   ///< [V]
  double frequency_hz = 0;  ///< [Hz]
  VoltageLoop loop;         ///< areas, spans and starts of the analysed period
  /// [m/s] (area forward + area backward) / (span forward + span backward): the loop's mean
  /// width over both directions (facts::LoopMeanWidth); NaN when the stage never moves.
  double mean_width_mps = 0;
};

struct StageFacts {
  std::string stage_name;
  std::vector<StageFact> facts;  ///< the facts run, in id order
  // The experiments' results (filled as far as the facts run needed them).
  std::vector<std::pair<double, double>> plateaus;  ///< (u [V], v [m/s]) per pulse, input order
  std::optional<FrictionModel> pulse_model;         ///< pulse LS, tau = 0
  std::optional<DelayTuningResult> delay;
  double rms_at_zero_mps = 0;  ///< [m/s] RMS dv at tau = 0 (F3)
  std::vector<FactsTrackingRow> tracking;
  double dominance_peak_ratio = 0;     ///< max |x''| / max |a1 x'| (the paper's bound)
  double dominance_pointwise_q99 = 0;  ///< 99 % quantile of |x''(t)| / |a1 x'(t)|
  double dominant_train_mse = 0, dominant_test_mse = 0;  ///< [V^2]
  double typical_train_mse = 0, typical_test_mse = 0;    ///< [V^2]
  std::optional<VoltageLoop> loop_triangle;  ///< F8: the triangle's loop (levels as options)
  std::vector<FactsLoopSine> loop_frequency_sweep;  ///< F8 (c), in frequency order
  std::vector<FactsLoopSine> loop_amplitude_sweep;  ///< F8 (d), in amplitude order

  const StageFact* Find(const std::string& id) const;
  /// Every required fact that was run is met.
  bool RequiredMet() const;
  /// {"stage": ..., "facts": [{"id", "fact", "paper", "virtual", "tolerance", "met", "required",
  ///  "note", "values": {...}}], "required_met": bool}
  std::string ToJson() const;
  /// A Markdown table: id | fact | paper | stage | tolerance | met.
  std::string ToMarkdown() const;
};

/// The criteria alone, on numbers (so they can be tested without running a stage).
namespace facts {
/// F1: every |v - v_paper| <= 0.02 |v_paper|; `stage` and `paper` in the same order.
bool PlateausMet(const std::vector<double>& stage_mps, const std::vector<double>& paper_mps);
/// F2: every coefficient within 5 %.
bool PulseModelMet(const FrictionModel& stage, const FrictionModel& paper);
/// F3: tau in [2.5, 4.5] ms and rms_at_tau <= 0.8 rms_at_zero.
bool DelayMet(double tau_s, double rms_at_tau_mps, double rms_at_zero_mps);
/// F4's ripple amplitude [m] of a PI run on a smooth profile made with `profile`.
double RippleAmplitude(const Eigen::VectorXd& e_m, const SmoothProfileOptions& profile);
/// F4 in motion: the RMS of e minus its centred moving average over `window_s` [s] (an odd
/// number of samples, 2 round(window_s rate / 2) + 1), over the samples after the first cycle
/// whose window lies inside e [m], each stroke's breakaway transient left out (from the
/// reference leaving a dwell to `window_s` after the largest |e| in the stroke's first half:
/// the onset error F5 measures), and the frequency [Hz] of the largest peak of that
/// residual's Hann-windowed periodogram, the left-out samples as 0 (0 when there are fewer
/// than 4 samples). Without `ringing_frequency` the periodogram, most of the cost, is skipped
/// and ringing_hz stays 0.
struct MotionRipple {
  double rms_m = 0;      ///< [m]
  double ringing_hz = 0;  ///< [Hz]
  long samples = 0;      ///< samples the RMS is over
  long breakaway_samples = 0;  ///< samples after cycle 1 left out as breakaway transients
};
MotionRipple MotionRippleOf(const Eigen::VectorXd& e_m, const SmoothProfileOptions& profile,
                            double window_s = 0.05, bool ringing_frequency = true);
/// F5: none > analytic > nn, and each within a factor 3 of the paper's (both ways).
bool TrackingOrderMet(double none_m, double analytic_m, double nn_m, double paper_none_m,
                      double paper_analytic_m, double paper_nn_m);
/// F6: ratio of peaks <= 0.3.
bool DominanceMet(double peak_ratio);
/// F7's contrast: the typical network's test MSE >= 2x its training MSE, and the dominant
/// network's test MSE below the typical's.
bool NetworkContrast(double typical_train, double typical_test, double dominant_test);
/// F8: a loop's mean width over both directions [m/s], (area_f + area_b) / (span_f + span_b);
/// NaN when the stage never moved.
double LoopMeanWidth(const VoltageLoop& loop);
/// F8 (a): width / mean(|v_rising|, |v_falling|) at a level; NaN without both branches.
double LoopRelativeWidth(const VoltageLoopLevel& level);
/// F8 (b): max / min of |start forward|, |start backward|; NaN when either never starts.
double StartRatio(const VoltageLoop& loop);
/// F8 (a): every relative width >= min_fraction (none NaN, at least one).
bool LoopWidthMet(const std::vector<double>& relative_widths, double min_fraction);
/// F8 (c): last / first >= min_ratio, both finite and the first > 0.
bool LoopRateMet(const std::vector<double>& widths_by_frequency, double min_ratio);
/// F8 (d): |last - first| >= min_change x min(|first|, |last|), both finite and nonzero.
bool LoopAmplitudeMet(const std::vector<double>& widths_by_amplitude, double min_change);
}  // namespace facts

using FactsProgress = std::function<void(const std::string& step)>;

/// Runs the experiments the selected facts need on `stage` and checks them. Throws OptionsError
/// for bad options or an unknown fact id, NumericalError when an experiment fails.
StageFacts RunStageFacts(const StageParameters& stage, const FactsOptions& options = {},
                         const FactsProgress& progress = {});

/// The facts at several seeds: how robust each verdict is to the noise realisation (which also
/// changes the data the networks train on). On the default stage F5's NN row is the fragile
/// one (docs/virtual_stage.md, "F5 over seeds").
struct FactsSeedSweep {
  std::string stage_name;
  std::vector<std::uint64_t> seeds;
  std::vector<StageFacts> runs;  ///< one per seed, in `seeds` order

  /// The seeds at which fact `id` is met (in `seeds` order).
  std::vector<std::uint64_t> MetAt(const std::string& id) const;
  /// Every required fact met at every seed.
  bool RequiredMetEverywhere() const;
  /// {"stage", "seeds": [...], "facts": [{"id", "fact", "required", "met_count", "runs",
  ///  "met_seeds": [...], "virtual": [one text per seed]}], "required_met_everywhere"}
  std::string ToJson() const;
  /// A Markdown table: id | fact | met at | not met at.
  std::string ToMarkdown() const;
};

/// At most this many seeds per sweep (each seed runs every experiment: ~10 s).
constexpr std::size_t kMaxFactsSeeds = 1000;

/// Parses "A-B" (inclusive range) or "A,B,C" into seeds; throws OptionsError naming `text` when
/// it is neither, when a range runs backwards, or when it holds more than kMaxFactsSeeds seeds
/// (checked before anything is allocated).
std::vector<std::uint64_t> ParseFactsSeeds(const std::string& text);

/// RunStageFacts at each seed (options.seed is replaced). `progress` gets "seed S (k/n): step".
FactsSeedSweep RunStageFactsOverSeeds(const StageParameters& stage,
                                      const std::vector<std::uint64_t>& seeds,
                                      const FactsOptions& options = {},
                                      const FactsProgress& progress = {});

}  // namespace sysid

#endif  // SYSID_STAGE_FACTS_HPP_
