#include "paper/f8_voltage_loop.hpp"

#include <algorithm>
#include <cmath>

#include "paper/measures.hpp"

namespace sysid::paper {

bool LoopWidthMet(const std::vector<double>& relative_widths, double min_fraction) {
  return !relative_widths.empty() && std::all_of(relative_widths.begin(), relative_widths.end(),
                                                 [&](double w) { return w >= min_fraction; });
}

bool LoopRateMet(const std::vector<double>& widths, double min_ratio) {
  if (widths.size() < 2) return false;
  const double first = widths.front(), last = widths.back();
  return first > 0 && std::isfinite(last) && last >= min_ratio * first;
}

bool LoopAmplitudeMet(const std::vector<double>& widths, double min_change) {
  if (widths.size() < 2) return false;
  const double first = widths.front(), last = widths.back();
  if (!std::isfinite(first) || !std::isfinite(last) || first == 0 || last == 0) return false;
  return std::abs(last - first) >= min_change * std::min(std::abs(first), std::abs(last));
}

VoltageLoopFact CheckVoltageLoop(Experiments& experiments) {
  const LoopExperiment& e = experiments.Loops();
  const FactsOptions& o = experiments.options();
  VoltageLoopFact f;
  f.triangle = e.triangle;
  f.frequency_sweep = e.frequency_sweep;
  f.amplitude_sweep = e.amplitude_sweep;
  for (const auto& l : f.triangle.levels) f.relative_widths.push_back(LoopRelativeWidth(l));
  f.a_met = LoopWidthMet(f.relative_widths, o.loop_min_relative_width);
  f.start_ratio = StartRatio(f.triangle);
  f.b_met = f.start_ratio >= o.loop_min_start_ratio;
  std::vector<double> by_f, by_a;
  for (const auto& s : f.frequency_sweep) by_f.push_back(s.mean_width_mps);
  for (const auto& s : f.amplitude_sweep) by_a.push_back(s.mean_width_mps);
  f.c_met = LoopRateMet(by_f, o.loop_min_rate_ratio);
  f.d_met = LoopAmplitudeMet(by_a, o.loop_min_amplitude_change);
  f.rate_ratio = by_f.back() / by_f.front();
  f.amplitude_change =
      (by_a.back() - by_a.front()) / std::min(std::abs(by_a.front()), std::abs(by_a.back()));
  f.met = f.a_met && f.b_met && f.c_met && f.d_met;
  return f;
}

}  // namespace sysid::paper
