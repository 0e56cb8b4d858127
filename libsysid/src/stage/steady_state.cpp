// The stage's steady-state physics: the motor's thrust and droop, the rail's sliding friction,
// the static drive map, the no-load speed and each plant's steady sliding velocity (a bisection
// on its steady force balance).
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <variant>
#include <vector>

#include "sysid/stage.hpp"

namespace sysid {
namespace {

// Steady friction g(v) + s2 v of one branch at speed |v| = s >= 0.
double SteadyFriction(const FrictionBranch& b, double s) {
  const double r = s / b.stribeck_velocity_mps;
  return b.coulomb_mps2 + (b.static_mps2 - b.coulomb_mps2) * std::exp(-r * r) + b.viscous_per_s * s;
}

}  // namespace

double MotorParameters::Thrust(double y) const {
  return thrust_limit_mps2 > 0 ? thrust_limit_mps2 * std::tanh(y / thrust_limit_mps2) : y;
}

double MotorParameters::ThrustSlope(double y) const {
  if (!(thrust_limit_mps2 > 0)) return 1.0;
  const double t = std::tanh(y / thrust_limit_mps2);
  return 1 - t * t;
}

double MotorParameters::DroopForThrust(double f) const {
  return thrust_limit_mps2 > 0 ? thrust_limit_mps2 * std::atanh(f / thrust_limit_mps2) : f;
}

double RailFriction::Sliding(double speed_mps) const {
  const double r = speed_mps / stribeck_velocity_mps;
  return coulomb_mps2 + (static_mps2 - coulomb_mps2) * std::exp(-r * r);
}

double RailFriction::SlidingSlope(double speed_mps) const {
  const double r = speed_mps / stribeck_velocity_mps;
  return (static_mps2 - coulomb_mps2) * std::exp(-r * r) * (-2.0 * r) / stribeck_velocity_mps;
}

double ActuatorDelayPlant::DriveMap(double u) const {
  const auto& in = drive_map_in_v;
  const auto& out = drive_map_out_v;
  // Segment [k, k+1] containing u; the end segments extrapolate linearly.
  size_t k = static_cast<size_t>(std::upper_bound(in.begin(), in.end(), u) - in.begin());
  k = std::clamp<size_t>(k, 1, in.size() - 1) - 1;
  const double s = (u - in[k]) / (in[k + 1] - in[k]);
  return out[k] + s * (out[k + 1] - out[k]);
}

double VelocitySourcePlant::NoLoadSpeed(double u) const {
  const auto& in = motor.speed_map_in_v;
  const auto& out = motor.speed_map_out_mps;
  const bool forward = u > 0;
  if (forward ? u <= motor.dead_zone_forward_v : u >= -motor.dead_zone_backward_v) return 0.0;
  // This side's knots, preceded by the dead-zone edge (|u| = dz, v_f = 0), in order of |u|.
  double prev_u = forward ? motor.dead_zone_forward_v : -motor.dead_zone_backward_v;
  double prev_v = 0;
  double last_u = prev_u, last_v = 0;
  bool have_segment = false;
  const size_t n = in.size();
  for (size_t j = 0; j < n; ++j) {
    const size_t i = forward ? j : n - 1 - j;
    if ((in[i] > 0) != forward) continue;
    const double ku = in[i], kv = out[i];
    if (forward ? u <= ku : u >= ku) return prev_v + (u - prev_u) / (ku - prev_u) * (kv - prev_v);
    last_u = prev_u;
    last_v = prev_v;
    prev_u = ku;
    prev_v = kv;
    have_segment = true;
  }
  if (!have_segment) return 0.0;
  // Beyond the last knot: the last segment extended.
  return prev_v + (u - prev_u) / (prev_u - last_u) * (prev_v - last_v);
}

double StageParameters::SteadyVelocity(double u_v) const {
  const double u = std::clamp(std::clamp(u_v, -rig.dac_range_v, rig.dac_range_v),
                              -driver.saturation_v, driver.saturation_v);
  return std::visit([u](const auto& p) { return p.SteadyVelocity(u); }, plant);
}

double VelocitySourcePlant::SteadyVelocity(double u) const {
  const double vf = NoLoadSpeed(u > 0   ? u - HeldDriveLag(true)
                                : u < 0 ? u + HeldDriveLag(false)
                                        : 0.0);
  const double p = motor.pole_per_s;
  if (std::abs(motor.Thrust(p * vf)) <= rail.static_mps2) return 0.0;
  // h(s) = T(p (|v_f| - s)) - g(s) falls through zero wherever it is zero (Validate), h(0) > 0
  // and h(|v_f|) < 0, so one root in (0, |v_f|).
  double lo = 0, hi = std::abs(vf);
  for (int i = 0; i < 200 && hi - lo > 1e-15; ++i) {
    const double mid = 0.5 * (lo + hi);
    (motor.Thrust(p * (std::abs(vf) - mid)) - rail.Sliding(mid) > 0 ? lo : hi) = mid;
  }
  return (vf > 0 ? 1.0 : -1.0) * 0.5 * (lo + hi);
}

double ActuatorDelayPlant::SteadyVelocity(double u) const {
  if (std::abs(u) <= dead_zone_v) return 0.0;
  const double sign = u > 0 ? 1.0 : -1.0;
  const FrictionBranch& b = u > 0 ? forward : backward;
  const double drive = sign * gain_mps2_per_v * DriveMap(u - sign * dead_zone_v);
  if (drive <= b.static_mps2) return 0.0;
  // g(v) + s2 v dips below Fs (Stribeck) and then rises; since drive > Fs >= g, friction
  // crosses the drive exactly once, above the dip.
  double lo = 0, hi = 1e-6;
  while (SteadyFriction(b, hi) <= drive) {
    lo = hi;
    hi *= 2;
    if (hi > 1e3) return sign * hi;  // friction never catches up (s2 = 0): unbounded
  }
  for (int i = 0; i < 200 && hi - lo > 1e-15; ++i) {
    const double mid = 0.5 * (lo + hi);
    (SteadyFriction(b, mid) > drive ? hi : lo) = mid;
  }
  return sign * 0.5 * (lo + hi);
}

}  // namespace sysid
