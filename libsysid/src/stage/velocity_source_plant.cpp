// The velocity-source plant's own parameters: their validation (the motor, the rail's
// well-posedness, the ceramic's hysteresis and creep), the held lag of the drive and the speed
// map through a table of steady points.
#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "stage/stage_rules.hpp"
#include "sysid/stage.hpp"

namespace sysid {

using internal::StageFmt;
using internal::StageRequire;
using internal::StageRequireFinite;

namespace {

void ValidateHysteresis(const DriveHysteresis& h) {
  const size_t n = h.thresholds_v.size();
  StageRequire(n <= 200, "hysteresis.thresholds_v", static_cast<double>(n),
               "at most 200 play operators");
  StageRequire(h.weights.size() == n, "hysteresis.weights", static_cast<double>(h.weights.size()),
               "one weight per threshold (" + std::to_string(n) + ")");
  StageRequire(h.rate_weights_s_per_v.size() == n, "hysteresis.rate_weights_s_per_v",
               static_cast<double>(h.rate_weights_s_per_v.size()),
               "one rate weight per threshold (" + std::to_string(n) + ")");
  double sum = 0;
  for (size_t i = 0; i < n; ++i) {
    const std::string idx = "[" + std::to_string(i) + "]";
    StageRequireFinite("hysteresis.thresholds_v" + idx, h.thresholds_v[i]);
    StageRequireFinite("hysteresis.weights" + idx, h.weights[i]);
    StageRequireFinite("hysteresis.rate_weights_s_per_v" + idx, h.rate_weights_s_per_v[i]);
    StageRequire(
        h.thresholds_v[i] > (i > 0 ? h.thresholds_v[i - 1] : 0.0), "hysteresis.thresholds_v" + idx,
        h.thresholds_v[i],
        i > 0 ? "thresholds strictly increasing (previous " + StageFmt(h.thresholds_v[i - 1]) + ")"
              : std::string("thresholds_v > 0"));
    StageRequire(h.weights[i] >= 0, "hysteresis.weights" + idx, h.weights[i], "weights >= 0");
    StageRequire(h.rate_weights_s_per_v[i] >= 0, "hysteresis.rate_weights_s_per_v" + idx,
                 h.rate_weights_s_per_v[i], "rate_weights_s_per_v >= 0");
    sum += h.weights[i];
  }
  StageRequire(sum < 1, "hysteresis.weights", sum,
               "sum of weights < 1 (the effective voltage rises with the command)");
  StageRequireFinite("hysteresis.rate_time_constant_s", h.rate_time_constant_s);
  StageRequire(h.rate_time_constant_s >= 0 && h.rate_time_constant_s <= 10,
               "hysteresis.rate_time_constant_s", h.rate_time_constant_s,
               "0 <= rate_time_constant_s <= 10");
  StageRequireFinite("hysteresis.asymmetry", h.asymmetry);
  StageRequire(h.asymmetry > -1 && h.asymmetry < 1, "hysteresis.asymmetry", h.asymmetry,
               "-1 < asymmetry < 1");
}

void ValidateCreep(const DriveCreep& creep, const DriveHysteresis& hysteresis) {
  StageRequireFinite("creep.voltage_share", creep.voltage_share);
  StageRequire(creep.voltage_share >= 0 && creep.voltage_share < 1, "creep.voltage_share",
               creep.voltage_share,
               "0 <= voltage_share < 1 (the voltage's share that arrives late)");
  StageRequireFinite("creep.loop_share", creep.loop_share);
  StageRequire(creep.loop_share >= 0 && creep.loop_share < 1, "creep.loop_share", creep.loop_share,
               "0 <= loop_share < 1 (the hysteresis lag's share that relaxes)");
  // The loop share relaxes the play operators' lag: without them it would do nothing.
  StageRequire(creep.loop_share == 0 || hysteresis.enabled(), "creep.loop_share", creep.loop_share,
               "loop_share = 0 without drive.hysteresis (it relaxes the play operators' lag)");
  StageRequireFinite("creep.time_constant_s", creep.time_constant_s);
  // The bound keeps a relaxation within the procedures' reach (one slower than every recording
  // is a gain change, not a rate effect).
  StageRequire(creep.time_constant_s > 0 && creep.time_constant_s <= 100, "creep.time_constant_s",
               creep.time_constant_s, "0 < time_constant_s <= 100");
}

}  // namespace

void VelocitySourcePlant::Validate() const {
  StageRequireFinite("motor.pole_per_s", motor.pole_per_s);
  StageRequireFinite("motor.dead_zone_forward_v", motor.dead_zone_forward_v);
  StageRequireFinite("motor.dead_zone_backward_v", motor.dead_zone_backward_v);
  StageRequire(motor.pole_per_s > 0, "motor.pole_per_s", motor.pole_per_s, "pole_per_s > 0");
  StageRequireFinite("motor.thrust_limit_mps2", motor.thrust_limit_mps2);
  StageRequire(motor.thrust_limit_mps2 == 0 || motor.thrust_limit_mps2 > rail.static_mps2,
               "motor.thrust_limit_mps2", motor.thrust_limit_mps2,
               "thrust_limit_mps2 = 0 (no limit) or > rail.static_mps2 (the stage can break away)");
  StageRequire(motor.dead_zone_forward_v >= 0, "motor.dead_zone_forward_v",
               motor.dead_zone_forward_v, "dead_zone_forward_v >= 0");
  StageRequire(motor.dead_zone_backward_v >= 0, "motor.dead_zone_backward_v",
               motor.dead_zone_backward_v, "dead_zone_backward_v >= 0");
  {
    const auto& in = motor.speed_map_in_v;
    const auto& out = motor.speed_map_out_mps;
    StageRequire(in.size() == out.size(), "motor.speed_map_out_mps",
                 static_cast<double>(out.size()),
                 "as many knots as speed_map_in_v (" + std::to_string(in.size()) + ")");
    bool pos = false, neg = false;
    for (size_t i = 0; i < in.size(); ++i) {
      const std::string idx = "[" + std::to_string(i) + "]";
      StageRequireFinite("motor.speed_map_in_v" + idx, in[i]);
      StageRequireFinite("motor.speed_map_out_mps" + idx, out[i]);
      StageRequire(in[i] > motor.dead_zone_forward_v || in[i] < -motor.dead_zone_backward_v,
                   "motor.speed_map_in_v" + idx, in[i],
                   "knots outside the dead zone [-dead_zone_backward_v, dead_zone_forward_v]");
      StageRequire(in[i] > 0 ? out[i] > 0 : out[i] < 0, "motor.speed_map_out_mps" + idx, out[i],
                   "v_f has the sign of its knot's voltage");
      if (i > 0) {
        StageRequire(in[i] > in[i - 1], "motor.speed_map_in_v" + idx, in[i],
                     "knots strictly increasing (previous " + StageFmt(in[i - 1]) + ")");
        StageRequire(out[i] > out[i - 1], "motor.speed_map_out_mps" + idx, out[i],
                     "values increasing (previous " + StageFmt(out[i - 1]) + ")");
      }
      (in[i] > 0 ? pos : neg) = true;
    }
    StageRequire(pos && neg, "motor.speed_map_in_v", static_cast<double>(in.size()),
                 "at least one knot on each side of the dead zone");
  }
  ValidateHysteresis(hysteresis);
  ValidateCreep(creep, hysteresis);
  StageRequireFinite("rail.coulomb_mps2", rail.coulomb_mps2);
  StageRequireFinite("rail.static_mps2", rail.static_mps2);
  StageRequireFinite("rail.stribeck_velocity_mps", rail.stribeck_velocity_mps);
  StageRequire(rail.coulomb_mps2 > 0, "rail.coulomb_mps2", rail.coulomb_mps2, "coulomb_mps2 > 0");
  StageRequire(rail.static_mps2 >= rail.coulomb_mps2, "rail.static_mps2", rail.static_mps2,
               "static_mps2 >= coulomb_mps2 (" + StageFmt(rail.coulomb_mps2) + ")");
  StageRequire(rail.stribeck_velocity_mps > 0, "rail.stribeck_velocity_mps",
               rail.stribeck_velocity_mps, "stribeck_velocity_mps > 0");
  StageRequireFinite("rail.memory_time_s", rail.memory_time_s);
  StageRequire(rail.memory_time_s >= 0 && rail.memory_time_s <= 1.0, "rail.memory_time_s",
               rail.memory_time_s, "0 <= memory_time_s <= 1");
  // Stick-slip is well posed only while the sliding force balance T(p (v_f - v)) - g(v) falls
  // with v wherever it is zero (then it has one root: one steady speed per voltage). There the
  // thrust equals g <= Fs, so its slope is p T' >= p (1 - (Fs/L)^2) (p without a limit), which
  // must beat max |g'| = (Fs - Fc) sqrt(2/e) / vs.
  {
    const double slope = (rail.static_mps2 - rail.coulomb_mps2) * std::sqrt(2.0 / std::exp(1.0)) /
                         rail.stribeck_velocity_mps;
    const double l = motor.thrust_limit_mps2;
    const double fall = l > rail.static_mps2 ? 1 - (rail.static_mps2 / l) * (rail.static_mps2 / l)
                                             : 1.0;  // no limit (a limit <= Fs was refused above)
    StageRequire(
        motor.pole_per_s * fall > slope, "motor.pole_per_s", motor.pole_per_s,
        "pole_per_s (1 - (Fs / thrust_limit)^2 with a thrust limit) > (Fs - Fc) sqrt(2/e) / "
        "vs = " +
            StageFmt(slope) + " (a single steady speed per voltage)");
  }
}

void VelocitySourcePlant::ValidateWithDriver(const DriverSettings& driver) const {
  const double clip = driver.saturation_v;
  StageRequire(motor.dead_zone_forward_v < clip, "motor.dead_zone_forward_v",
               motor.dead_zone_forward_v, "0 <= dead_zone_forward_v < saturation_v");
  StageRequire(motor.dead_zone_backward_v < clip, "motor.dead_zone_backward_v",
               motor.dead_zone_backward_v, "0 <= dead_zone_backward_v < saturation_v");
}

void VelocitySourcePlant::SetSpeedMapThrough(
    const std::vector<std::pair<double, double>>& steady_points) {
  std::vector<std::pair<double, double>> knots;
  for (const auto& [u, v] : steady_points)
    knots.emplace_back(u > 0 ? u - HeldDriveLag(true) : u + HeldDriveLag(false),
                       v + (v > 0 ? 1.0 : -1.0) * motor.DroopForThrust(rail.Sliding(std::abs(v))) /
                               motor.pole_per_s);
  std::sort(knots.begin(), knots.end());
  motor.speed_map_in_v.clear();
  motor.speed_map_out_mps.clear();
  for (const auto& [u, vf] : knots) {
    motor.speed_map_in_v.push_back(u);
    motor.speed_map_out_mps.push_back(vf);
  }
}

double VelocitySourcePlant::HeldDriveLag(bool rising) const {
  return (1 - creep.loop_share) * hysteresis.HeldLag(rising);
}

}  // namespace sysid
