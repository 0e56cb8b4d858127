// The open-loop experiments: the sinusoidal dominance test (F6) and the voltage-velocity loops
// of the triangle and the sinusoids (F8).
#include <fmt/format.h>

#include <cmath>

#include "paper/experiments.hpp"
#include "paper/measures.hpp"

namespace sysid::paper {
namespace {

constexpr double kHalfPi = 1.5707963267948966;

}  // namespace

Recording RecordedWindow(const StageParameters& stage, const StageRun& run, Eigen::Index first,
                         Eigen::Index count, const std::string& source) {
  const long stride = stage.RecordStride();
  Recording rec;
  rec.source = source;
  rec.names = {"t", "u", "x"};
  rec.data.resize(count, 3);
  for (Eigen::Index k = 0; k < count; ++k) {
    const Eigen::Index at = (first + k) * stride;
    rec.data(k, 0) = run.t_s[at] - run.t_s[first * stride];
    rec.data(k, 1) = run.u_v[at];
    rec.data(k, 2) = run.x_m[at];
  }
  return rec;
}

const DominanceResult& Experiments::Dominance() {
  if (dominance_) return *dominance_;
  FrictionModel model = Pulses().identification.model;
  model.tau_s = 0;  // the paper compares x'' with a1 x'(t)
  Step("sinusoidal dominance test (open loop)");
  // The stage runs at the control rate; the analysis reads the record rate's samples (every
  // stride-th), as the paper's differentiation of its logged encoder positions.
  const double rate = stage_.rig.sample_rate_hz, record_rate = stage_.RecordRateHz();
  const long stride = stage_.RecordStride();
  const auto n = static_cast<Eigen::Index>(std::llround(o_.dominance_duration_s * record_rate)) + 1;
  // One lead-in period first: the input starts at 1.5 sin(-pi/2) - 0.3 = -1.8 V, a step from
  // rest whose start-up transient (x'' ~ p v_f) is not the periodic response the paper
  // plotted; the analysed period is the second one.
  const Eigen::Index lead = n - 1;
  Eigen::VectorXd u((lead + n - 1) * stride + 1);
  for (Eigen::Index k = 0; k < u.size(); ++k) {
    const double t = static_cast<double>(k) / rate;
    u[k] = o_.dominance_amplitude_v * std::sin(o_.dominance_omega_rad_s * t - kHalfPi) +
           o_.dominance_offset_v;
  }
  const StageRun run = RunOpenLoop(stage_, u, DeriveSeed(o_.seed, 3));
  DominanceOptions dopt;
  dopt.min_speed_mps = o_.dominance_min_speed_mps;
  dopt.threads = 1;
  dominance_ =
      AnalyzeDominance(model, RecordedWindow(stage_, run, lead, n, "dominance test"), dopt);
  return *dominance_;
}

// Two periods from rest, the second one analysed (the first starts with a step to
// A sin(-pi/2) + offset from rest, a transient the periodic loop does not have). The encoder's
// x at the record rate, v by the loop analysis' central difference, as `sysid loop` on a rig's
// recording.
LoopSine Experiments::SineLoop(double amplitude_v, double frequency_hz,
                               std::uint64_t stream) const {
  const double rate = stage_.rig.sample_rate_hz, record_rate = stage_.RecordRateHz();
  const long stride = stage_.RecordStride();
  const auto period = static_cast<Eigen::Index>(std::llround(record_rate / frequency_hz));
  Eigen::VectorXd u(2 * period * stride + 1);
  for (Eigen::Index k = 0; k < u.size(); ++k) {
    const double t = static_cast<double>(k) / rate;
    u[k] = amplitude_v * std::sin(4 * kHalfPi * frequency_hz * t - kHalfPi) + o_.loop_sine_offset_v;
  }
  const StageRun run = RunOpenLoop(stage_, u, DeriveSeed(o_.seed, stream));
  const Recording rec =
      RecordedWindow(stage_, run, period, period + 1,
                     fmt::format("open-loop sinusoid {:g} V, {:g} Hz", amplitude_v, frequency_hz));
  LoopSine out;
  out.amplitude_v = amplitude_v;
  out.frequency_hz = frequency_hz;
  VoltageLoopOptions lo;
  lo.levels_v = {o_.loop_sine_offset_v + 0.5 * amplitude_v};  // one level: the areas matter
  out.loop = AnalyzeVoltageLoop(rec, lo);
  out.loop.u_v.resize(0);  // the traces are not kept (12 seeds x 8 runs)
  out.loop.v_mps.resize(0);
  out.mean_width_mps = LoopMeanWidth(out.loop);
  return out;
}

const LoopExperiment& Experiments::Loops() {
  if (loops_) return *loops_;
  Step("open-loop triangle (voltage-velocity loop)");
  TriangleProcedure tri;
  tri.period_s = o_.loop_period_s;
  tri.peak_forward_v = o_.loop_peak_forward_v;
  tri.peak_backward_v = o_.loop_peak_backward_v;
  const Recording rec =
      RunTriangleTest(stage_, tri, DeriveSeed(o_.seed, 4), TrackingProcedure{}.derivative);
  VoltageLoopOptions lo;
  lo.levels_v = o_.loop_levels_v;
  lo.cycles = tri.cycles;
  LoopExperiment e;
  e.triangle = AnalyzeVoltageLoop(rec, lo);
  std::uint64_t stream = 5;
  for (double hz : o_.loop_sine_frequencies_hz) {
    Step(fmt::format("open-loop sinusoid {:g} V at {:g} Hz", o_.loop_sine_amplitude_v, hz));
    e.frequency_sweep.push_back(SineLoop(o_.loop_sine_amplitude_v, hz, stream++));
  }
  for (double a : o_.loop_sine_amplitudes_v) {
    Step(fmt::format("open-loop sinusoid {:g} V at {:g} Hz", a, o_.loop_sine_frequency_hz));
    e.amplitude_sweep.push_back(SineLoop(a, o_.loop_sine_frequency_hz, stream++));
  }
  loops_ = std::move(e);
  return *loops_;
}

}  // namespace sysid::paper
