// FactsOptions: defaults, the reduced set for tests, and Validate.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "core/option_rule.hpp"
#include "paper/facts_results.hpp"
#include "sysid/error.hpp"
#include "sysid/stage_facts.hpp"

namespace sysid {

DelayTuningOptions FactsOptions::DefaultDelay() {
  DelayTuningOptions d;
  d.curve_points = 21;  // tau = 0, 1, ..., 20 ms: the curve and RMS at tau = 0
  return d;
}

NeuralTrainingOptions FactsOptions::DefaultTraining() {
  NeuralTrainingOptions t;  // the pipeline's: 100 epochs, output layer re-solved each step
  t.hidden = 24;
  t.max_epochs = 100;
  t.solve_output_layer = true;
  return t;
}

FactsOptions FactsOptions::Reduced() {
  FactsOptions o;
  o.delay.coarse_evaluations = 8;
  o.delay.max_evaluations = 20;
  o.delay.curve_points = 5;
  o.training.hidden = 8;
  o.training.max_epochs = 15;
  o.typical_hidden = 12;
  o.typical_max_epochs = 10;
  o.typical_stride = 4;
  return o;
}

void FactsOptions::Validate() const {
  auto fail = [](const std::string& field, const auto& value, const std::string& rule) {
    internal::FailOption("FactsOptions", field, value, rule);
  };
  for (const auto& id : facts)
    if (std::find(paper::FactIds().begin(), paper::FactIds().end(), id) == paper::FactIds().end())
      fail("facts", "'" + id + "'", "ids are F1, F2, F3, F4, F5, F6, F7, F8");
  if (threads < 0) fail("threads", threads, "threads >= 0 (0: all cores)");
  pulse.Validate();
  delay.Validate();
  if (delay.tau_min_s != 0.0 || delay.curve_points < 2)
    fail("delay.tau_min_s", fmt::format("{:g} (curve_points {})", delay.tau_min_s,
                                        delay.curve_points),
         "tau_min_s = 0 and curve_points >= 2 (F3 compares with tau = 0)");
  pi.Validate();
  if (track_frequencies_hz.empty()) fail("track_frequencies_hz", "{}", "at least one frequency");
  for (double f : track_frequencies_hz)
    if (!(f >= 0.01 && f <= 50))  // bounds the run length: cycles / f seconds of samples
      fail("track_frequencies_hz", f, "0.01 <= f <= 50 Hz");
  if (!(std::abs(track_amplitude_m) > 0) || !std::isfinite(track_amplitude_m))
    fail("track_amplitude_m", track_amplitude_m, "finite and != 0");
  if (track_cycles < 2 || track_cycles > 100)
    fail("track_cycles", track_cycles, "2 <= track_cycles <= 100");
  if (!(ripple_tolerance_m > 0))
    fail("ripple_tolerance_m", ripple_tolerance_m, "> 0");
  if (!(motion_ripple_tolerance_m > 0))
    fail("motion_ripple_tolerance_m", motion_ripple_tolerance_m, "> 0");
  if (!(motion_ripple_window_s > 0) || !(motion_ripple_window_s <= 10))
    fail("motion_ripple_window_s", motion_ripple_window_s,
         "0 < window <= 10 s");
  if (training.hidden < 1 || typical_hidden < 1) fail("training.hidden", fmt::format("{} (typical_hidden {})", training.hidden, typical_hidden), "both >= 1");
  if (typical_max_epochs < 0) fail("typical_max_epochs", typical_max_epochs, ">= 0");
  if (typical_stride < 1) fail("typical_stride", typical_stride, ">= 1");
  if (!(collection_kp_v_per_m > 0) || !std::isfinite(collection_kp_v_per_m))
    fail("collection_kp_v_per_m", collection_kp_v_per_m, "> 0 and finite");
  if (network_initializations < 1 || network_initializations > 100)
    fail("network_initializations", network_initializations,
         "1 <= network_initializations <= 100");
  if (!(dominance_duration_s > 0) || dominance_duration_s > 3600)
    fail("dominance_duration_s", dominance_duration_s,
         "0 < duration <= 3600 s");
  if (!std::isfinite(dominance_amplitude_v) || !std::isfinite(dominance_offset_v) ||
      !(dominance_omega_rad_s > 0))
    fail("dominance_omega_rad_s", fmt::format("{:g} (amplitude {:g} V, offset {:g} V)", dominance_omega_rad_s, dominance_amplitude_v, dominance_offset_v), "finite amplitude and offset, omega > 0");
  if (!(dominance_min_speed_mps > 0)) fail("dominance_min_speed_mps", dominance_min_speed_mps, "> 0");
  if (!(loop_period_s > 0 && loop_period_s <= 600))
    fail("loop_period_s", loop_period_s, "0 < period <= 600 s");
  if (!(loop_peak_forward_v > 0 && loop_peak_forward_v <= 10) ||
      !(loop_peak_backward_v > 0 && loop_peak_backward_v <= 10))
    fail("loop_peak_forward_v",
         fmt::format("{:g} (loop_peak_backward_v {:g})", loop_peak_forward_v, loop_peak_backward_v),
         "each in (0, 10] V");
  if (loop_levels_v.empty() || loop_levels_v.size() > 20)
    fail("loop_levels_v", fmt::format("{} values", loop_levels_v.size()), "1 to 20 levels");
  for (double l : loop_levels_v)
    if (!(l > 0 ? l < loop_peak_forward_v : l > -loop_peak_backward_v))
      fail("loop_levels_v", l,
           "every level != 0 and inside the triangle's range (-peak_backward_v, peak_forward_v)");
  if (!(loop_min_relative_width > 0) || !std::isfinite(loop_min_relative_width))
    fail("loop_min_relative_width", loop_min_relative_width, "> 0");
  if (!(loop_min_start_ratio > 1) || !std::isfinite(loop_min_start_ratio))
    fail("loop_min_start_ratio", loop_min_start_ratio, "> 1");
  if (!(loop_min_rate_ratio > 1) || !std::isfinite(loop_min_rate_ratio))
    fail("loop_min_rate_ratio", loop_min_rate_ratio, "> 1");
  if (!(loop_min_amplitude_change > 0) || !std::isfinite(loop_min_amplitude_change))
    fail("loop_min_amplitude_change", loop_min_amplitude_change, "> 0");
  if (!(std::abs(loop_sine_offset_v) <= 10))
    fail("loop_sine_offset_v", loop_sine_offset_v, "|offset| <= 10 V");
  auto sweep = [&](const std::vector<double>& x, const std::string& name, double lo, double hi,
                   const std::string& unit) {
    if (x.size() < 2 || x.size() > 10)
      fail(name, fmt::format("{} values", x.size()), "2 to 10 values");
    for (std::size_t i = 0; i < x.size(); ++i)
      if (!(x[i] >= lo && x[i] <= hi) || (i > 0 && !(x[i] > x[i - 1])))
        fail(name + "[" + std::to_string(i) + "]", x[i],
             fmt::format("increasing, each in [{:g}, {:g}] {}", lo, hi, unit));
  };
  // Bounds the runs: two periods of the slowest sinusoid, at most 2 / 0.05 = 40 s.
  sweep(loop_sine_frequencies_hz, "loop_sine_frequencies_hz", 0.05, 50, "Hz");
  sweep(loop_sine_amplitudes_v, "loop_sine_amplitudes_v", 0.01, 10, "V");
  if (!(loop_sine_frequency_hz >= 0.05 && loop_sine_frequency_hz <= 50))
    fail("loop_sine_frequency_hz", loop_sine_frequency_hz, "0.05 to 50 Hz");
  if (!(std::abs(loop_sine_amplitude_v) <= 10) || !(loop_sine_amplitude_v > 0))
    fail("loop_sine_amplitude_v", loop_sine_amplitude_v, "0 < A <= 10 V");
}

}  // namespace sysid
