// The rough physical model of a friction-dominated stage (the paper's equation with
// direction-dependent coefficients):
//
//   x'' = -a1 * v(t - tau) - a2 * sgn(v) + a3 * u(t)
//   a1 = a1p if v(t - tau) > 0, a1n if v(t - tau) < 0      [1/s]
//   a2 = a2p if v > 0,          a2n if v < 0               [m/s^2]
//
// A model file is JSON: {"a1p":…, "a1n":…, "a2p":…, "a2n":…, "a3":…, "tau":…} (SI units).
#ifndef SYSID_MODEL_HPP_
#define SYSID_MODEL_HPP_

#include <string>
#include <string_view>

#include "sysid/serialize.hpp"

namespace sysid {

struct FrictionModel {
  double a1p = 0;    ///< [1/s] viscous coefficient for motion in +x, >= 0 (0: pure Coulomb)
  double a1n = 0;    ///< [1/s] viscous coefficient for motion in -x, >= 0 (0: pure Coulomb)
  double a2p = 0;    ///< [m/s^2] Coulomb level for motion in +x (breakaway threshold forward)
  double a2n = 0;    ///< [m/s^2] Coulomb level for motion in -x (breakaway threshold backward)
  double a3 = 6.0;   ///< [m/(s^2 V)] actuator gain
  double tau_s = 0;  ///< [s] delay of the viscous term, >= 0

  /// The model file's fields, in file order (sysid/serialize.hpp): every coefficient must be
  /// written, tau may be left out (0: no delay), and a delay of more than a second is no
  /// actuator's.
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(a1p).Required().Minimum(0).Unit("1/s"));
    a->Visit(SYSID_NVP(a1n).Required().Minimum(0).Unit("1/s"));
    a->Visit(SYSID_NVP(a2p).Required().Minimum(0).Unit("m/s^2"));
    a->Visit(SYSID_NVP(a2n).Required().Minimum(0).Unit("m/s^2"));
    a->Visit(SYSID_NVP(a3).Required().ExclusiveMinimum(0).Unit("m/(s^2 V)"));
    a->Visit(SYSID_NVP(tau_s).Renamed("tau").Minimum(0).Maximum(1).Unit("s"));
  }

  /// Throws OptionsError naming the field and the violated rule (finite, a1 >= 0, a2 >= 0,
  /// a3 != 0, tau_s >= 0).
  void Validate() const;

  /// The paper's identified model: a1p = 104.0154, a1n = 117.1441, a2p = 3.1023,
  /// a2n = 6.8216, a3 = 6, tau = 3.5 ms.
  static FrictionModel Paper();

  /// Steady-state sliding velocity [m/s] under a constant voltage `u_v` [V]:
  /// (a3 u - a2p)/a1p when a3 u > a2p, (a3 u + a2n)/a1n when a3 u < -a2n, else 0 (stuck);
  /// +-infinity when the force wins and that direction's a1 is 0 (pure Coulomb: no steady state).
  double SteadyVelocity(double u_v) const;

  /// The analytic inverse u = (a + a1 v_delayed + a2 sgn v) / a3 [V] from acceleration
  /// a [m/s^2], delayed velocity v(t - tau) [m/s] and current velocity v [m/s].
  double InverseVoltage(double a_mps2, double v_delayed_mps, double v_mps) const;
};

/// Parses a model file's text; `source` names it in errors ("FILE:LINE:COLUMN: ...").
/// Unknown keys are errors (a typo must not silently leave a default).
FrictionModel ParseModel(std::string_view json_text, const std::string& source);
/// Reads and validates a model file. Throws InputError.
FrictionModel ReadModel(const std::string& path);
/// The model as a JSON object text (keys a1p, a1n, a2p, a2n, a3, tau; SI units).
std::string ModelToJson(const FrictionModel& model, int indent = 2);
/// Writes a model file atomically.
void WriteModel(const std::string& path, const FrictionModel& model);

}  // namespace sysid

#endif  // SYSID_MODEL_HPP_
