// Private: F7, the typical (v, a) 120-unit network against the dominant v 24-unit one: their
// MSEs, reported and not required. The paper's contrast (the typical network fits its training
// set, not the test set) is the verdict.
#ifndef SYSID_SRC_PAPER_F7_NETWORKS_HPP_
#define SYSID_SRC_PAPER_F7_NETWORKS_HPP_

#include "paper/experiments.hpp"

namespace sysid::paper {

struct NetworksFact {
  int typical_hidden = 0, dominant_hidden = 0;  ///< units
  SetMse typical, dominant;                     ///< [V^2] on every row
  SetMse typical_moving, dominant_moving;       ///< [V^2] rows with |v| >= kRestSpeedMps
  SetMse irreducible_v, irreducible_va;         ///< [V^2] of v, of (v, a)
  SetCoverage coverage;
  double collection_kp_v_per_m = 0;  ///< [V/m] the P gain that collected the sets
  bool contrast = false;             ///< NetworkContrast
};

/// The typical network's test MSE >= 2x its training MSE, and the dominant network's test MSE
/// below the typical's.
bool NetworkContrast(double typical_train, double typical_test, double dominant_test);

NetworksFact CheckNetworks(Experiments& experiments);

}  // namespace sysid::paper

#endif  // SYSID_SRC_PAPER_F7_NETWORKS_HPP_
