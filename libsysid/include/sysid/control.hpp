// Discrete PI position control with feedforward, a closed-loop runner and reference profiles.
//
// At every sample k (period Ts) the controller reads the position x_k and computes
//   e_k = x_ref,k - x_k,   I_k = I_{k-1} + Ts e_k   (backward-rectangle integral of e [m s]),
//   u_k = sat(Kp e_k + Ki I_k + u_ff,k),   sat(.) = clip to [-u_max, u_max].
// Anti-windup by conditional integration (clamping): the integral step is skipped when the
// unclipped output is beyond a limit AND e_k would push it further out; the integral then holds
// its value instead of winding up, and resumes as soon as the error changes sign or the output
// comes back inside the limits. The paper's gains are the defaults.
#ifndef SYSID_CONTROL_HPP_
#define SYSID_CONTROL_HPP_

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <complex>
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "sysid/io.hpp"
#include "sysid/model.hpp"
#include "sysid/serialize.hpp"

namespace sysid {

class VirtualStage;
class NeuralNetwork;
class HysteresisModel;
class PiezoStack;
struct Recording;
struct StageParameters;
struct StackParameters;

enum class AntiWindup { kNone, kConditionalIntegration };

struct PiOptions {
  double kp_v_per_m = 19000;     ///< [V/m] proportional gain (paper)
  double ki_v_per_m_s = 660000;  ///< [V/(m s)] integral gain (paper)
  double sample_time_s = 1e-3;   ///< [s] Ts > 0
  double u_max_v = 10.0;         ///< [V] output saturation +-u_max_v, > 0
  AntiWindup anti_windup = AntiWindup::kConditionalIntegration;
  /// The fields, in file order (sysid/serialize.hpp).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(kp_v_per_m));
    a->Visit(SYSID_NVP(ki_v_per_m_s));
    a->Visit(SYSID_NVP(sample_time_s));
    a->Visit(SYSID_NVP(u_max_v));
    a->Visit(SYSID_NVP(anti_windup));
  }
  void Validate() const;  ///< throws OptionsError naming the field and the rule
  /// Gains that are stable on the actuator-delay preset (StageParameters::ActuatorDelay()):
  /// Kp = 3000 V/m, Ki = 104100 V/(m s) (the paper's ratio Ki/Kp = 34.7 1/s). The paper's
  /// Kp = 19000 V/m puts the crossover of Kp a3 / (s (s + a1)) near 330 rad/s, where that
  /// stage's 3.5 ms of delay and lag cost ~66 degrees: there that loop limit-cycles at +-10 V.
  /// The default velocity-source stage runs the paper's gains (the defaults above).
  static PiOptions ForActuatorDelayStage();
};

/// Gain and phase margins of a linear open loop L(j omega). NaN where the sweep found no
/// crossing.
struct LoopMargins {
  static constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
  double crossover_rad_s = kNone;        ///< [rad/s] gain crossover: the last |L| = 1 going down
  double phase_margin_deg = kNone;       ///< [deg] 180 + arg L there, in (-180, 180]
  double phase_crossover_rad_s = kNone;  ///< [rad/s] the first arg L = -180 (mod 360) going down
  double gain_margin = kNone;            ///< 1 / |L| there (> 1: the loop has gain to spare)
  /// The fields, in file order (sysid/serialize.hpp): a crossing the sweep did not find is null.
  /// The derived crossover_hz (after crossover_rad_s), gain_margin_db (after gain_margin) and
  /// stable (last) are computed as they are written and read into nothing: a reader takes the
  /// four fields.
  template <class Archive>
  void Serialize(Archive* a) {
    double crossover_hz = CrossoverHz();
    double gain_margin_db = GainMarginDb();
    bool stable = Stable();
    a->Visit(SYSID_NVP(crossover_rad_s).NaNAsNull().ExclusiveMinimum(0).Required());
    a->Visit(SYSID_NVP(crossover_hz).NaNAsNull());
    a->Visit(SYSID_NVP(phase_margin_deg).NaNAsNull().Minimum(-180).Maximum(180).Required());
    a->Visit(SYSID_NVP(phase_crossover_rad_s).NaNAsNull().ExclusiveMinimum(0).Required());
    a->Visit(SYSID_NVP(gain_margin).NaNAsNull().ExclusiveMinimum(0).Required());
    a->Visit(SYSID_NVP(gain_margin_db).NaNAsNull());
    a->Visit(SYSID_NVP(stable));
  }
  /// A gain crossover with phase margin > 0, and gain margin > 1 or no phase crossover.
  bool Stable() const;
  /// [Hz] the gain crossover; NaN when none was found.
  double CrossoverHz() const { return crossover_rad_s / (2 * 3.14159265358979323846); }
  /// [dB] 20 log10 of the gain margin; NaN when there is no phase crossover.
  double GainMarginDb() const { return 20 * std::log10(gain_margin); }
};

/// The margins of `open_loop` (omega [rad/s] -> L(j omega)) between w_min and w_max [rad/s]
/// (0 < w_min < w_max): a log-spaced sweep of `points` (>= 16, <= 10^7) samples, arg L
/// unwrapped from w_min, brackets each crossing; bisection refines it to 1e-12 relative.
LoopMargins ComputeLoopMargins(const std::function<std::complex<double>(double)>& open_loop,
                               double w_min_rad_s, double w_max_rad_s, int points = 20000);

/// The open loop of the discrete PI law above around steady motion of the rough model in one
/// direction (+1: a1p, -1: a1n). In steady sliding the Coulomb term is constant, so the
/// position responds to u as a3 / (s (s + a1 e^(-s tau))); the sample-and-hold adds half a
/// sample of delay, the actuator `extra_delay_s` [s] more (e.g. a driver lag), and the PI law is
/// exact at z = e^(j omega Ts):
///   L(j omega) = (Kp + Ki Ts / (1 - e^(-j omega Ts))) a3 e^(-j omega (Ts/2 + extra_delay_s))
///                / (j omega (j omega + a1 e^(-j omega tau)))
/// A linear view: stick-slip, the dead zone and saturation are outside it.
std::complex<double> RoughModelPiLoop(const FrictionModel& model, int direction,
                                      const PiOptions& pi, double omega_rad_s,
                                      double extra_delay_s = 0);

/// ComputeLoopMargins of RoughModelPiLoop from 0.1 rad/s (lower, to where |L| > 1, for a
/// low-gain loop whose crossover lies below it) to the Nyquist frequency pi / Ts. Throws
/// OptionsError for Kp = Ki = 0 (no loop).
LoopMargins RoughModelPiMargins(const FrictionModel& model, int direction, const PiOptions& pi,
                                double extra_delay_s = 0);

/// The margins of one direction of sliding, as a margins report lists them.
struct PiMarginsDirection {
  std::string direction;  ///< "forward" (a1p) or "backward" (a1n)
  double a1_per_s = 0;    ///< [1/s] the model's a1p or a1n
  LoopMargins margins;
  /// The fields, in file order (sysid/serialize.hpp): the margins beside the name and a1.
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(direction).Required());
    a->Visit(SYSID_NVP(a1_per_s).Required());
    a->Visit(SYSID_NVP(margins).Inline());
  }
};

/// The PI gains' margins on an identified rough model, both directions.
struct PiMarginsReport {
  PiOptions pi;                ///< the gains and the rate (the saturation plays no part)
  double extra_delay_s = 0;    ///< [s] actuator delay beyond the sample-and-hold
  double tau_s = 0;            ///< [s] the model's delay
  double a3_mps2_per_v = 0;    ///< [m/(s^2 V)] the model's actuator gain
  std::vector<PiMarginsDirection> directions;  ///< forward (a1p), then backward (a1n)
  const LoopMargins& forward() const { return directions.at(0).margins; }
  const LoopMargins& backward() const { return directions.at(1).margins; }
  /// The fields, in file order (sysid/serialize.hpp): of the PI's, the gains and the rate.
  template <class Archive>
  void Serialize(Archive* a) {
    FieldSlice<Archive> gains(a, 0, 3);
    pi.Serialize(&gains);
    a->Visit(SYSID_NVP(extra_delay_s).Minimum(0).Required());
    a->Visit(SYSID_NVP(tau_s).Minimum(0).Required());
    a->Visit(SYSID_NVP(a3_mps2_per_v).ExclusiveMinimum(0).Required());
    a->Visit(SYSID_NVP(directions).Required());
  }
};
/// RoughModelPiMargins in both directions.
PiMarginsReport AnalyzePiMargins(const FrictionModel& model, const PiOptions& pi,
                                 double extra_delay_s = 0);
/// {"kp_v_per_m", "ki_v_per_m_s", "sample_time_s", "extra_delay_s", "tau_s", "a3_mps2_per_v",
///  "directions": [{"direction": "forward" | "backward", "a1_per_s", "crossover_rad_s",
///  "crossover_hz", "phase_margin_deg", "phase_crossover_rad_s", "gain_margin",
///  "gain_margin_db", "stable"}]}; a crossing the sweep did not find is null.
std::string ToJson(const PiMarginsReport& report, int indent = 2);

/// The discrete PI law above, one sample at a time.
class PiController {
 public:
  explicit PiController(const PiOptions& options = {});
  /// u_k [V] from the error e_k [m] and the feedforward u_ff,k [V]; advances the integral.
  double Update(double error_m, double u_ff_v = 0.0);
  void Reset();
  double integral_m_s() const { return integral_m_s_; }  ///< [m s] I_k
  bool saturated() const { return saturated_; }          ///< last output was clipped
  const PiOptions& options() const { return options_; }

 private:
  PiOptions options_;
  double integral_m_s_ = 0;
  bool saturated_ = false;
};

/// The reference at one control sample k, as the loop hands it to its feedforward.
struct ReferenceSample {
  double x_m = 0;     ///< [m] position x_ref,k
  double v_mps = 0;   ///< [m/s] velocity v_ref,k
  double a_mps2 = 0;  ///< [m/s^2] acceleration a_ref,k
};
/// Feedforward voltage [V] at sample k from the reference at k. RunClosedLoop calls it once per
/// sample, in order, so a causal inverse steps inside it with only the past; each takes the
/// inputs its stepper's Step takes: the friction inverse v and a, a velocity network its named
/// inputs (v, a), a hysteresis inverse x.
using Feedforward = std::function<double(const ReferenceSample& reference)>;

/// A sampled position reference; all vectors have the same length.
struct PositionReference {
  Eigen::VectorXd t_s;     ///< [s]
  Eigen::VectorXd x_m;     ///< [m]
  Eigen::VectorXd v_mps;   ///< [m/s]
  Eigen::VectorXd a_mps2;  ///< [m/s^2]
  std::string description;
};

/// The smooth back-and-forth profile of the tracking experiment. One period 1/f: dwell at
/// x = 0 for d/f, move to x = amplitude_m in Tm = (1 - 2d)/(2f), dwell d/f, move back in Tm
/// (d = dwell_fraction). Each move follows the minimum-jerk polynomial
///   s(tau) = 10 tau^3 - 15 tau^4 + 6 tau^5,  tau = (t - t_start) / Tm in [0, 1],
/// so position, velocity and acceleration are continuous and v = a = 0 at both ends (the
/// stage starts from rest each stroke, where friction makes tracking hardest). Peak velocity
/// 1.875 amplitude_m / Tm. The profile begins with a dwell at 0 and repeats `cycles` times.
struct SmoothProfileOptions {
  double frequency_hz = 0.5;     ///< [Hz] f > 0 (the paper uses 0.5 and 1.0)
  double amplitude_m = 0.01;     ///< [m] stroke length, != 0
  double dwell_fraction = 0.1;   ///< [1] of the period spent at rest at each end, in [0, 0.5)
  int cycles = 2;                ///< >= 1
  double sample_rate_hz = 1000;  ///< [Hz] > 0
  /// The fields, in file order (sysid/serialize.hpp).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(frequency_hz));
    a->Visit(SYSID_NVP(amplitude_m));
    a->Visit(SYSID_NVP(dwell_fraction));
    a->Visit(SYSID_NVP(cycles));
    a->Visit(SYSID_NVP(sample_rate_hz));
  }
  void Validate() const;
};
PositionReference MakeSmoothProfile(const SmoothProfileOptions& options = {});
/// The smooth profile for `stage`: sampled at the stage's rate (options.sample_rate_hz is
/// replaced) and checked to stay inside the stage's travel: the stroke from
/// initial_position_m must end within [travel_min_m, travel_max_m], else OptionsError with
/// field "amplitude_m".
PositionReference MakeStageProfile(const StageParameters& stage, SmoothProfileOptions options);

/// Reference from sampled positions (e.g. a CSV column): v and a by central differences.
PositionReference ReferenceFromPositions(const Eigen::VectorXd& t_s, const Eigen::VectorXd& x_m);
/// Reference from a CSV with columns t [s] and x_ref [m] (or x [m] when there is no x_ref), as
/// ReferenceFromPositions; the description is the path. MAT/HDF5 files through `mapping`.
/// Throws InputError as ReadRecording.
PositionReference ReadPositionReference(const std::string& path,
                                        const SourceMapping& mapping = {});
/// `ref` at the control rate `control_rate_hz` [Hz] when it is sampled uniformly at a rate that
/// divides it (R = control rate / reference rate a whole number: a 1 kHz trajectory on a 10 kHz
/// loop, R = 10): between two reference samples x_ref, v_ref and a_ref are each interpolated
/// linearly (v_ref and a_ref being the reference's own central differences, at its rate), so
/// the feedforward sees the trajectory's acceleration rather than the kinks of a line or the
/// steps of a hold. The first and last t stay; R = 1 returns `ref` unchanged. A reference at
/// another rate or not uniform is returned unchanged (CheckReferenceForPlant refuses it, naming
/// the sample). Throws InputError when the result would exceed kMaxReferenceSamples.
PositionReference ReferenceAtControlRate(const PositionReference& ref, double control_rate_hz);
/// The most samples ReferenceAtControlRate makes (2e7: 160 MB per column set of four).
inline constexpr double kMaxReferenceSamples = 2e7;

/// Checks a reference read from a file against the plant that will track it, before any run:
/// sampled uniformly at the plant's control rate `control_rate_hz` [Hz] (the loop takes one
/// reference sample per control period; ReferenceAtControlRate brings a slower one there), and every x_ref inside [x_min_m, x_max_m] [m] (the
/// plant's travel). Throws InputError naming ref.description, the sample and the rule.
void CheckReferenceForPlant(const PositionReference& ref, double control_rate_hz, double x_min_m,
                            double x_max_m);

/// Traces and metrics of a closed-loop run; row k is sample k.
struct TrackingResult {
  Eigen::VectorXd t_s, x_ref_m, x_m, e_m, u_v, u_ff_v;  ///< [s], [m], [m], [m], [V], [V]
  double max_error_m = 0;                               ///< [m] max |e_k|
  double rms_error_m = 0;                               ///< [m] sqrt(mean e_k^2)
  double rms_u_v = 0;                                   ///< [V] control effort sqrt(mean u_k^2)
  double max_abs_u_v = 0;                               ///< [V] max |u_k|
  double total_variation_v = 0;                         ///< [V] sum |u_k - u_{k-1}| (chattering)
  long saturated_samples = 0;                           ///< samples where the PI output was clipped
  /// The metrics, in file order (sysid/serialize.hpp); the traces are not in the JSON.
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(max_error_m).Minimum(0).Required());
    a->Visit(SYSID_NVP(rms_error_m).Minimum(0).Required());
    a->Visit(SYSID_NVP(rms_u_v).Minimum(0).Required());
    a->Visit(SYSID_NVP(max_abs_u_v).Minimum(0).Required());
    a->Visit(SYSID_NVP(total_variation_v).Minimum(0).Required());
    a->Visit(
        SYSID_NVP(saturated_samples).Minimum(0).Maximum(static_cast<double>(1L << 40)).Required());
  }
  std::string BriefReport() const;
  /// BriefReport plus every metric: max |u|, total variation, saturated samples, samples.
  std::string FullReport() const;
};

/// The traces of a run as a recording with columns t [s], x_ref [m], x [m], e [m], u [V],
/// u_ff [V] and metadata ff = `scheme` and the units (`sysid track -o`'s track_<ff>.csv).
Recording TrackingRecording(const TrackingResult& result, const std::string& scheme);

/// The options as JSON, every field (anti_windup "none" or "conditional-integration"), and
/// their readers: every key optional, the result validated, InputError "SOURCE:LINE:COL: NAME:
/// expected ..., found ..." otherwise (as MotionOptionsFromJson).
std::string ToJson(const PiOptions& options, int indent = 2);
std::string ToJson(const SmoothProfileOptions& options, int indent = 2);
PiOptions PiOptionsFromJson(std::string_view text, const std::string& source_name);
SmoothProfileOptions SmoothProfileOptionsFromJson(std::string_view text,
                                                  const std::string& source_name);

/// The run's metrics as JSON (max_error_m, rms_error_m, rms_u_v, max_abs_u_v,
/// total_variation_v, saturated_samples); the traces are not included. `sysid track --json`
/// lists one per feedforward scheme.
std::string ToJson(const TrackingResult& result, int indent = 2);
/// Reads the metrics ToJson(TrackingResult) writes (the traces stay empty). Throws InputError
/// "SOURCE:LINE:COL: NAME: expected ..., found ..." for a missing key or a bad value.
TrackingResult TrackingResultFromJson(std::string_view text, const std::string& source_name);

/// One sample of a plant: applies u [V] for one period and returns the next measured position
/// [m].
using PlantStep = std::function<double(double u_v)>;

/// Runs the PI loop (with `feedforward`, or none when empty) over `reference`, starting from
/// the reading `x0_measured_m`. The controller's sample time must match the reference's.
TrackingResult RunClosedLoop(const PlantStep& plant, double x0_measured_m,
                             const PositionReference& reference, const PiOptions& pi = {},
                             const Feedforward& feedforward = {});
/// The same on the virtual stage (sample time taken from the stage).
TrackingResult RunClosedLoop(VirtualStage& stage, const PositionReference& reference,
                             PiOptions pi = {}, const Feedforward& feedforward = {});

/// A feedforward that plays precomputed voltages u_ff_v[k] [V], one per call. RunClosedLoop
/// calls its feedforward exactly once per sample, in order, so a feedforward computed over the
/// whole reference beforehand (e.g. the analytic inverse with the delayed velocity
/// v_ref(t - tau)) plays back in step. Throws InternalError if called more often than it has
/// values.
Feedforward SampledFeedforward(Eigen::VectorXd u_ff_v);

/// The feedforward schemes of the tracking experiment: PI alone, PI + the analytic inverse
/// model, PI + the neural inverse model (the stage's), PI + a hysteresis model's inverse of
/// the position reference (the piezo stack's).
enum class FeedforwardScheme { kNone, kAnalytic, kNetwork, kHysteresis };
std::string ToString(FeedforwardScheme scheme);  ///< "none", "analytic", "nn", "hysteresis"
/// Inverse of ToString. Throws OptionsError naming the accepted names.
FeedforwardScheme ParseFeedforwardScheme(const std::string& name);
/// A comma-separated list of scheme names ("none,analytic"), in order. Throws OptionsError
/// (field "schemes") for an unknown name or an empty list.
std::vector<FeedforwardScheme> ParseFeedforwardSchemes(const std::string& comma_list);
/// True when `schemes` holds `scheme`.
bool Uses(const std::vector<FeedforwardScheme>& schemes, FeedforwardScheme scheme);

/// The inverse models the schemes play; each is needed only by its scheme (not owned).
struct InverseModels {
  const FrictionModel* model = nullptr;    ///< for kAnalytic
  const NeuralNetwork* network = nullptr;  ///< for kNetwork
  const HysteresisModel* hysteresis = nullptr;  ///< for kHysteresis
};

/// The feedforward of `scheme` over `reference` sampled every `dt_s` [s]: empty for kNone;
/// otherwise the scheme's inverse stepped inside the loop, one sample per call with only the
/// past, as a real-time controller runs it: the analytic inverse (FrictionInverseStepper on
/// v_ref,k and a_ref,k: the delayed velocity v_ref(t - tau) from its delay line), the network
/// (NetworkStepper on its inputs v, a), the hysteresis inverse u = H^-1[x_ref]
/// (HysteresisModel::InverseStepper on x_ref,k). The models' checks (OptionsError,
/// NumericalError when not invertible) are thrown here, before the loop runs; a reference the
/// hysteresis model cannot reach stops the loop at that sample with Invert's InputError (the
/// hysteresis feedforward refers to *models.hysteresis, which must outlive it). Throws
/// OptionsError when the scheme's model is missing.
Feedforward SchemeFeedforward(FeedforwardScheme scheme, const PositionReference& reference,
                              double dt_s, const InverseModels& models);

/// One scheme's closed-loop run.
struct SchemeTracking {
  FeedforwardScheme scheme = FeedforwardScheme::kNone;
  TrackingResult result;
  std::string stage_limits;  ///< StageStatus::Describe() of the run's stage
  /// The fields of a `sysid track --json` "schemes" entry, in file order (sysid/serialize.hpp):
  /// the scheme's name (ToString) as "ff", the result's metrics beside it.
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(scheme).Renamed("ff").Required());
    a->Visit(SYSID_NVP(result).Inline());
    a->Visit(SYSID_NVP(stage_limits).Required());
  }
};
/// {"ff", the result's metrics (ToJson(TrackingResult)), "stage_limits"}: one entry of
/// `sysid track --json`'s "schemes".
std::string ToJson(const SchemeTracking& run, int indent = 2);
/// `sysid track --json` and its summary.json: {"plant", "reference" (its description),
/// "kp_v_per_m", "ki_v_per_m_s", "schemes": [ToJson(run), ...]} plus, for a single run, its
/// "max_error_m" and "rms_error_m".
std::string TrackingSummaryToJson(const std::string& plant, const PositionReference& reference,
                                  const PiOptions& pi, const std::vector<SchemeTracking>& runs,
                                  int indent = 2);

/// PI tracking of `reference` once per scheme, each on a fresh VirtualStage(stage, seed): every
/// scheme sees the same plant and noise. pi.sample_time_s is taken from the stage. `on_scheme`
/// (optional) is called before each run with the scheme and its 0-based index. The hysteresis
/// scheme is the stack's (OptionsError here).
std::vector<SchemeTracking> TrackSchemes(
    const StageParameters& stage, std::uint64_t seed, const PositionReference& reference,
    PiOptions pi, const std::vector<FeedforwardScheme>& schemes, const InverseModels& models,
    const std::function<void(FeedforwardScheme, std::size_t)>& on_scheme = {});

/// PI tracking of `reference` once per scheme, each on a fresh FrictionModelPlant(plant,
/// sample_time_s) (sysid/simulate.hpp: the identified model simulated by the delayed
/// stick-slip simulator, from rest at x = reference.x_m[0], exact x: no encoder). `sysid track
/// --plant M.json`. pi.sample_time_s is sample_time_s; the reference must be sampled at it.
/// stage_limits names the plant's events ("model plant: N stick/slip events"). The hysteresis
/// scheme is the stack's (OptionsError).
std::vector<SchemeTracking> TrackModelSchemes(
    const FrictionModel& plant, double sample_time_s, const PositionReference& reference,
    PiOptions pi, const std::vector<FeedforwardScheme>& schemes, const InverseModels& models,
    const std::function<void(FeedforwardScheme, std::size_t)>& on_scheme = {});

// ---- The piezo stack (sysid/stack.hpp; docs/piezo_stack.md) -------------------------------

/// The stack's reference waveforms: x(t) from 0 up to `stroke_m` and back, `cycles` periods of
/// 1/f, starting at rest at 0 (where the stack starts):
///   sine      x = (S/2) (1 - cos(2 pi f t))
///   triangle  x rises linearly to S in 1/(2f) and falls back (v jumps at the corners, a = 0)
enum class StackWaveform { kSine, kTriangle };
std::string ToString(StackWaveform waveform);  ///< "sine", "triangle"
/// Inverse of ToString; OptionsError (field "waveform") naming both otherwise.
StackWaveform ParseStackWaveform(const std::string& name);

struct StackReferenceOptions {
  StackWaveform waveform = StackWaveform::kSine;
  double frequency_hz = 10;        ///< [Hz] f > 0
  double stroke_m = 20e-6;         ///< [m] S > 0, peak-to-peak
  int cycles = 2;                  ///< >= 1
  double sample_rate_hz = 10000;   ///< [Hz] > 0 (the stack's control rate)
  /// OptionsError naming the field; also refuses more than kMaxStackReferenceSamples samples.
  void Validate() const;
};
/// The longest reference a stack run takes (5e7 samples: 1.6 GB of traces).
inline constexpr double kMaxStackReferenceSamples = 5e7;
PositionReference MakeStackReference(const StackReferenceOptions& options);

/// PI gains for a stack (docs/piezo_stack.md, "The PI loop"): with g = MaxStaticGain() [m/V]
/// (the steepest static slope) and w_n = 2 pi f_n,
///   Ki = 2 zeta w_n / (3 g)   (the integral path's gain at the resonance peak is 1/3),
///   Kp = 0.05 / g             (a twentieth of the static gain: adds little at the peak),
///   u_max = rig.voltage_max_v, Ts = the control period.
PiOptions StackPiOptions(const StackParameters& stack);

/// The PI loop's open loop on the stack with the hysteresis replaced by its steepest static
/// slope p0 + sum w_i (the rate terms at rate 0) and the creep by its transfer function:
///   L(j w) = C(e^(j w Ts)) (p0 + sum w_i) (1 + sum_j kappa_j / (1 + j w tau_j))
///            w_n^2 / (w_n^2 - w^2 + 2 j zeta w_n w) e^(-j w Ts / 2),
/// C(z) = Kp + Ki Ts / (1 - z^-1) the discrete PI law, e^(-j w Ts/2) the zero-order hold.
std::complex<double> StackPiLoop(const StackParameters& stack, const PiOptions& pi,
                                 double omega_rad_s);
/// ComputeLoopMargins of StackPiLoop from 0.1 rad/s to the Nyquist frequency pi / Ts.
LoopMargins StackPiMargins(const StackParameters& stack, const PiOptions& pi);

/// PI tracking of `reference` on a fresh PiezoStack(stack, seed) once per scheme (none or
/// hysteresis; OptionsError for the stage's schemes), every scheme on the same plant and noise.
/// pi.sample_time_s is taken from the stack. stage_limits holds PiezoStack::DescribeLimits().
std::vector<SchemeTracking> TrackStackSchemes(
    const StackParameters& stack, std::uint64_t seed, const PositionReference& reference,
    PiOptions pi, const std::vector<FeedforwardScheme>& schemes, const InverseModels& models,
    const std::function<void(FeedforwardScheme, std::size_t)>& on_scheme = {});

}  // namespace sysid

#endif  // SYSID_CONTROL_HPP_
