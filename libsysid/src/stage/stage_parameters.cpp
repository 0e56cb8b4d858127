// StageParameters: the plant it holds, validation of the settings both plants share, the drive
// hysteresis and creep setters and the paper's pulse table (each plant's own fields:
// velocity_source_plant.cpp, actuator_delay_plant.cpp; presets: stage_presets.cpp; the
// steady-state physics: steady_state.cpp).
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <variant>

#include "stage/stage_rules.hpp"
#include "sysid/error.hpp"
#include "sysid/stage.hpp"

namespace sysid {

using internal::StageFmt;
using internal::StageRequire;
using internal::StageRequireFinite;

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

StageModel StageParameters::model() const {
  return std::holds_alternative<ActuatorDelayPlant>(plant) ? StageModel::kActuatorDelay
                                                           : StageModel::kVelocitySource;
}

namespace {

[[noreturn]] void WrongPlant(StageModel held, const char* asked) {
  throw OptionsError("StageParameters: this stage's model is " + ToString(held) + "; " + asked +
                     " belongs to the other model");
}

}  // namespace

VelocitySourcePlant& StageParameters::velocity_source() {
  if (auto* p = std::get_if<VelocitySourcePlant>(&plant)) return *p;
  WrongPlant(model(), "velocity_source()");
}

const VelocitySourcePlant& StageParameters::velocity_source() const {
  if (const auto* p = std::get_if<VelocitySourcePlant>(&plant)) return *p;
  WrongPlant(model(), "velocity_source()");
}

ActuatorDelayPlant& StageParameters::actuator_delay() {
  if (auto* p = std::get_if<ActuatorDelayPlant>(&plant)) return *p;
  WrongPlant(model(), "actuator_delay()");
}

const ActuatorDelayPlant& StageParameters::actuator_delay() const {
  if (const auto* p = std::get_if<ActuatorDelayPlant>(&plant)) return *p;
  WrongPlant(model(), "actuator_delay()");
}

void StageParameters::SetDriveHysteresis(const DriveHysteresis& h) {
  VelocitySourcePlant& vs = velocity_source();
  const double forward = vs.HeldDriveLag(true), backward = vs.HeldDriveLag(false);
  vs.hysteresis = h;
  MoveForHeldLag(forward, backward);
}

void StageParameters::SetDriveCreep(const DriveCreep& c) {
  VelocitySourcePlant& vs = velocity_source();
  const double forward = vs.HeldDriveLag(true), backward = vs.HeldDriveLag(false);
  vs.creep = c;
  MoveForHeldLag(forward, backward);
}

void StageParameters::MoveForHeldLag(double forward_before, double backward_before) {
  VelocitySourcePlant& vs = velocity_source();
  const double forward = vs.HeldDriveLag(true) - forward_before;
  const double backward = vs.HeldDriveLag(false) - backward_before;
  vs.motor.dead_zone_forward_v -= forward;
  vs.motor.dead_zone_backward_v -= backward;
  for (double& u : vs.motor.speed_map_in_v) u += u > 0 ? -forward : backward;
  Validate();
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

void DriverSettings::Validate() const {
  StageRequireFinite("saturation_v", saturation_v);
  StageRequireFinite("transport_delay_s", transport_delay_s);
  StageRequireFinite("lag_time_constant_s", lag_time_constant_s);
  StageRequire(saturation_v > 0, "saturation_v", saturation_v, "saturation_v > 0");
  StageRequire(transport_delay_s >= 0 && transport_delay_s <= 1.0, "transport_delay_s",
               transport_delay_s, "0 <= transport_delay_s <= 1");
  StageRequire(lag_time_constant_s > 0, "lag_time_constant_s", lag_time_constant_s,
               "lag_time_constant_s > 0");
}

void RigSettings::Validate() const {
  const struct {
    const char* field;
    double value;
  } finite[] = {{"sample_rate_hz", sample_rate_hz},
                {"dac_range_v", dac_range_v},
                {"encoder_resolution_m", encoder_resolution_m},
                {"position_noise_m", position_noise_m},
                {"travel_min_m", travel_min_m},
                {"travel_max_m", travel_max_m},
                {"max_velocity_mps", max_velocity_mps},
                {"initial_position_m", initial_position_m}};
  for (const auto& f : finite) StageRequireFinite(f.field, f.value);
  StageRequire(sample_rate_hz > 0, "sample_rate_hz", sample_rate_hz, "sample_rate_hz > 0");
  StageRequireFinite("record_rate_hz", record_rate_hz);
  StageRequire(record_rate_hz >= 0 && record_rate_hz <= sample_rate_hz, "record_rate_hz",
               record_rate_hz,
               "0 <= record_rate_hz <= the control rate sample_rate_hz (" +
                   StageFmt(sample_rate_hz) + "); 0: the control rate");
  if (record_rate_hz > 0) {
    const double n = sample_rate_hz / record_rate_hz;
    StageRequire(std::abs(n - std::round(n)) <= 1e-9 * n, "record_rate_hz", record_rate_hz,
                 "the control rate sample_rate_hz (" + StageFmt(sample_rate_hz) +
                     ") is an integer multiple of record_rate_hz (recordings keep every n-th "
                     "sample)");
  }
  StageRequire(dac_bits >= 1 && dac_bits <= 32, "dac_bits", dac_bits, "1 <= dac_bits <= 32");
  StageRequire(dac_range_v > 0, "dac_range_v", dac_range_v, "dac_range_v > 0");
  StageRequire(travel_max_m > travel_min_m, "travel_max_m", travel_max_m,
               "travel_max_m > travel_min_m (" + StageFmt(travel_min_m) + ")");
  // Bounded on both sides: the encoder divides by its resolution (1e-320 m made every position
  // inf) and noise beyond the travel is no stage; 1 fm is below any encoder made.
  const double span = travel_max_m - travel_min_m;
  StageRequire(encoder_resolution_m >= 1e-15 && encoder_resolution_m <= span,
               "encoder_resolution_m", encoder_resolution_m,
               "1e-15 <= encoder_resolution_m <= the travel (" + StageFmt(span) + ")");
  StageRequire(position_noise_m >= 0 && position_noise_m <= span, "position_noise_m",
               position_noise_m, "0 <= position_noise_m <= the travel (" + StageFmt(span) + ")");
  StageRequire(initial_position_m >= travel_min_m && initial_position_m <= travel_max_m,
               "initial_position_m", initial_position_m,
               "travel_min_m <= initial_position_m <= travel_max_m");
  StageRequire(max_velocity_mps > 0, "max_velocity_mps", max_velocity_mps, "max_velocity_mps > 0");
}

void IntegratorSettings::Validate() const {
  StageRequireFinite("relative_tolerance", relative_tolerance);
  StageRequireFinite("position_tolerance_m", position_tolerance_m);
  StageRequire(relative_tolerance > 0 && relative_tolerance <= 1e-2, "relative_tolerance",
               relative_tolerance, "0 < relative_tolerance <= 1e-2");
  StageRequire(position_tolerance_m > 0, "position_tolerance_m", position_tolerance_m,
               "position_tolerance_m > 0");
  StageRequire(max_steps_per_sample >= 10 && max_steps_per_sample <= 100000000,
               "max_steps_per_sample", static_cast<double>(max_steps_per_sample),
               "10 <= max_steps_per_sample <= 1e8");
}

void StageParameters::Validate() const {
  driver.Validate();
  rig.Validate();
  integrator.Validate();
  std::visit(
      [this](const auto& p) {
        p.Validate();
        p.ValidateWithDriver(driver);
      },
      plant);
}

long RigSettings::RecordStride() const {
  return std::max(1L, std::lround(sample_rate_hz / RecordRateHz()));
}

std::string StageStatus::Describe() const {
  std::string s;
  if (travel_limit_hit) s += "travel limit hit at t = " + StageFmt(first_travel_hit_s) + " s";
  if (velocity_limit_exceeded) {
    if (!s.empty()) s += "; ";
    s += "velocity limit exceeded at t = " + StageFmt(first_velocity_exceed_s) + " s";
  }
  return s.empty() ? "none" : s;
}

}  // namespace sysid
