// The end-to-end pipeline: from a stage's recordings to a controller's feedforward.
//
//   identify (pulse LS) -> tune delay (NLopt) -> [refine (Ceres)] -> dominance ->
//   NN hidden-size sweep on the dominant variable(s) + the "typical" (v, a) network ->
//   compare analytic vs NN inverse on the test set and test waveforms ->
//   [PI tracking with none / analytic / NN feedforward on a stage model] -> report
//
// Inputs come from a folder laid out by convention, or from a manifest (see PipelineInputs).
#ifndef SYSID_PIPELINE_HPP_
#define SYSID_PIPELINE_HPP_

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "sysid/compare.hpp"
#include "sysid/compare_stack.hpp"
#include "sysid/control.hpp"
#include "sysid/control_tuning.hpp"
#include "sysid/delay.hpp"
#include "sysid/dominance.hpp"
#include "sysid/dominance_candidates.hpp"
#include "sysid/identify.hpp"
#include "sysid/io.hpp"
#include "sysid/nn.hpp"
#include "sysid/serialize.hpp"
#include "sysid/stage_facts.hpp"
#include "sysid/validate.hpp"

namespace sysid {

/// The recordings of one stage.
///
/// From a folder: `manifest.json` when present, e.g.
///   {"pulses": ["pulses.csv"], "training": "training.csv", "test": "test.csv",
///    "waveforms": ["waveform_square.csv"], "loops": ["loop_triangle.csv"], "stage": "stage.json",
///    "a3": 6}
/// (paths relative to the manifest), else the naming convention: pulses*.csv (pulse tests),
/// training*.csv or train*.csv (tracking training set), test*.csv (tracking test set),
/// waveform*.csv (test waveforms), loop*.csv (slow open-loop sweeps: the voltage-velocity
/// loop, optional), stage.json (a virtual-stage file, enables tracking).
///
/// **Pulse recordings alone** (no training or test set; waveforms, loops and a stage file
/// optional) are a stage data set too: the pipeline then runs what pulses allow (PulsesOnly,
/// RunPipeline) and names the recordings that would enable the rest. A training set without a
/// test set, or the reverse, is an error.
///
/// A **stack** data set (a piezo stack: no pulse test, recordings with columns t [s], u [V],
/// x [m]) is a folder with none of pulses*, train*, test* (every *.csv in it is a stack
/// recording), or a manifest {"stack": ["piezo.csv", ...]} (without the stage's keys). The
/// pipeline then fits and scores the hysteresis models instead (RunPipeline, "stack").
struct PipelineInputs {
  std::string root;                    ///< the folder or manifest it came from
  std::vector<std::string> pulses;     ///< pulse-test recordings (t, u, x), at least one
  std::string training;                ///< tracking training set (t, u, x[, v, a])
  std::string test;                    ///< tracking test set
  std::vector<std::string> waveforms;  ///< test-waveform recordings
  std::vector<std::string> loops;      ///< open-loop sweeps for the voltage-velocity loop
  std::string stage;                   ///< stage parameter file for tracking, may be empty
  std::optional<double> a3;            ///< [m/(s^2 V)] from the manifest, if given
  std::vector<std::string> stack;      ///< a stack's recordings (t, u, x); empty for a stage
  /// Applied to every recording above (`sysid pipeline --var/--rate/--scale`); empty: a CSV's
  /// own columns, a MAT/HDF5 file's top-level vectors named t, u, x (v, a).
  SourceMapping mapping;

  bool IsStack() const { return !stack.empty(); }
  /// Pulse recordings and no training or test set: identification, delay, refinement,
  /// validation on the pulses' held-out parts, margins, PI tuning and tracking on the
  /// identified model; no dominance, network or inverse comparison.
  bool PulsesOnly() const {
    return !pulses.empty() && training.empty() && test.empty() && !IsStack();
  }
  /// `base` with `mapping`: how every step and the report read these recordings.
  ReadOptions Read(ReadOptions base = {}) const {
    base.mapping = mapping;
    return base;
  }

  /// Throws InputError naming the folder and what is missing.
  static PipelineInputs FromDirectory(const std::string& dir);
  static PipelineInputs FromManifest(const std::string& path);
};

struct PipelineOptions {
  double a3 = 6.0;  ///< [m/(s^2 V)] actuator gain (manifest a3 wins)
  bool a3_given = false;  ///< a3 is the user's (else the paper's: the report warns)
  bool tune_delay = true;
  DelayTuningOptions delay;  ///< tau search (curve_points set for the report)
  bool refine = false;       ///< output-error refinement after the delay
  std::vector<int> hidden_sizes{16, 18, 20, 22, 24, 26, 28, 30, 32};
  /// LM options of the sweep (hidden is swept). The pipeline's defaults: 100 epochs with the
  /// linear output layer re-solved after each step (NeuralTrainingOptions::solve_output_layer),
  /// which reaches the noise floor in tens of epochs where the plain rule needs thousands.
  NeuralTrainingOptions training = DefaultTraining();
  /// Network inputs; empty: the dominant variable alone (the paper's approach).
  std::vector<std::string> nn_inputs;
  bool typical = true;       ///< also train the typical (v, a) network
  int typical_hidden = 120;  ///< the paper's 120 units
  int typical_max_epochs = 60;
  int typical_stride = 2;  ///< training rows used by the typical net: every n-th
  /// With pulse recordings alone (PipelineInputs::PulsesOnly): identify, tune the delay and
  /// refine on the first fraction F of each pulse recording's duration (CropRecording, as
  /// `--fit-fraction` elsewhere) and validate the model on the rest; in (0, 1], 1: fit on the
  /// whole recordings and validate on the waveforms alone. Unused with a training set.
  double pulse_fit_fraction = 0.7;
  bool track = true;       ///< PI tracking when a stage file is available
  std::vector<double> track_frequencies_hz{0.5, 1.0};
  double track_amplitude_m = 0.01;  ///< [m] stroke of the smooth profile
  PiOptions pi;             ///< the paper's gains (stable on the default velocity-source stage)
  /// Also run the paper's experiments on the stage file (RunStageFacts, F1-F8, ~10 s) and put
  /// the facts table (paper vs stage, tolerance, met) in the report and facts.json.
  bool facts = false;
  FactsOptions facts_options;  ///< the paper's experiments by default (threads: `threads`)
  /// JSON of reference numbers placed beside ours in the report (experiments/ passes the
  /// paper's); empty: none.
  std::string reference_path;
  /// Threads for every long step (delay tuning, dominance, sweep, the typical network); 0: all
  /// cores. Overrides the `threads` of `delay` and `training`; results do not depend on it.
  int threads = 0;
  /// The fields, in file order (sysid/serialize.hpp).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(a3));
    a->Visit(SYSID_NVP(tune_delay));
    a->Visit(SYSID_NVP(delay));
    a->Visit(SYSID_NVP(refine));
    a->Visit(SYSID_NVP(hidden_sizes));
    a->Visit(SYSID_NVP(training));
    a->Visit(SYSID_NVP(nn_inputs));
    a->Visit(SYSID_NVP(typical));
    a->Visit(SYSID_NVP(typical_hidden));
    a->Visit(SYSID_NVP(typical_max_epochs));
    a->Visit(SYSID_NVP(typical_stride));
    a->Visit(SYSID_NVP(pulse_fit_fraction));
    a->Visit(SYSID_NVP(track));
    a->Visit(SYSID_NVP(track_frequencies_hz));
    a->Visit(SYSID_NVP(track_amplitude_m));
    a->Visit(SYSID_NVP(pi));
    a->Visit(SYSID_NVP(facts));
    a->Visit(SYSID_NVP(facts_options));
    a->Visit(SYSID_NVP(reference_path));
    a->Visit(SYSID_NVP(threads));
  }
  void Validate() const;
  static NeuralTrainingOptions DefaultTraining();
};

/// The options as JSON, every field (nested options as objects), and the reader: every key
/// optional (absent: the defaults above, e.g. DefaultTraining()), the result validated (with
/// facts_options.Validate()), InputError "SOURCE:LINE:COL: NAME: expected ..., found ..."
/// otherwise.
std::string ToJson(const PipelineOptions& options, int indent = 2);
PipelineOptions PipelineOptionsFromJson(std::string_view text, const std::string& source_name);

struct TrackingRow {
  double frequency_hz = 0;  ///< [Hz]
  std::string scheme;       ///< "none", "analytic", "nn"
  TrackingResult result;
  /// The fields of a summary's row, in file order (sysid/serialize.hpp): the scheme as "ff",
  /// the result's two errors beside it; the traces and other metrics are the report's.
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(frequency_hz).ExclusiveMinimum(0).Required());
    a->Visit(SYSID_NVP(scheme).Renamed("ff").Required());
    a->Visit(NameValue<double>("max_error_m", &result.max_error_m).Minimum(0).Required());
    a->Visit(NameValue<double>("rms_error_m", &result.rms_error_m).Minimum(0).Required());
  }
};

/// The traces behind the report's figures, computed by RunPipeline from the data and models it
/// holds, so that the report draws what the pipeline computed and reads or simulates nothing.
struct PipelineFigures {
  struct Trace {
    std::string label;
    Eigen::VectorXd x, y;
  };
  /// The first pulse recording: measured velocity [m/s] against t [s], then the final model
  /// simulated with tau = 0 and with its tau, at the delay fit's tolerances (options.delay).
  std::vector<Trace> pulse_velocity;
  std::string pulse_velocity_note;  ///< why a simulation is missing; empty when both ran
  /// The training set against t [s]: a1 v(t - tau) and x'' [m/s^2] (the dominance figure).
  std::vector<Trace> dominance_terms;
  /// With a typical network, per set (training, then test): the data u, the typical and the
  /// dominant network's outputs [V] on every row, their MSEs and the least MSE their inputs
  /// allow (EstimateIrreducibleError) [V^2].
  struct NetworkSet {
    std::string set;
    Eigen::VectorXd targets_v, typical_v, dominant_v;
    double typical_mse = 0, dominant_mse = 0;
    double typical_floor_mse = 0, dominant_floor_mse = 0;
  };
  std::vector<NetworkSet> networks;
  /// With tracking on the stage: where PI alone rings while the stage moves (the RMS of its
  /// error minus the error's moving average above FactsOptions' motion_ripple_tolerance_m, as
  /// F4 measures it), one entry per such tracking frequency.
  struct Ringing {
    double frequency_hz = 0;    ///< [Hz] the profile's
    double sample_rate_hz = 0;  ///< [Hz] the loop's
    double rms_m = 0;           ///< [m] RMS of e minus its moving average, in motion
    double ringing_hz = 0;      ///< [Hz] the ripple's frequency
  };
  std::vector<Ringing> tracking_ringing;
  /// A stack data set: the first recording's scored part, its first samples (at most
  /// kStackFigureSamples, a few periods), against t [s]: the measured x [m] then each model's
  /// forward simulation (stack_position), the measured u [V] then each model's inverse
  /// (stack_voltage). Labels "measured" and "ROW LABEL" (the row of stack_models, from 1).
  std::string stack_source;
  std::vector<Trace> stack_position, stack_voltage;
};

/// The most samples of the stack figures' traces (PipelineFigures::stack_position).
inline constexpr Eigen::Index kStackFigureSamples = 600;

/// Reference numbers set beside ours in the report (e.g. the paper's:
/// experiments/paper_numbers.json), read by RunPipeline from options.reference_path before the
/// first step. Every key is optional; an absent one leaves its member unset.
struct PipelineReference {
  std::string label = "reference";  ///< "label"
  /// "model": friction-model parameters by name (a1p, a1n, a2p, a2n, a3 [SI], tau [s]).
  std::optional<std::vector<std::pair<std::string, double>>> model;
  std::optional<double> dominance_ratio_bound;  ///< [1] "dominance_ratio_bound"
  struct SweepRow {
    int hidden = -1;
    int epochs = 0;
    double train_mse = 0, test_mse = 0;  ///< [V^2]
  };
  std::optional<std::vector<SweepRow>> sweep;  ///< "sweep"
  struct TrackingError {
    double frequency_hz = 0;  ///< [Hz]
    std::string scheme;       ///< "none", "analytic", "nn"
    double max_error_mm = 0;  ///< [mm]
  };
  /// "tracking_max_error_mm": {"FREQUENCY": {"SCHEME": max error [mm]}}.
  std::optional<std::vector<TrackingError>> tracking_max_error_mm;
  /// The model value named `name`, if given.
  std::optional<double> ModelValue(const std::string& name) const;
};

/// Reads a reference file; InputError "PATH:LINE:COL: ..." on bad JSON or a value of the wrong
/// type.
PipelineReference ReadPipelineReference(const std::string& path);

struct PipelineResult {
  PipelineInputs inputs;
  PipelineOptions options;
  PulseIdentificationResult pulse;
  std::optional<DelayTuningResult> delay;
  std::optional<RefineResult> refine;
  FrictionModel model;                 ///< the final rough model
  DominanceSummary dominance;          ///< on the training and test sets
  std::vector<std::string> nn_inputs;  ///< the network's inputs (recording columns)
  HiddenSweepResult sweep;
  NeuralNetwork network;        ///< the sweep's chosen network
  double network_test_mse = 0;  ///< [V^2]
  std::optional<NeuralTrainingResult> typical;
  double typical_test_mse = 0;                 ///< [V^2]
  std::vector<InverseComparison> comparisons;  ///< test set, then waveforms
  /// The final model simulated free-run on every recording it was not fitted on (training,
  /// test, then each waveform) and scored (ValidateFrictionModel); a recording whose
  /// simulation fails is left out with a note.
  std::vector<Validation> validations;
  std::vector<VoltageLoop> loops;  ///< AnalyzeVoltageLoop of each inputs.loops recording
  std::vector<TrackingRow> tracking;
  /// With options.track: options.pi's linear loop margins on `model` (AnalyzePiMargins), at
  /// the stage's sample time, else at the pulse recordings' (the report's section 6).
  std::optional<PiMarginsReport> margins;
  std::optional<StageFacts> facts;  ///< when options.facts and a stage file
  /// Pulse recordings alone, with options.track: TunePi of `model` (default targets: 45 deg,
  /// 6 dB) at the margins' sample time; unset with a note when no gains meet the targets.
  std::optional<PiTuningResult> tuning;
  /// Pulse recordings alone, with options.track: PI tracking of the smooth profile
  /// (track_frequencies_hz, track_amplitude_m) on the identified model as the plant
  /// (TrackModelSchemes at the margins' sample time) with no and with analytic feedforward,
  /// under the tuned gains (options.pi when tuning failed).
  std::vector<TrackingRow> model_tracking;
  /// The steps a pulse-only run skipped, each "STEP: needs RECORDINGS" (also in notes).
  std::vector<std::string> skipped;
  /// A stack data set (inputs.IsStack()): the stage's steps above are skipped and these are
  /// filled instead. Each of StackModelSpecs fitted on the first kStackTrainFraction of every
  /// recording and scored on the rest (FitAndScoreHysteresis), and RankCandidates of each
  /// recording (which variable carries the input).
  std::vector<HysteresisSplitScore> stack_models;
  std::vector<CandidateRanking> stack_dominance;
  PipelineFigures figures;
  std::optional<PipelineReference> reference;  ///< with options.reference_path
  std::vector<std::pair<std::string, double>> step_seconds;  ///< wall time per step
  std::vector<std::string> notes;                            ///< honest remarks for the report
  /// The summary's described keys, in file order (sysid/serialize.hpp): model, skipped (a
  /// pulse-only run's), tracking, model_tracking (pulse-only), steps [{name, wall_time_s}].
  /// ToJson(PipelineResult) writes the derived and conditional keys between them (the
  /// network's, the typical network's MSEs, tuned_pi, the margins' and facts' verdicts).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(model).Required());
    a->Visit(SYSID_NVP(skipped).OmitEmpty());
    a->Visit(SYSID_NVP(tracking).Required());
    a->Visit(SYSID_NVP(model_tracking).OmitEmpty());
    a->Visit(SYSID_NVP(step_seconds).Renamed("steps").PairKeys("name", "wall_time_s").Required());
  }
};

using PipelineProgress = std::function<void(const std::string& step)>;

/// Runs every step. Throws like the steps do (InputError, NumericalError, OptionsError).
/// For a stack data set (inputs.IsStack()) the steps are: read the recordings, rank the
/// candidate variables, fit and score each hysteresis model (RunStackPipeline).
PipelineResult RunPipeline(const PipelineInputs& inputs, const PipelineOptions& options = {},
                           const PipelineProgress& progress = {});

/// The run's summary as `sysid pipeline --json` prints it (without the report's path): model
/// (ModelToJson), dominant, nn_inputs, hidden (the network's), network (NeuralNetworkToJson),
/// nn_test_mse, typical_train_mse / typical_test_mse (with a typical network), tracking
/// [{frequency_hz, ff, max_error_m, rms_error_m}], with margins: margins [{direction (forward,
/// backward), crossover_rad_s, phase_margin_deg, gain_margin, stable}], with facts: facts [{id,
/// required, met}] and facts_required_met, and steps [{name, wall_time_s [s]}] in run order.
/// NaN MSEs and crossings not found are null.
std::string ToJson(const PipelineResult& result, int indent = 2);
/// `sysid pipeline --json`: that summary after {"report": report_path}.
std::string ToJson(const PipelineResult& result, const std::string& report_path,
                   int indent = 2);
/// Reads that summary back (a "report" key, which the CLI adds, is allowed): ToJson of the
/// result gives the text again. What the summary does not carry stays default: inputs,
/// options, the pulse, delay and refinement results, the dominance analysis but its dominant
/// variable, the sweep, the typical network (only its train_mse is set), comparisons, the
/// tracking traces and metrics other than max/rms error, the margins' model, gains and phase
/// crossovers, and the facts' texts and numbers (only id, required and met). The derived values
/// are checked: hidden against the network, each margin's stable against its margins,
/// facts_required_met against the facts. A pulse-only run's summary has no dominant, nn_inputs,
/// hidden, network and nn_test_mse (they come together), and carries skipped [strings],
/// tuned_pi {kp_v_per_m, ki_v_per_m_s, sample_time_s} and model_tracking (as tracking): read
/// back into skipped, tuning->pi and model_tracking. Throws InputError "SOURCE:LINE:COL: NAME:
/// expected
/// ..., found ...".
PipelineResult PipelineResultFromJson(std::string_view text, const std::string& source_name);

/// The stack steps of RunPipeline (inputs.IsStack() required).
PipelineResult RunStackPipeline(const PipelineInputs& inputs, const PipelineOptions& options = {},
                                const PipelineProgress& progress = {});

/// One recording's verdict in a stack run's summary: of its CandidateRanking, the source, the
/// dominant variable, the margin and the linear model's r2 (NaN as null).
struct StackDominanceRow {
  std::string source;
  std::string dominant;
  double margin = 0;  ///< rms(top) / rms(second)
  double r2 = 0;      ///< 1 - SSE / SST of the linear model
  /// The fields, in file order (sysid/serialize.hpp).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(source).Required());
    a->Visit(SYSID_NVP(dominant).Required());
    a->Visit(SYSID_NVP(margin).NaNAsNull().Minimum(0).Required());
    a->Visit(SYSID_NVP(r2).NaNAsNull().Required());
  }
};

/// A stack run's summary (`sysid pipeline --json`, summary.json of the report), as
/// StackSummaryOf builds it from the run.
struct StackSummary {
  std::string report;             ///< the report's path (`sysid pipeline --json`), else ""
  std::string dataset = "stack";  ///< the kind of data set
  std::vector<std::string> recordings;
  double train_fraction = 0;      ///< [1] kStackTrainFraction
  std::string split;              ///< the split in words
  std::vector<StackDominanceRow> dominance;  ///< per recording
  std::vector<HysteresisSplitScore> models;  ///< per StackModelSpecs row
  std::vector<std::pair<std::string, double>> steps;  ///< [(step, wall time [s])], run order
  /// The fields, in file order (sysid/serialize.hpp): the report's path left out when empty.
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(report).OmitEmpty());
    a->Visit(SYSID_NVP(dataset).Required());
    a->Visit(SYSID_NVP(recordings).Required());
    a->Visit(SYSID_NVP(train_fraction).ExclusiveMinimum(0).Maximum(1).Required());
    a->Visit(SYSID_NVP(split).Required());
    a->Visit(SYSID_NVP(dominance).Required());
    a->Visit(SYSID_NVP(models).Required());
    a->Visit(SYSID_NVP(steps).PairKeys("name", "wall_time_s").Required());
  }
};
/// The summary of a stack run (RunStackPipeline), without the report's path.
StackSummary StackSummaryOf(const PipelineResult& result);
/// {report (when set), dataset "stack", recordings, train_fraction, split, dominance [{source,
/// dominant, margin, r2}], models [ToJson(HysteresisSplitScore)], steps [{name, wall_time_s}]}.
std::string ToJson(const StackSummary& summary, int indent = 2);

// The pipeline's written report (report.md, plots) is WritePipelineReport in report.hpp.

}  // namespace sysid

#endif  // SYSID_PIPELINE_HPP_
