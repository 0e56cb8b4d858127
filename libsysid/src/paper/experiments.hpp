// Private: the paper's experiments on a stage, each simulated once and shared by the facts that
// read it (F1, F2 and F6 read the pulse test; F3 and F5 the delay tuning; F4 and F5 the
// tracking runs; F5 and F7 the networks).
#ifndef SYSID_SRC_PAPER_EXPERIMENTS_HPP_
#define SYSID_SRC_PAPER_EXPERIMENTS_HPP_

#include <cstdint>
#include <optional>
#include <vector>

#include "sysid/control.hpp"
#include "sysid/delay.hpp"
#include "sysid/dominance.hpp"
#include "sysid/identify.hpp"
#include "sysid/nn.hpp"
#include "sysid/stage.hpp"
#include "sysid/stage_facts.hpp"

namespace sysid::paper {

/// One pulse's steady velocity.
struct Plateau {
  double u_v = 0;    ///< [V] pulse amplitude
  double v_mps = 0;  ///< [m/s] steady velocity; NaN when the pulse gave no plateau
};

struct PulseExperiment {
  Recording recording;
  PulseIdentificationResult identification;  ///< least squares with the paper's a3, tau = 0
  std::vector<Plateau> plateaus;             ///< in pulse order
};

struct DelayExperiment {
  DelayTuningResult tuning;    ///< its curve holds tau = 0
  double rms_at_zero_mps = 0;  ///< [m/s] RMS dv at tau = 0
};

/// Where the networks' training and test sets lie in (v, a) and how noisy a is: F7's context.
struct SetCoverage {
  double training_max_abs_v_mps = 0, training_max_abs_a_mps2 = 0;  ///< [m/s], [m/s^2]
  double test_max_abs_v_mps = 0, test_max_abs_a_mps2 = 0;          ///< [m/s], [m/s^2]
  double test_rows_outside_training_box_fraction = 0;  ///< outside the training (v, a) box
  /// [m/s^2] RMS of a minus its centred 21-sample moving average (differentiation noise).
  double training_a_noise_rms_mps2 = 0;
  double training_a_rms_mps2 = 0;             ///< [m/s^2]
  double training_rest_fraction = 0;          ///< rows with |v| < kRestSpeedMps
  double training_u_variance_at_rest_v2 = 0;  ///< [V^2] spread of u over those rows
};

/// A network's mean squared error of u [V^2] on the training and test sets.
struct SetMse {
  double train_v2 = 0, test_v2 = 0;
};

struct NetworkExperiment {
  NeuralNetwork dominant;                    ///< v -> u, FactsOptions::training
  NeuralDataset train_v;                     ///< its training set
  SetMse dominant_mse, dominant_moving_mse;  ///< all rows; rows with |v| >= kRestSpeedMps
  SetCoverage coverage;
  bool typical_trained = false;  ///< the rest is set only then (F7 asked)
  SetMse typical_mse, typical_moving_mse;
  /// [V^2] the least MSE any function of v (of v and a) can reach (k-NN estimate).
  SetMse irreducible_v, irreducible_va;
};

/// F7 splits every MSE at this speed [m/s]: below it the stage is at rest (10 encoder counts
/// per millisecond), where u spans the dead zone and no function of (v, a) can follow it.
constexpr double kRestSpeedMps = 1e-3;

/// One PI run on the smooth profile and the measures F4 reads from it.
struct TrackingRun {
  double frequency_hz = 0;  ///< [Hz]
  FeedforwardScheme scheme = FeedforwardScheme::kNone;
  double max_error_m = 0;      ///< [m]
  double ripple_m = 0;         ///< [m] RippleAmplitude (measures.hpp)
  double motion_ripple_m = 0;  ///< [m] MotionRippleOf's RMS
  double ringing_hz = 0;       ///< [Hz] its periodogram peak
  long saturated_samples = 0;
  double max_abs_u_v = 0;  ///< [V]
};

/// One open-loop sinusoid of F8: u = amplitude sin(2 pi f t - pi/2) + offset, its second period.
struct LoopSine {
  double amplitude_v = 0;     ///< [V]
  double frequency_hz = 0;    ///< [Hz]
  VoltageLoop loop;           ///< areas, spans and starts of the analysed period (no traces)
  double mean_width_mps = 0;  ///< [m/s] LoopMeanWidth(loop); NaN when the stage never moves
};

struct LoopExperiment {
  VoltageLoop triangle;                   ///< levels: FactsOptions::loop_levels_v
  std::vector<LoopSine> frequency_sweep;  ///< in frequency order
  std::vector<LoopSine> amplitude_sweep;  ///< in amplitude order
};

class Experiments {
 public:
  /// `typical_network`: also train the typical (v, a) network with the dominant one (F7).
  Experiments(const StageParameters& stage, const FactsOptions& options,
              const FactsProgress& progress, bool typical_network);

  const StageParameters& stage() const { return stage_; }
  const FactsOptions& options() const { return o_; }

  const PulseExperiment& Pulses();
  const DelayExperiment& Delay();
  const NetworkExperiment& Networks();
  /// PI tracking at every frequency, alone and, with `feedforward`, with the analytic and the
  /// network inverse.
  void Track(bool feedforward);
  /// A run Track made; throws NumericalError when there is none.
  const TrackingRun& Run(double frequency_hz, FeedforwardScheme scheme) const;
  /// Per frequency, the max |e| [m] of dominant networks from FactsOptions::
  /// network_initializations initial weights, the first being Run(f, kNetwork)'s.
  std::vector<std::vector<double>> NetworkSpread();
  /// The dominance test's analysis (the pulse model, tau = 0, as the paper compares x'' with
  /// a1 x'(t)).
  const DominanceResult& Dominance();
  const LoopExperiment& Loops();

  // What has been run so far.
  const std::optional<PulseExperiment>& pulses_run() const { return pulse_; }
  const std::optional<DelayExperiment>& delay_run() const { return delay_; }
  const std::vector<TrackingRun>& tracking_runs() const { return tracking_; }

 private:
  void Step(const std::string& step) const;
  NeuralTrainingOptions DominantTraining(int k) const;
  SmoothProfileOptions Profile(double frequency_hz) const;
  LoopSine SineLoop(double amplitude_v, double frequency_hz, std::uint64_t stream) const;
  void TrainTypical(const Recording& training, const Recording& test);

  const StageParameters& stage_;
  const FactsOptions& o_;
  const FactsProgress& progress_;
  bool typical_network_;
  std::optional<PulseExperiment> pulse_;
  std::optional<DelayExperiment> delay_;
  std::optional<NetworkExperiment> network_;
  std::vector<TrackingRun> tracking_;
  bool tracked_none_ = false, tracked_feedforward_ = false;
  std::optional<DominanceResult> dominance_;
  std::optional<LoopExperiment> loops_;
};

/// The stage's records of an open-loop input: samples [first, first + count) at the record rate
/// of a run at the control rate, t from 0 (the analyses read the encoder's logged positions).
Recording RecordedWindow(const StageParameters& stage, const StageRun& run, Eigen::Index first,
                         Eigen::Index count, const std::string& source);

}  // namespace sysid::paper

#endif  // SYSID_SRC_PAPER_EXPERIMENTS_HPP_
