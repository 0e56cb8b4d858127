#include <cmath>
#include <limits>
#include <string>

#include "core/option_rule.hpp"
#include "sysid/error.hpp"
#include "sysid/model.hpp"

namespace sysid {
namespace {

void Require(bool ok, const char* field, double value, const char* rule) {
  if (!ok) internal::FailOption("FrictionModel", field, value, rule);
}

}  // namespace

void FrictionModel::Validate() const {
  const double fields[] = {a1p, a1n, a2p, a2n, a3, tau_s};
  const char* names[] = {"a1p", "a1n", "a2p", "a2n", "a3", "tau"};
  for (int i = 0; i < 6; ++i) Require(std::isfinite(fields[i]), names[i], fields[i], "finite");
  // a1 = 0 is pure Coulomb friction: a valid model (no viscous term), the textbook case.
  Require(a1p >= 0, "a1p", a1p, "a1p >= 0");
  Require(a1n >= 0, "a1n", a1n, "a1n >= 0");
  Require(a2p >= 0, "a2p", a2p, "a2p >= 0");
  Require(a2n >= 0, "a2n", a2n, "a2n >= 0");
  Require(a3 > 0, "a3", a3, "a3 > 0");
  Require(tau_s >= 0, "tau", tau_s, "tau >= 0");
}

FrictionModel FrictionModel::Paper() {
  FrictionModel m;
  m.a1p = 104.0154;
  m.a1n = 117.1441;
  m.a2p = 3.1023;
  m.a2n = 6.8216;
  m.a3 = 6.0;
  m.tau_s = 0.0035;
  return m;
}

double FrictionModel::SteadyVelocity(double u_v) const {
  const double f = a3 * u_v;
  // With a1 = 0 (pure Coulomb) an unbalanced force accelerates for ever: +-infinity.
  if (f > a2p) return a1p > 0 ? (f - a2p) / a1p : std::numeric_limits<double>::infinity();
  if (f < -a2n) return a1n > 0 ? (f + a2n) / a1n : -std::numeric_limits<double>::infinity();
  return 0.0;
}

double FrictionModel::InverseVoltage(double a_mps2, double v_delayed_mps, double v_mps) const {
  const double a1 = v_delayed_mps > 0 ? a1p : (v_delayed_mps < 0 ? a1n : 0.0);
  const double a2 = v_mps > 0 ? a2p : (v_mps < 0 ? -a2n : 0.0);
  return (a_mps2 + a1 * v_delayed_mps + a2) / a3;
}

}  // namespace sysid
