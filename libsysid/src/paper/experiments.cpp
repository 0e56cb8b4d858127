// The closed-loop experiments and their cache: the pulse test, delay tuning and PI tracking on
// the smooth profile (the networks are in network_experiment.cpp, the open-loop tests in
// open_loop_experiments.cpp).
#include "paper/experiments.hpp"

#include <fmt/format.h>

#include <cmath>
#include <string>
#include <vector>

#include "paper/measures.hpp"
#include "paper/paper_numbers.hpp"
#include "sysid/error.hpp"

namespace sysid::paper {

Experiments::Experiments(const StageParameters& stage, const FactsOptions& options,
                         const FactsProgress& progress, bool typical_network)
    : stage_(stage), o_(options), progress_(progress), typical_network_(typical_network) {}

void Experiments::Step(const std::string& step) const {
  if (progress_) progress_(step);
}

const PulseExperiment& Experiments::Pulses() {
  if (pulse_) return *pulse_;
  Step("pulse test and least squares");
  PulseExperiment e;
  e.recording = RunPulseTest(stage_, o_.pulse, o_.seed);
  PulseIdentificationOptions po;
  po.fit.a3 = PulseModel().a3;
  po.fit.a3_given = true;  // the facts are the paper's experiments: its a3 on purpose
  e.identification = IdentifyFromPulses({e.recording}, po);
  for (const auto& p : e.identification.pulses)
    e.plateaus.push_back({p.pulse.amplitude_v, p.usable() ? p.v_mps : std::nan("")});
  pulse_ = std::move(e);
  return *pulse_;
}

const DelayExperiment& Experiments::Delay() {
  if (delay_) return *delay_;
  const PulseExperiment& pulses = Pulses();
  Step("delay tuning on the pulse recording");
  DelayTuningOptions d = o_.delay;
  d.threads = o_.threads;
  // The paper's procedure (and F3's reference): velocity from the encoder's x, and the
  // simulated x through the same filter, not the recording's v column against the simulated
  // true velocity.
  d.motion.prefer_velocity_column = false;
  DelayExperiment e;
  e.tuning = TuneDelay(pulses.identification.model, {pulses.recording}, d);
  if (!IsSolutionUsable(e.tuning.termination))
    throw NumericalError("stage facts: delay tuning failed: " + e.tuning.message);
  // The curve holds tau_min = 0 (Validate: tau_min_s = 0, curve_points >= 2).
  double cost0 = std::nan("");
  for (const auto& [tau, cost] : e.tuning.curve)
    if (tau == 0.0) cost0 = cost;
  e.rms_at_zero_mps = std::sqrt(cost0 / static_cast<double>(e.tuning.samples));
  delay_ = std::move(e);
  return *delay_;
}

// The dominant network's training options, from the k-th initial weights (k = 0: the network
// of F5's NN row). One thread, as every network of the facts. Training does not depend on the
// thread count or on where malloc puts its buffers (nn kernels test), so this only keeps the
// facts' CPU use predictable beside the experiments' own threads.
NeuralTrainingOptions Experiments::DominantTraining(int k) const {
  NeuralTrainingOptions t = o_.training;
  t.threads = 1;
  // Restart r of network k uses seed + k * restarts + r: no two networks share a start.
  t.seed += static_cast<std::uint64_t>(k) * static_cast<std::uint64_t>(t.restarts);
  return t;
}

SmoothProfileOptions Experiments::Profile(double frequency_hz) const {
  SmoothProfileOptions p;
  p.frequency_hz = frequency_hz;
  p.amplitude_m = o_.track_amplitude_m;
  p.cycles = o_.track_cycles;
  p.sample_rate_hz = stage_.rig.sample_rate_hz;
  return p;
}

void Experiments::Track(bool feedforward) {
  if (tracked_none_ && (!feedforward || tracked_feedforward_)) return;
  FrictionModel model;
  const NeuralNetwork* network = nullptr;
  if (feedforward) {
    model = Delay().tuning.model;
    network = &Networks().dominant;
  }
  std::vector<FeedforwardScheme> schemes;
  if (!tracked_none_) schemes.push_back(FeedforwardScheme::kNone);
  if (feedforward && !tracked_feedforward_)
    schemes.insert(schemes.end(), {FeedforwardScheme::kAnalytic, FeedforwardScheme::kNetwork});
  for (double f : o_.track_frequencies_hz) {
    const SmoothProfileOptions p = Profile(f);
    const PositionReference ref = MakeSmoothProfile(p);
    const auto runs =
        TrackSchemes(stage_, o_.seed, ref, o_.pi, schemes, {&model, network},
                     [&](FeedforwardScheme s, std::size_t) {
                       Step(fmt::format("PI tracking at {} Hz, feedforward {}", f, ToString(s)));
                     });
    for (const auto& run : runs) {
      const TrackingResult& t = run.result;
      TrackingRun row;
      row.frequency_hz = f;
      row.scheme = run.scheme;
      row.max_error_m = t.max_error_m;
      row.ripple_m = RippleAmplitude(t.e_m, p);
      const MotionRipple motion = MotionRippleOf(t.e_m, p, o_.motion_ripple_window_s);
      row.motion_ripple_m = motion.rms_m;
      row.ringing_hz = motion.ringing_hz;
      row.saturated_samples = t.saturated_samples;
      row.max_abs_u_v = t.max_abs_u_v;
      tracking_.push_back(row);
    }
  }
  tracked_none_ = true;
  if (feedforward) tracked_feedforward_ = true;
}

const TrackingRun& Experiments::Run(double frequency_hz, FeedforwardScheme scheme) const {
  for (const auto& row : tracking_)
    if (row.frequency_hz == frequency_hz && row.scheme == scheme) return row;
  throw NumericalError(fmt::format("stage facts: no tracking run at {:g} Hz with feedforward {}",
                                   frequency_hz, ToString(scheme)));
}

// On this kind of stage networks of equal MSE differ in how they cross v = 0, where the data
// (the stage at rest while u spans the dead zone) does not decide, and that decides the onset.
std::vector<std::vector<double>> Experiments::NetworkSpread() {
  Track(true);
  std::vector<std::vector<double>> errors;
  std::vector<PositionReference> refs;
  for (double hz : o_.track_frequencies_hz) {
    errors.push_back({Run(hz, FeedforwardScheme::kNetwork).max_error_m});
    refs.push_back(MakeSmoothProfile(Profile(hz)));
  }
  const FrictionModel model = Delay().tuning.model;
  for (int k = 1; k < o_.network_initializations; ++k) {
    Step(fmt::format("dominant network from initial weights {} of {}", k + 1,
                     o_.network_initializations));
    const NeuralNetwork net =
        TrainNeuralNetwork(Networks().train_v, nullptr, DominantTraining(k)).network;
    for (std::size_t i = 0; i < refs.size(); ++i) {
      const auto runs = TrackSchemes(stage_, o_.seed, refs[i], o_.pi, {FeedforwardScheme::kNetwork},
                                     {&model, &net});
      errors[i].push_back(runs.front().result.max_error_m);
    }
  }
  return errors;
}

}  // namespace sysid::paper
