// The refined parameters by name ("a1p", "a1n", "a2p", "a2n", "a3", "tau"): refinement's
// parameter layout, its far-from-prior warnings and its full report address the model's fields
// through this one map.
#ifndef SYSID_DELAY_PARAMETER_NAMES_HPP_
#define SYSID_DELAY_PARAMETER_NAMES_HPP_

#include <stdexcept>
#include <string>

#include "sysid/model.hpp"

namespace sysid::internal {

inline double& ParameterByName(FrictionModel& m, const std::string& name) {
  if (name == "a1p") return m.a1p;
  if (name == "a1n") return m.a1n;
  if (name == "a2p") return m.a2p;
  if (name == "a2n") return m.a2n;
  if (name == "a3") return m.a3;
  if (name == "tau") return m.tau_s;
  throw std::logic_error("ParameterByName: no model parameter named '" + name + "'");
}

inline double ParameterByName(const FrictionModel& m, const std::string& name) {
  return ParameterByName(const_cast<FrictionModel&>(m), name);
}

}  // namespace sysid::internal

#endif  // SYSID_DELAY_PARAMETER_NAMES_HPP_
