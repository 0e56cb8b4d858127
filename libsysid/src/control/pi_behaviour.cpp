// The gains' step and sine on the model plant, and the limit-cycle check of a run's hold.
#include <algorithm>
#include <cmath>
#include <limits>

#include "core/option_rule.hpp"
#include "sysid/control_tuning.hpp"
#include "sysid/error.hpp"

namespace sysid {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

void Require(bool ok, const char* field, double value, const char* rule) {
  if (!ok) internal::FailOption("PiBehaviourOptions", field, value, rule);
}

PositionReference Sampled(const Eigen::VectorXd& x_m, double ts, const std::string& what) {
  const Eigen::Index n = x_m.size();
  PositionReference r =
      ReferenceFromPositions(Eigen::VectorXd::LinSpaced(n, 0, ts * static_cast<double>(n - 1)), x_m);
  r.description = what;
  return r;
}

}  // namespace

void PiBehaviourOptions::Validate() const {
  Require(std::isfinite(step_m) && step_m != 0, "step_m", step_m, "finite, != 0");
  Require(step_duration_s > 0 && step_duration_s <= 1000, "step_duration_s", step_duration_s,
          "0 < step_duration_s <= 1000");
  Require(std::isfinite(sine_amplitude_m) && sine_amplitude_m > 0, "sine_amplitude_m",
          sine_amplitude_m, "finite, > 0");
  Require(sine_frequency_hz > 0 && sine_frequency_hz <= 1e4, "sine_frequency_hz",
          sine_frequency_hz, "0 < sine_frequency_hz <= 1e4");
  Require(sine_cycles >= 1 && sine_cycles <= 1000, "sine_cycles", sine_cycles,
          "1 <= sine_cycles <= 1000");
  Require(std::isfinite(limit_cycle_threshold_m) && limit_cycle_threshold_m > 0,
          "limit_cycle_threshold_m", limit_cycle_threshold_m, "finite, > 0");
}

PositionReference AppendHold(const PositionReference& reference, double hold_s) {
  const Eigen::Index n = reference.x_m.size();
  if (n < 2) throw OptionsError("AppendHold: the reference needs at least 2 samples");
  const double ts = reference.t_s[1] - reference.t_s[0];
  if (!(hold_s >= 0) || !(hold_s / ts <= kMaxSignalSamples))
    throw OptionsError("AppendHold: expected 0 <= hold_s <= 2e7 samples, found " +
                       std::to_string(hold_s) + " s");
  const auto extra = static_cast<Eigen::Index>(std::llround(hold_s / ts));
  PositionReference r = reference;
  r.t_s.conservativeResize(n + extra);
  r.x_m.conservativeResize(n + extra);
  r.v_mps.conservativeResize(n + extra);
  r.a_mps2.conservativeResize(n + extra);
  for (Eigen::Index k = n; k < n + extra; ++k) {
    r.t_s[k] = reference.t_s[n - 1] + static_cast<double>(k - n + 1) * ts;
    r.x_m[k] = reference.x_m[n - 1];
    r.v_mps[k] = r.a_mps2[k] = 0;
  }
  r.description += " + " + std::to_string(hold_s) + " s hold";
  return r;
}

LimitCycleCheck CheckLimitCycle(const TrackingResult& run, double window_s, double threshold_m) {
  const Eigen::Index n = run.t_s.size();
  if (!(threshold_m > 0) || !std::isfinite(threshold_m))
    throw OptionsError("CheckLimitCycle: expected threshold_m > 0, found " +
                       std::to_string(threshold_m));
  if (n < 2 || !(window_s > 0) || !(window_s <= run.t_s[n - 1] - run.t_s[0]))
    throw OptionsError("CheckLimitCycle: expected 0 < window_s <= the run's length, found " +
                       std::to_string(window_s) + " s");
  Eigen::Index first = n - 1;
  while (first > 0 && run.t_s[first - 1] >= run.t_s[n - 1] - window_s) --first;
  const Eigen::Index len = n - first;
  LimitCycleCheck c;
  c.window_s = window_s;
  c.threshold_m = threshold_m;
  c.error_peak_to_peak_m = run.e_m.tail(len).maxCoeff() - run.e_m.tail(len).minCoeff();
  c.control_peak_to_peak_v = run.u_v.tail(len).maxCoeff() - run.u_v.tail(len).minCoeff();
  c.limit_cycle = c.error_peak_to_peak_m > threshold_m;
  return c;
}

PiBehaviour SimulatePiBehaviour(const FrictionModel& model, const PiOptions& pi,
                                const PiBehaviourOptions& o) {
  o.Validate();
  pi.Validate();
  const double ts = pi.sample_time_s;
  const std::vector<FeedforwardScheme> none = {FeedforwardScheme::kNone};
  PiBehaviour b;
  b.step.step_m = o.step_m;
  {
    const auto n = static_cast<Eigen::Index>(std::llround(o.step_duration_s / ts)) + 1;
    if (!(static_cast<double>(n) <= kMaxSignalSamples))
      throw OptionsError("SimulatePiBehaviour: the step run exceeds 2e7 samples", "step_duration_s");
    Eigen::VectorXd x = Eigen::VectorXd::Constant(n, o.step_m);
    x[0] = 0;  // at rest at 0, the step at the first control sample
    PositionReference ref = Sampled(x, ts, "step");
    ref.v_mps.setZero();
    ref.a_mps2.setZero();
    const TrackingResult r = TrackModelSchemes(model, ts, ref, pi, none, {})[0].result;
    const double s = o.step_m, sign = s > 0 ? 1 : -1;
    const Eigen::VectorXd y = sign * r.x_m / s;  // the normalised response, 0 -> 1
    b.step.overshoot = std::max(0.0, y.maxCoeff() - 1);
    double t10 = kNaN, t90 = kNaN;
    for (Eigen::Index k = 0; k < n; ++k) {
      if (std::isnan(t10) && y[k] >= 0.1) t10 = r.t_s[k];
      if (std::isnan(t90) && y[k] >= 0.9) t90 = r.t_s[k];
    }
    b.step.rise_time_s = t90 - t10;
    b.step.settling_time_s = kNaN;
    if (std::abs(y[n - 1] - 1) <= 0.02) {
      Eigen::Index k = n - 1;
      while (k > 0 && std::abs(y[k - 1] - 1) <= 0.02) --k;
      b.step.settling_time_s = r.t_s[k];
    }
    b.step.final_error_m = r.e_m[n - 1];
    b.step.saturated_samples = r.saturated_samples;
    b.step.max_abs_u_v = r.max_abs_u_v;
  }
  {
    b.sine.amplitude_m = o.sine_amplitude_m;
    b.sine.frequency_hz = o.sine_frequency_hz;
    const double period = 1 / o.sine_frequency_hz;
    const auto n = static_cast<Eigen::Index>(std::llround(o.sine_cycles * period / ts)) + 1;
    if (!(static_cast<double>(n) * 1.5 <= kMaxSignalSamples))
      throw OptionsError("SimulatePiBehaviour: the sine run exceeds 2e7 samples", "sine_cycles");
    Eigen::VectorXd x(n);
    for (Eigen::Index k = 0; k < n; ++k)
      x[k] = o.sine_amplitude_m * std::sin(2 * M_PI * o.sine_frequency_hz * ts * static_cast<double>(k));
    const PositionReference ref = AppendHold(Sampled(x, ts, "sine"), period);
    b.sine.run = TrackModelSchemes(model, ts, ref, pi, none, {})[0].result;
    b.sine.limit_cycle = CheckLimitCycle(b.sine.run, period / 2, o.limit_cycle_threshold_m);
  }
  return b;
}

}  // namespace sysid
