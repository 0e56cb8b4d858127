// PI tracking on the virtual piezo stack: its reference waveforms, its PI gains and their linear
// margins, and the loop run once per feedforward scheme (none, or a hysteresis model's inverse).
#include <fmt/format.h>

#include <cmath>
#include <complex>
#include <optional>

#include "control/scheme_loop.hpp"
#include "core/option_rule.hpp"
#include "sysid/control.hpp"
#include "sysid/error.hpp"
#include "sysid/hysteresis_model.hpp"
#include "sysid/stack.hpp"

namespace sysid {
namespace {

[[noreturn]] void Violated(const char* field, double value, const std::string& rule) {
  internal::FailOption("StackReferenceOptions", field, value, rule);
}

// The stack, rebuilt for each scheme with the same seed: the same plant and noise.
class StackPlant final : public internal::TrackedPlant {
 public:
  StackPlant(const StackParameters& stack, std::uint64_t seed) : stack_(stack), seed_(seed) {}
  void Reset() override { plant_.emplace(stack_, seed_); }
  double Step(double u_v) override { return plant_->Step(u_v); }
  double measured_position_m() const override { return plant_->measured_position_m(); }
  std::string DescribeLimits() const override { return plant_->DescribeLimits(); }

 private:
  const StackParameters& stack_;
  std::uint64_t seed_;
  std::optional<PiezoStack> plant_;
};

}  // namespace

std::string ToString(StackWaveform waveform) {
  return waveform == StackWaveform::kSine ? "sine" : "triangle";
}

StackWaveform ParseStackWaveform(const std::string& name) {
  if (name == "sine") return StackWaveform::kSine;
  if (name == "triangle") return StackWaveform::kTriangle;
  throw OptionsError("'" + name + "' is not one of sine, triangle", "waveform");
}

void StackReferenceOptions::Validate() const {
  if (!std::isfinite(frequency_hz) || !(frequency_hz > 0))
    Violated("frequency_hz", frequency_hz, "frequency_hz > 0");
  if (!std::isfinite(stroke_m) || !(stroke_m > 0)) Violated("stroke_m", stroke_m, "stroke_m > 0");
  if (cycles < 1) Violated("cycles", cycles, "cycles >= 1");
  if (!std::isfinite(sample_rate_hz) || !(sample_rate_hz > 0))
    Violated("sample_rate_hz", sample_rate_hz, "sample_rate_hz > 0");
  // As the stage's profile: a period needs samples to be a waveform at all (1 MHz gave a
  // one-sample "trace" and a tracking error of 0).
  if (!(frequency_hz <= sample_rate_hz / 20))
    Violated("frequency_hz", frequency_hz,
             fmt::format("frequency_hz <= sample_rate_hz / 20 = {:g} Hz (20 samples a period)",
                         sample_rate_hz / 20));
  const double samples = cycles * sample_rate_hz / frequency_hz;
  if (!(samples <= kMaxStackReferenceSamples))
    Violated("cycles", cycles,
             fmt::format("cycles * sample_rate_hz / frequency_hz <= {:g} samples (asked {:.4g})",
                         kMaxStackReferenceSamples, samples));
}

PositionReference MakeStackReference(const StackReferenceOptions& o) {
  o.Validate();
  const auto n =
      static_cast<Eigen::Index>(std::llround(o.cycles * o.sample_rate_hz / o.frequency_hz)) + 1;
  PositionReference r;
  r.t_s.resize(n);
  r.x_m.resize(n);
  r.v_mps.resize(n);
  r.a_mps2.resize(n);
  const double w = 2 * M_PI * o.frequency_hz, half = 0.5 * o.stroke_m;
  for (Eigen::Index k = 0; k < n; ++k) {
    const double t = static_cast<double>(k) / o.sample_rate_hz;
    r.t_s[k] = t;
    if (o.waveform == StackWaveform::kSine) {
      r.x_m[k] = half * (1 - std::cos(w * t));
      r.v_mps[k] = half * w * std::sin(w * t);
      r.a_mps2[k] = half * w * w * std::cos(w * t);
    } else {
      const double phase = t * o.frequency_hz - std::floor(t * o.frequency_hz);  // in [0, 1)
      const double slope = 2 * o.stroke_m * o.frequency_hz;
      r.x_m[k] = phase < 0.5 ? 2 * phase * o.stroke_m : 2 * (1 - phase) * o.stroke_m;
      r.v_mps[k] = phase < 0.5 ? slope : -slope;
      r.a_mps2[k] = 0;
    }
  }
  r.description = fmt::format("{} {:g} Hz, stroke {:g} um, {} cycles", ToString(o.waveform),
                              o.frequency_hz, 1e6 * o.stroke_m, o.cycles);
  return r;
}

PiOptions StackPiOptions(const StackParameters& stack) {
  stack.Validate();
  const double g = stack.MaxStaticGain();
  const double wn = 2 * M_PI * stack.mechanics.resonance_hz;
  PiOptions pi;
  pi.ki_v_per_m_s = 2 * stack.mechanics.damping_ratio * wn / (3 * g);
  pi.kp_v_per_m = 0.05 / g;
  pi.u_max_v = stack.rig.voltage_max_v;
  pi.sample_time_s = stack.sample_time_s();
  return pi;
}

std::complex<double> StackPiLoop(const StackParameters& stack, const PiOptions& pi, double w) {
  using C = std::complex<double>;
  const C j(0, 1);
  const double ts = pi.sample_time_s;
  const C z = std::exp(j * w * ts);
  const C controller = pi.kp_v_per_m + pi.ki_v_per_m_s * ts / (1.0 - 1.0 / z);
  double slope = stack.hysteresis.linear_gain_m_per_v;
  for (double wi : stack.hysteresis.weights_m_per_v) slope += wi;
  C creep = 1;
  for (size_t i = 0; i < stack.creep.fractions.size(); ++i)
    creep += stack.creep.fractions[i] / (1.0 + j * w * stack.creep.time_constants_s[i]);
  const double wn = 2 * M_PI * stack.mechanics.resonance_hz;
  const C mechanics =
      wn * wn / (wn * wn - w * w + 2.0 * j * stack.mechanics.damping_ratio * wn * w);
  return controller * slope * creep * mechanics * std::exp(-j * w * ts / 2.0);
}

LoopMargins StackPiMargins(const StackParameters& stack, const PiOptions& pi) {
  pi.Validate();
  return ComputeLoopMargins([&](double w) { return StackPiLoop(stack, pi, w); }, 0.1,
                            M_PI / pi.sample_time_s);
}

std::vector<SchemeTracking> TrackStackSchemes(
    const StackParameters& stack, std::uint64_t seed, const PositionReference& reference,
    PiOptions pi, const std::vector<FeedforwardScheme>& schemes, const InverseModels& models,
    const std::function<void(FeedforwardScheme, std::size_t)>& on_scheme) {
  pi.sample_time_s = stack.sample_time_s();
  pi.Validate();
  for (auto s : schemes)
    if (s != FeedforwardScheme::kNone && s != FeedforwardScheme::kHysteresis)
      throw OptionsError("the piezo stack takes the schemes none and hysteresis ('" + ToString(s) +
                             "' is the stage's: a friction or network inverse of velocity)",
                         "schemes");
  StackPlant plant(stack, seed);
  return internal::TrackEachScheme(plant, reference, pi, schemes, models, on_scheme);
}

}  // namespace sysid
