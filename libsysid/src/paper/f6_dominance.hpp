// Private: F6, dominance: under u = 1.5 sin(pi/2 t - pi/2) - 0.3 V open loop the ratio of
// peaks max |x''| / max |a1 x'| over the moving part is at most 0.3 (the paper's O(10^-1)).
#ifndef SYSID_SRC_PAPER_F6_DOMINANCE_HPP_
#define SYSID_SRC_PAPER_F6_DOMINANCE_HPP_

#include "paper/experiments.hpp"

namespace sysid::paper {

constexpr double kDominanceMaxRatio = 0.3;

struct DominanceFact {
  double peak_ratio = 0;              ///< max |x''| / max |a1 x'| (the paper's bound)
  double pointwise_ratio_q99 = 0;     ///< 99 % quantile of |x''(t)| / |a1 x'(t)|
  double peak_acceleration_mps2 = 0;  ///< [m/s^2] max |x''|
  double peak_viscous_mps2 = 0;       ///< [m/s^2] max |a1 x'|
  long moving_samples = 0;
  bool met = false;
};

/// peak_ratio <= kDominanceMaxRatio.
bool DominanceMet(double peak_ratio);

DominanceFact CheckDominance(Experiments& experiments);

}  // namespace sysid::paper

#endif  // SYSID_SRC_PAPER_F6_DOMINANCE_HPP_
