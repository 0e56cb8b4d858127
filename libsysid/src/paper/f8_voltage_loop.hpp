// Private: F8, the voltage-velocity loop of the paper's section-3 tests, open loop: (a) on the
// 6 s triangle (+1.5 / -2.1 V) a loop whose width at stated voltages of the pulse region is at
// least a fraction of the velocity there; (b) asymmetric: the start voltages of the two
// directions differ; (c) rate: under u = 1.6 sin(2 pi f t - pi/2) - 0.3 V the loop's mean width
// grows with f; (d) amplitude: at 1 Hz the mean width changes with A (thresholds at
// FactsOptions' loop_* fields).
#ifndef SYSID_SRC_PAPER_F8_VOLTAGE_LOOP_HPP_
#define SYSID_SRC_PAPER_F8_VOLTAGE_LOOP_HPP_

#include <vector>

#include "paper/experiments.hpp"

namespace sysid::paper {

struct VoltageLoopFact {
  VoltageLoop triangle;                 ///< with its traces
  std::vector<double> relative_widths;  ///< LoopRelativeWidth per triangle level
  double start_ratio = 0;               ///< StartRatio of the triangle
  std::vector<LoopSine> frequency_sweep, amplitude_sweep;
  double rate_ratio = 0;        ///< mean width at the highest f / at the lowest
  double amplitude_change = 0;  ///< (largest A's - smallest A's) / the smaller in magnitude
  bool a_met = false, b_met = false, c_met = false, d_met = false;
  bool met = false;  ///< all four
};

/// (a): every relative width >= min_fraction (none NaN, at least one).
bool LoopWidthMet(const std::vector<double>& relative_widths, double min_fraction);
/// (c): last / first >= min_ratio, both finite and the first > 0.
bool LoopRateMet(const std::vector<double>& widths_by_frequency, double min_ratio);
/// (d): |last - first| >= min_change x min(|first|, |last|), both finite and nonzero.
bool LoopAmplitudeMet(const std::vector<double>& widths_by_amplitude, double min_change);

VoltageLoopFact CheckVoltageLoop(Experiments& experiments);

}  // namespace sysid::paper

#endif  // SYSID_SRC_PAPER_F8_VOLTAGE_LOOP_HPP_
