// The paper's measured facts, checked on a stage: runs the paper's experiments on a virtual stage
// and compares what they give with what the paper printed (`sysid stage facts`). Ids are fixed:
//
//   F1 pulse plateaus     the ten 0.4 s pulses' steady velocities, each within 2 % of the paper's
//   F2 pulse LS           a1p, a1n, a2p, a2n within 5 % of 104.0154, 117.1441, 3.1023, 6.8216
//   F3 delay              tune-delay on the pulse recording: tau in [2.5, 4.5] ms and
//                         RMS dv(tau) <= 0.8 RMS dv(0)
//   F4 paper gains        PI Kp = 19000 V/m, Ki = 660000 V/(m s) on the 0.5 and 1 Hz references:
//                         no limit cycle and quiet in motion
//   F5 tracking table     max |e|: PI > PI + analytic > PI + NN at both frequencies, each within a
//                         factor 3 of the paper's table
//   F6 dominance          u = 1.5 sin(pi/2 t - pi/2) - 0.3 V open loop: the ratio of peaks
//                         max |x''| / max |a1 x'| over the moving part <= 0.3 (O(10^-1))
//   F7 networks           typical (v, a) 120-unit vs dominant v 24-unit network MSEs; reported,
//                         not required (the paper's contrast: typical fits training, not test)
//   F8 voltage loop       the open-loop voltage-velocity loop of the paper's section-3 tests:
//                         its width, asymmetry, and change with rate and amplitude
//
// This header is the command's entry point: the options, the table of facts and the run. The
// experiments, each fact's typed numbers and criterion, and the paper's printed numbers are the
// paper's reproduction, not API: libsysid/src/paper/ (f1_plateaus.hpp ... f8_voltage_loop.hpp).
// Every experiment is seeded; the same stage and options give the same numbers.
#ifndef SYSID_STAGE_FACTS_HPP_
#define SYSID_STAGE_FACTS_HPP_

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "sysid/control.hpp"
#include "sysid/delay.hpp"
#include "sysid/identify.hpp"
#include "sysid/nn.hpp"
#include "sysid/serialize.hpp"
#include "sysid/stage.hpp"

namespace sysid {

namespace paper {
struct FactsResults;
}  // namespace paper

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
  /// The fields, in file order (sysid/serialize.hpp).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(facts));
    a->Visit(SYSID_NVP(seed));
    a->Visit(SYSID_NVP(threads));
    a->Visit(SYSID_NVP(pulse));
    a->Visit(SYSID_NVP(delay));
    a->Visit(SYSID_NVP(pi));
    a->Visit(SYSID_NVP(track_frequencies_hz));
    a->Visit(SYSID_NVP(track_amplitude_m));
    a->Visit(SYSID_NVP(track_cycles));
    a->Visit(SYSID_NVP(ripple_tolerance_m));
    a->Visit(SYSID_NVP(motion_ripple_tolerance_m));
    a->Visit(SYSID_NVP(motion_ripple_window_s));
    a->Visit(SYSID_NVP(training));
    a->Visit(SYSID_NVP(typical_hidden));
    a->Visit(SYSID_NVP(typical_max_epochs));
    a->Visit(SYSID_NVP(typical_stride));
    a->Visit(SYSID_NVP(collection_kp_v_per_m));
    a->Visit(SYSID_NVP(network_initializations));
    a->Visit(SYSID_NVP(dominance_amplitude_v));
    a->Visit(SYSID_NVP(dominance_omega_rad_s));
    a->Visit(SYSID_NVP(dominance_offset_v));
    a->Visit(SYSID_NVP(dominance_duration_s));
    a->Visit(SYSID_NVP(dominance_min_speed_mps));
    a->Visit(SYSID_NVP(loop_period_s));
    a->Visit(SYSID_NVP(loop_peak_forward_v));
    a->Visit(SYSID_NVP(loop_peak_backward_v));
    a->Visit(SYSID_NVP(loop_levels_v));
    a->Visit(SYSID_NVP(loop_min_relative_width));
    a->Visit(SYSID_NVP(loop_min_start_ratio));
    a->Visit(SYSID_NVP(loop_sine_offset_v));
    a->Visit(SYSID_NVP(loop_sine_amplitude_v));
    a->Visit(SYSID_NVP(loop_sine_frequencies_hz));
    a->Visit(SYSID_NVP(loop_sine_frequency_hz));
    a->Visit(SYSID_NVP(loop_sine_amplitudes_v));
    a->Visit(SYSID_NVP(loop_min_rate_ratio));
    a->Visit(SYSID_NVP(loop_min_amplitude_change));
  }
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

struct StageFacts {
  std::string stage_name;
  std::vector<StageFact> facts;  ///< the facts run, in id order
  /// Each fact's numbers as typed fields and the experiments behind them (libsysid/src/paper/
  /// facts_results.hpp, not API); null in a table read back from JSON.
  std::shared_ptr<const paper::FactsResults> results;

  const StageFact* Find(const std::string& id) const;
  /// Every required fact that was run is met.
  bool RequiredMet() const;
  /// {"stage": ..., "facts": [{"id", "fact", "paper", "virtual", "tolerance", "met", "required",
  ///  "note", "values": {...}}], "required_met": bool}
  std::string ToJson() const;
  /// A Markdown table: id | fact | paper | stage | tolerance | met.
  std::string ToMarkdown() const;
};

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
