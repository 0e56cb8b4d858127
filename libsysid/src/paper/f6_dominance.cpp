#include "paper/f6_dominance.hpp"

namespace sysid::paper {

bool DominanceMet(double peak_ratio) { return peak_ratio <= kDominanceMaxRatio; }

DominanceFact CheckDominance(Experiments& experiments) {
  const DominanceResult& d = experiments.Dominance();
  DominanceFact f;
  f.peak_ratio = d.peak_ratio;
  f.pointwise_ratio_q99 = d.pointwise_ratio_quantile;
  // terms: acceleration, viscous, coulomb (dominance.hpp's fixed order).
  f.peak_acceleration_mps2 = d.terms[0].peak;
  f.peak_viscous_mps2 = d.terms[1].peak;
  f.moving_samples = static_cast<long>(d.moving_samples);
  f.met = DominanceMet(f.peak_ratio);
  return f;
}

}  // namespace sysid::paper
