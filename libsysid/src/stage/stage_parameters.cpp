// StageParameters: validation of each model's fields, the drive hysteresis and creep setters,
// the paper's pulse table and the speed map through it (presets: stage_presets.cpp; the
// steady-state physics: steady_state.cpp).
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

#include "core/option_rule.hpp"
#include "sysid/error.hpp"
#include "sysid/stage.hpp"

namespace sysid {
namespace {

std::string Fmt(double v) {
  std::ostringstream s;
  s.precision(17);
  s << v;
  return s.str();
}

void Require(bool ok, const std::string& field, double value, const std::string& rule) {
  if (!ok) internal::FailOption("StageParameters", field, value, rule);
}

void RequireFinite(const std::string& field, double value) {
  Require(std::isfinite(value), field, value, field + " is finite");
}

void ValidateBranch(const std::string& name, const FrictionBranch& b) {
  RequireFinite(name + ".coulomb_mps2", b.coulomb_mps2);
  RequireFinite(name + ".static_mps2", b.static_mps2);
  RequireFinite(name + ".stribeck_velocity_mps", b.stribeck_velocity_mps);
  RequireFinite(name + ".viscous_per_s", b.viscous_per_s);
  Require(b.coulomb_mps2 > 0, name + ".coulomb_mps2", b.coulomb_mps2, "coulomb_mps2 > 0");
  Require(b.static_mps2 >= b.coulomb_mps2, name + ".static_mps2", b.static_mps2,
          "static_mps2 >= coulomb_mps2 (" + Fmt(b.coulomb_mps2) + ")");
  Require(b.stribeck_velocity_mps > 0, name + ".stribeck_velocity_mps", b.stribeck_velocity_mps,
          "stribeck_velocity_mps > 0");
  Require(b.viscous_per_s >= 0, name + ".viscous_per_s", b.viscous_per_s, "viscous_per_s >= 0");
}

}  // namespace

// The paper's pulse table (section "Parameter Identification"): amplitude [V], measured
// steady velocity [m/s].
const double kPaperPulseTable[10][2] = {
    {-2.5, -0.07120}, {-2.3, -0.05562}, {-2.1, -0.04991}, {-2.0, -0.04622}, {-1.8, -0.03393},
    {1.3, 0.04465},   {1.5, 0.05742},   {1.6, 0.06222},   {1.7, 0.06863},   {2.0, 0.08519}};

std::vector<std::pair<double, double>> StageParameters::PaperPulseTable() {
  std::vector<std::pair<double, double>> table;
  for (const auto& row : kPaperPulseTable) table.emplace_back(row[0], row[1]);
  return table;
}

void StageParameters::SetSpeedMapThrough(
    const std::vector<std::pair<double, double>>& steady_points) {
  std::vector<std::pair<double, double>> knots;
  for (const auto& [u, v] : steady_points)
    knots.emplace_back(u > 0 ? u - HeldDriveLag(true) : u + HeldDriveLag(false),
                       v + (v > 0 ? 1.0 : -1.0) *
                                  motor.DroopForThrust(rail.Sliding(std::abs(v))) /
                                  motor.pole_per_s);
  std::sort(knots.begin(), knots.end());
  motor.speed_map_in_v.clear();
  motor.speed_map_out_mps.clear();
  for (const auto& [u, vf] : knots) {
    motor.speed_map_in_v.push_back(u);
    motor.speed_map_out_mps.push_back(vf);
  }
}

void StageParameters::SetDriveHysteresis(const DriveHysteresis& h) {
  const double forward = HeldDriveLag(true), backward = HeldDriveLag(false);
  hysteresis = h;
  MoveForHeldLag(forward, backward);
}

void StageParameters::SetDriveCreep(const DriveCreep& c) {
  const double forward = HeldDriveLag(true), backward = HeldDriveLag(false);
  creep = c;
  MoveForHeldLag(forward, backward);
}

void StageParameters::MoveForHeldLag(double forward_before, double backward_before) {
  const double forward = HeldDriveLag(true) - forward_before;
  const double backward = HeldDriveLag(false) - backward_before;
  motor.dead_zone_forward_v -= forward;
  motor.dead_zone_backward_v -= backward;
  for (double& u : motor.speed_map_in_v) u += u > 0 ? -forward : backward;
  Validate();
}

double StageParameters::HeldDriveLag(bool rising) const {
  return (1 - creep.loop_share) * hysteresis.HeldLag(rising);
}

double DriveHysteresis::HeldLag(bool rising) const {
  double lag = 0;
  for (size_t i = 0; i < thresholds_v.size() && i < weights.size(); ++i)
    lag += weights[i] * thresholds_v[i];
  return lag * (rising ? 1 + asymmetry : 1 - asymmetry);
}

double DriveHysteresis::SaturationRate() const {
  double w = 0, s = 0;
  for (double x : weights) w += x;
  for (double x : rate_weights_s_per_v) s += x;
  return s > 0 ? (1 - w) / s : std::numeric_limits<double>::infinity();
}

std::string ToString(StageModel model) {
  return model == StageModel::kActuatorDelay ? "actuator-delay" : "velocity-source";
}

StageModel ParseStageModel(const std::string& text) {
  if (text == "velocity-source") return StageModel::kVelocitySource;
  if (text == "actuator-delay") return StageModel::kActuatorDelay;
  throw OptionsError("stage model '" + text + "' is not one of velocity-source, actuator-delay");
}

void StageParameters::Validate() const {
  const struct {
    const char* field;
    double value;
  } finite[] = {{"gain_mps2_per_v", gain_mps2_per_v},
                {"dead_zone_v", dead_zone_v},
                {"saturation_v", saturation_v},
                {"transport_delay_s", transport_delay_s},
                {"lag_time_constant_s", lag_time_constant_s},
                {"bristle_stiffness_per_s2", bristle_stiffness_per_s2},
                {"bristle_damping_per_s", bristle_damping_per_s},
                {"sample_rate_hz", sample_rate_hz},
                {"dac_range_v", dac_range_v},
                {"encoder_resolution_m", encoder_resolution_m},
                {"position_noise_m", position_noise_m},
                {"travel_min_m", travel_min_m},
                {"travel_max_m", travel_max_m},
                {"max_velocity_mps", max_velocity_mps},
                {"initial_position_m", initial_position_m},
                {"relative_tolerance", relative_tolerance},
                {"position_tolerance_m", position_tolerance_m}};
  for (const auto& f : finite) RequireFinite(f.field, f.value);
  Require(gain_mps2_per_v > 0, "gain_mps2_per_v", gain_mps2_per_v, "gain_mps2_per_v > 0");
  Require(dead_zone_v >= 0, "dead_zone_v", dead_zone_v, "dead_zone_v >= 0");
  Require(saturation_v > dead_zone_v, "saturation_v", saturation_v,
          "saturation_v > dead_zone_v (" + Fmt(dead_zone_v) + ")");
  Require(transport_delay_s >= 0 && transport_delay_s <= 1.0, "transport_delay_s",
          transport_delay_s, "0 <= transport_delay_s <= 1");
  Require(lag_time_constant_s > 0, "lag_time_constant_s", lag_time_constant_s,
          "lag_time_constant_s > 0");
  Require(sample_rate_hz > 0, "sample_rate_hz", sample_rate_hz, "sample_rate_hz > 0");
  RequireFinite("record_rate_hz", record_rate_hz);
  Require(record_rate_hz >= 0 && record_rate_hz <= sample_rate_hz, "record_rate_hz",
          record_rate_hz,
          "0 <= record_rate_hz <= the control rate sample_rate_hz (" + Fmt(sample_rate_hz) +
              "); 0: the control rate");
  if (record_rate_hz > 0) {
    const double n = sample_rate_hz / record_rate_hz;
    Require(std::abs(n - std::round(n)) <= 1e-9 * n, "record_rate_hz", record_rate_hz,
            "the control rate sample_rate_hz (" + Fmt(sample_rate_hz) +
                ") is an integer multiple of record_rate_hz (recordings keep every n-th sample)");
  }
  Require(max_steps_per_sample >= 10 && max_steps_per_sample <= 100000000, "max_steps_per_sample",
          static_cast<double>(max_steps_per_sample), "10 <= max_steps_per_sample <= 1e8");
  Require(dac_bits >= 1 && dac_bits <= 32, "dac_bits", dac_bits, "1 <= dac_bits <= 32");
  Require(dac_range_v > 0, "dac_range_v", dac_range_v, "dac_range_v > 0");
  Require(travel_max_m > travel_min_m, "travel_max_m", travel_max_m,
          "travel_max_m > travel_min_m (" + Fmt(travel_min_m) + ")");
  // Bounded on both sides: the encoder divides by its resolution (1e-320 m made every position
  // inf) and noise beyond the travel is no stage; 1 fm is below any encoder made.
  const double span = travel_max_m - travel_min_m;
  Require(encoder_resolution_m >= 1e-15 && encoder_resolution_m <= span, "encoder_resolution_m",
          encoder_resolution_m, "1e-15 <= encoder_resolution_m <= the travel (" + Fmt(span) + ")");
  Require(position_noise_m >= 0 && position_noise_m <= span, "position_noise_m",
          position_noise_m, "0 <= position_noise_m <= the travel (" + Fmt(span) + ")");
  Require(initial_position_m >= travel_min_m && initial_position_m <= travel_max_m,
          "initial_position_m", initial_position_m,
          "travel_min_m <= initial_position_m <= travel_max_m");
  Require(max_velocity_mps > 0, "max_velocity_mps", max_velocity_mps, "max_velocity_mps > 0");
  Require(relative_tolerance > 0 && relative_tolerance <= 1e-2, "relative_tolerance",
          relative_tolerance, "0 < relative_tolerance <= 1e-2");
  Require(position_tolerance_m > 0, "position_tolerance_m", position_tolerance_m,
          "position_tolerance_m > 0");
  if (model == StageModel::kVelocitySource) {
    ValidateVelocitySource();
    return;
  }
  Require(!hysteresis.enabled(), "hysteresis.thresholds_v",
          static_cast<double>(hysteresis.thresholds_v.size()),
          "no drive hysteresis on the actuator-delay model (it belongs to the velocity source)");
  Require(!creep.enabled(), "creep.voltage_share", creep.voltage_share,
          "no drive creep on the actuator-delay model (it belongs to the velocity source)");
  Require(!creep.enabled(), "creep.loop_share", creep.loop_share,
          "no drive creep on the actuator-delay model (it belongs to the velocity source)");
  // Actuator-delay model: LuGre rail and drive map.
  Require(bristle_stiffness_per_s2 > 0, "bristle_stiffness_per_s2", bristle_stiffness_per_s2,
          "bristle_stiffness_per_s2 > 0");
  Require(bristle_damping_per_s >= 0, "bristle_damping_per_s", bristle_damping_per_s,
          "bristle_damping_per_s >= 0");
  ValidateBranch("forward", forward);
  ValidateBranch("backward", backward);
  // The drive map.
  ValidateDriveMap();
}

void StageParameters::ValidateVelocitySource() const {
  RequireFinite("motor.pole_per_s", motor.pole_per_s);
  RequireFinite("motor.dead_zone_forward_v", motor.dead_zone_forward_v);
  RequireFinite("motor.dead_zone_backward_v", motor.dead_zone_backward_v);
  Require(motor.pole_per_s > 0, "motor.pole_per_s", motor.pole_per_s, "pole_per_s > 0");
  RequireFinite("motor.thrust_limit_mps2", motor.thrust_limit_mps2);
  Require(motor.thrust_limit_mps2 == 0 || motor.thrust_limit_mps2 > rail.static_mps2,
          "motor.thrust_limit_mps2", motor.thrust_limit_mps2,
          "thrust_limit_mps2 = 0 (no limit) or > rail.static_mps2 (the stage can break away)");
  Require(motor.dead_zone_forward_v >= 0 && motor.dead_zone_forward_v < saturation_v,
          "motor.dead_zone_forward_v", motor.dead_zone_forward_v,
          "0 <= dead_zone_forward_v < saturation_v");
  Require(motor.dead_zone_backward_v >= 0 && motor.dead_zone_backward_v < saturation_v,
          "motor.dead_zone_backward_v", motor.dead_zone_backward_v,
          "0 <= dead_zone_backward_v < saturation_v");
  {
    const auto& in = motor.speed_map_in_v;
    const auto& out = motor.speed_map_out_mps;
    Require(in.size() == out.size(), "motor.speed_map_out_mps", static_cast<double>(out.size()),
            "as many knots as speed_map_in_v (" + std::to_string(in.size()) + ")");
    bool pos = false, neg = false;
    for (size_t i = 0; i < in.size(); ++i) {
      const std::string idx = "[" + std::to_string(i) + "]";
      RequireFinite("motor.speed_map_in_v" + idx, in[i]);
      RequireFinite("motor.speed_map_out_mps" + idx, out[i]);
      Require(in[i] > motor.dead_zone_forward_v || in[i] < -motor.dead_zone_backward_v,
              "motor.speed_map_in_v" + idx, in[i],
              "knots outside the dead zone [-dead_zone_backward_v, dead_zone_forward_v]");
      Require(in[i] > 0 ? out[i] > 0 : out[i] < 0, "motor.speed_map_out_mps" + idx, out[i],
              "v_f has the sign of its knot's voltage");
      if (i > 0) {
        Require(in[i] > in[i - 1], "motor.speed_map_in_v" + idx, in[i],
                "knots strictly increasing (previous " + Fmt(in[i - 1]) + ")");
        Require(out[i] > out[i - 1], "motor.speed_map_out_mps" + idx, out[i],
                "values increasing (previous " + Fmt(out[i - 1]) + ")");
      }
      (in[i] > 0 ? pos : neg) = true;
    }
    Require(pos && neg, "motor.speed_map_in_v", static_cast<double>(in.size()),
            "at least one knot on each side of the dead zone");
  }
  ValidateHysteresis();
  ValidateCreep();
  RequireFinite("rail.coulomb_mps2", rail.coulomb_mps2);
  RequireFinite("rail.static_mps2", rail.static_mps2);
  RequireFinite("rail.stribeck_velocity_mps", rail.stribeck_velocity_mps);
  Require(rail.coulomb_mps2 > 0, "rail.coulomb_mps2", rail.coulomb_mps2, "coulomb_mps2 > 0");
  Require(rail.static_mps2 >= rail.coulomb_mps2, "rail.static_mps2", rail.static_mps2,
          "static_mps2 >= coulomb_mps2 (" + Fmt(rail.coulomb_mps2) + ")");
  Require(rail.stribeck_velocity_mps > 0, "rail.stribeck_velocity_mps",
          rail.stribeck_velocity_mps, "stribeck_velocity_mps > 0");
  RequireFinite("rail.memory_time_s", rail.memory_time_s);
  Require(rail.memory_time_s >= 0 && rail.memory_time_s <= 1.0, "rail.memory_time_s",
          rail.memory_time_s, "0 <= memory_time_s <= 1");
  // Stick-slip is well posed only while the sliding force balance T(p (v_f - v)) - g(v) falls
  // with v wherever it is zero (then it has one root: one steady speed per voltage). There the
  // thrust equals g <= Fs, so its slope is p T' >= p (1 - (Fs/L)^2) (p without a limit), which
  // must beat max |g'| = (Fs - Fc) sqrt(2/e) / vs.
  {
    const double slope = (rail.static_mps2 - rail.coulomb_mps2) * std::sqrt(2.0 / std::exp(1.0)) /
                         rail.stribeck_velocity_mps;
    const double l = motor.thrust_limit_mps2;
    const double fall = l > rail.static_mps2
                            ? 1 - (rail.static_mps2 / l) * (rail.static_mps2 / l)
                            : 1.0;  // no limit (a limit <= Fs was refused above)
    Require(motor.pole_per_s * fall > slope, "motor.pole_per_s", motor.pole_per_s,
            "pole_per_s (1 - (Fs / thrust_limit)^2 with a thrust limit) > (Fs - Fc) sqrt(2/e) / "
            "vs = " + Fmt(slope) + " (a single steady speed per voltage)");
  }
}

void StageParameters::ValidateHysteresis() const {
  const DriveHysteresis& h = hysteresis;
  const size_t n = h.thresholds_v.size();
  Require(n <= 200, "hysteresis.thresholds_v", static_cast<double>(n),
          "at most 200 play operators");
  Require(h.weights.size() == n, "hysteresis.weights", static_cast<double>(h.weights.size()),
          "one weight per threshold (" + std::to_string(n) + ")");
  Require(h.rate_weights_s_per_v.size() == n, "hysteresis.rate_weights_s_per_v",
          static_cast<double>(h.rate_weights_s_per_v.size()),
          "one rate weight per threshold (" + std::to_string(n) + ")");
  double sum = 0;
  for (size_t i = 0; i < n; ++i) {
    const std::string idx = "[" + std::to_string(i) + "]";
    RequireFinite("hysteresis.thresholds_v" + idx, h.thresholds_v[i]);
    RequireFinite("hysteresis.weights" + idx, h.weights[i]);
    RequireFinite("hysteresis.rate_weights_s_per_v" + idx, h.rate_weights_s_per_v[i]);
    Require(h.thresholds_v[i] > (i > 0 ? h.thresholds_v[i - 1] : 0.0),
            "hysteresis.thresholds_v" + idx, h.thresholds_v[i],
            i > 0 ? "thresholds strictly increasing (previous " + Fmt(h.thresholds_v[i - 1]) + ")"
                  : std::string("thresholds_v > 0"));
    Require(h.weights[i] >= 0, "hysteresis.weights" + idx, h.weights[i], "weights >= 0");
    Require(h.rate_weights_s_per_v[i] >= 0, "hysteresis.rate_weights_s_per_v" + idx,
            h.rate_weights_s_per_v[i], "rate_weights_s_per_v >= 0");
    sum += h.weights[i];
  }
  Require(sum < 1, "hysteresis.weights", sum,
          "sum of weights < 1 (the effective voltage rises with the command)");
  RequireFinite("hysteresis.rate_time_constant_s", h.rate_time_constant_s);
  Require(h.rate_time_constant_s >= 0 && h.rate_time_constant_s <= 10,
          "hysteresis.rate_time_constant_s", h.rate_time_constant_s,
          "0 <= rate_time_constant_s <= 10");
  RequireFinite("hysteresis.asymmetry", h.asymmetry);
  Require(h.asymmetry > -1 && h.asymmetry < 1, "hysteresis.asymmetry", h.asymmetry,
          "-1 < asymmetry < 1");
}

void StageParameters::ValidateCreep() const {
  RequireFinite("creep.voltage_share", creep.voltage_share);
  Require(creep.voltage_share >= 0 && creep.voltage_share < 1, "creep.voltage_share",
          creep.voltage_share, "0 <= voltage_share < 1 (the voltage's share that arrives late)");
  RequireFinite("creep.loop_share", creep.loop_share);
  Require(creep.loop_share >= 0 && creep.loop_share < 1, "creep.loop_share", creep.loop_share,
          "0 <= loop_share < 1 (the hysteresis lag's share that relaxes)");
  // The loop share relaxes the play operators' lag: without them it would do nothing.
  Require(creep.loop_share == 0 || hysteresis.enabled(), "creep.loop_share", creep.loop_share,
          "loop_share = 0 without drive.hysteresis (it relaxes the play operators' lag)");
  RequireFinite("creep.time_constant_s", creep.time_constant_s);
  // The bound keeps a relaxation within the procedures' reach (one slower than every recording
  // is a gain change, not a rate effect).
  Require(creep.time_constant_s > 0 && creep.time_constant_s <= 100, "creep.time_constant_s",
          creep.time_constant_s, "0 < time_constant_s <= 100");
}

void StageParameters::ValidateDriveMap() const {
  const auto& in = drive_map_in_v;
  const auto& out = drive_map_out_v;
  Require(
      in.size() == out.size(), "drive_map_out_v", static_cast<double>(out.size()),
      "drive_map_out_v has as many knots as drive_map_in_v (" + std::to_string(in.size()) + ")");
  Require(in.size() >= 2, "drive_map_in_v", static_cast<double>(in.size()), "at least 2 knots");
  bool has_zero = false;
  for (size_t i = 0; i < in.size(); ++i) {
    const std::string idx = "[" + std::to_string(i) + "]";
    RequireFinite("drive_map_in_v" + idx, in[i]);
    RequireFinite("drive_map_out_v" + idx, out[i]);
    if (i > 0) {
      Require(in[i] > in[i - 1], "drive_map_in_v" + idx, in[i],
              "knots strictly increasing (previous " + Fmt(in[i - 1]) + ")");
      Require(out[i] >= out[i - 1], "drive_map_out_v" + idx, out[i],
              "values non-decreasing (previous " + Fmt(out[i - 1]) + ")");
    }
    if (in[i] == 0) {
      has_zero = true;
      Require(out[i] == 0, "drive_map_out_v" + idx, out[i], "M(0) = 0");
    }
  }
  Require(has_zero, "drive_map_in_v", 0.0, "a knot at 0 V (with M(0) = 0)");
}

long StageParameters::RecordStride() const {
  return std::max(1L, std::lround(sample_rate_hz / RecordRateHz()));
}

std::string StageStatus::Describe() const {
  std::string s;
  if (travel_limit_hit) s += "travel limit hit at t = " + Fmt(first_travel_hit_s) + " s";
  if (velocity_limit_exceeded) {
    if (!s.empty()) s += "; ";
    s += "velocity limit exceeded at t = " + Fmt(first_velocity_exceed_s) + " s";
  }
  return s.empty() ? "none" : s;
}

}  // namespace sysid
