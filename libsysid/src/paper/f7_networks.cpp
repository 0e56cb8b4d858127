#include "paper/f7_networks.hpp"

namespace sysid::paper {

bool NetworkContrast(double typical_train, double typical_test, double dominant_test) {
  return typical_test >= 2 * typical_train && dominant_test < typical_test;
}

NetworksFact CheckNetworks(Experiments& experiments) {
  const NetworkExperiment& n = experiments.Networks();
  const FactsOptions& o = experiments.options();
  NetworksFact f;
  f.typical_hidden = o.typical_hidden;
  f.dominant_hidden = o.training.hidden;
  f.typical = n.typical_mse;
  f.dominant = n.dominant_mse;
  f.typical_moving = n.typical_moving_mse;
  f.dominant_moving = n.dominant_moving_mse;
  f.irreducible_v = n.irreducible_v;
  f.irreducible_va = n.irreducible_va;
  f.coverage = n.coverage;
  f.collection_kp_v_per_m = o.collection_kp_v_per_m;
  f.contrast = NetworkContrast(f.typical.train_v2, f.typical.test_v2, f.dominant.test_v2);
  return f;
}

}  // namespace sysid::paper
