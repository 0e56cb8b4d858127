// The stage presets: the calibrated virtual stage (the default), the velocity source, the
// actuator-delay model and the drive-hysteresis variants, each built once from the member
// defaults; the table every message listing them reads.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "sysid/error.hpp"
#include "sysid/stage.hpp"

namespace sysid {

namespace {

// The velocity source on the member defaults (1 kHz loop, 0.3 ms envelope): the default
// before the loop-rate candidate C, kept as the preset "virtual-1khz".
StageParameters VelocitySourceAtMemberDefaults() {
  StageParameters p;  // velocity source: the member defaults are the calibrated values
  // Speed map through the paper's ten pulse points: a held pulse settles where
  // p (v_f(u_i) - v) = g(v), so v_f(u_i) = v_i + sgn(v_i) g(|v_i|) / p gives exactly v_i.
  p.velocity_source().SetSpeedMapThrough(StageParameters::PaperPulseTable());
  return p;
}

// The loop-rate candidate C (docs/virtual_stage.md, "Loop rate"): at the member defaults'
// 1 kHz loop with a 0.3 ms envelope the paper's PI gains ring in motion and the NN
// feedforward beats the analytic inverse at 5 of 12 seeds (F5); a 10 kHz loop recorded at
// 1 kHz (the paper's record rate) with a 0.1 ms envelope is quiet after each breakaway and
// meets F5 at 11 of 12. The member defaults stay 1 kHz / 0.3 ms because the actuator-delay
// preset builds on them; the speed map does not depend on the rates or the lag. The
// drive-hysteresis presets build on C itself, not on Default(), so that they stay C if the
// default moves again.
StageParameters LoopRateC() {
  StageParameters p = VelocitySourceAtMemberDefaults();
  p.rig.sample_rate_hz = 10000;
  p.rig.record_rate_hz = 1000;
  p.driver.lag_time_constant_s = 0.0001;
  return p;
}

}  // namespace

namespace {

// Candidate C with asymmetric play operators of thresholds r [V], each of weight w (alpha 0.3).
StageParameters LoopRateCWithPlay(const std::vector<double>& r, double w) {
  StageParameters p = LoopRateC();
  DriveHysteresis h;
  h.thresholds_v = r;
  h.weights.assign(r.size(), w);
  h.rate_weights_s_per_v.assign(r.size(), 0.0);
  h.rate_time_constant_s = 0.01;
  h.asymmetry = 0.3;
  p.SetDriveHysteresis(h);
  return p;
}

// Preset "drive-hysteresis-static" (docs/virtual_stage.md, "Drive hysteresis"):
// C with the ceramic's asymmetric, rate-independent hysteresis.
StageParameters DriveHysteresisStaticPreset() {
  StageParameters p = LoopRateCWithPlay({0.1, 0.2, 0.3}, 0.2);
  p.name = "virtual PLS8/HR-8 (velocity source, static drive hysteresis)";
  return p;
}

// Preset "drive-hysteresis" (docs/virtual_stage.md, "F8 with F5"): C with narrow
// play operators whose lag partly creeps out (the creep's loop share), so that the loop widens
// with the rate (F8 (c)) while a held pulse settles as without it (F1-F3). It meets every
// required fact at seed 1 and F5 at 14 of 24 seeds (wider operators: 3 of 12).
StageParameters DriveHysteresisPreset() {
  StageParameters p = LoopRateCWithPlay({0.05, 0.1, 0.2}, 0.16);
  p.name = "virtual PLS8/HR-8 (velocity source, drive hysteresis with creep)";
  DriveCreep c;
  c.voltage_share = 0;
  c.loop_share = 0.3;
  c.time_constant_s = 0.04;
  p.SetDriveCreep(c);
  return p;
}

}  // namespace

// The default is the drive-hysteresis stage: of every stage tried it is the closest to the
// paper that meets each required fact at seed 1, F8's loop among them. C is the preset
// "velocity-source".
StageParameters StageParameters::Default() { return DriveHysteresisPreset(); }

StageParameters StageParameters::VelocitySource() {
  StageParameters p = LoopRateC();
  p.name = "virtual PLS8/HR-8 (velocity source)";
  return p;
}

namespace {

StageParameters VirtualOneKhz() {
  StageParameters p = VelocitySourceAtMemberDefaults();
  p.name = "virtual PLS8/HR-8 (velocity source, 1 kHz loop)";
  return p;
}

struct PresetEntry {
  const char* name;
  StageParameters (*make)();
};

// Every preset, once: IsPresetName, Preset, PresetNames and every message listing them read it.
constexpr PresetEntry kPresets[] = {{"virtual", &StageParameters::Default},
                                    {"velocity-source", &StageParameters::VelocitySource},
                                    {"virtual-1khz", &VirtualOneKhz},
                                    {"actuator-delay", &StageParameters::ActuatorDelay},
                                    {"drive-hysteresis", &StageParameters::Default},
                                    {"drive-hysteresis-static", &DriveHysteresisStaticPreset}};

}  // namespace

const std::vector<std::string>& StageParameters::PresetNames() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> v;
    for (const PresetEntry& e : kPresets) v.emplace_back(e.name);
    return v;
  }();
  return names;
}

std::string StageParameters::PresetNameList() {
  std::string text;
  for (const std::string& name : PresetNames())
    text += (text.empty() ? "" : ", ") + name + (name == "virtual" ? " (= drive-hysteresis)" : "");
  return text;
}

bool StageParameters::IsPresetName(const std::string& name) {
  const auto& names = PresetNames();
  return std::find(names.begin(), names.end(), name) != names.end();
}

StageParameters StageParameters::Preset(const std::string& name) {
  for (const PresetEntry& e : kPresets)
    if (name == e.name) return e.make();
  throw OptionsError("stage preset '" + name + "' is not one of " + PresetNameList());
}

StageParameters StageParameters::ActuatorDelay() {
  StageParameters p;
  p.name = "virtual PLS8/HR-8 (actuator delay)";
  ActuatorDelayPlant& ad = p.plant.emplace<ActuatorDelayPlant>();
  p.driver.transport_delay_s = 0.002;
  p.driver.lag_time_constant_s = 0.0015;
  // Friction branches near the paper's rough model (a1 ~ s2, a2 ~ Fc + a3 dz) with a Stribeck
  // dip the rough model lacks; breakaway at dz + Fs/a3 = 0.63 V forward, 1.32 V backward.
  ad.forward = {2.2, 2.9, 0.004, 104.0};
  ad.backward = {5.9, 7.0, 0.004, 117.0};
  // The driver's static characteristic, calibrated to the paper's pulse table: the knot at
  // |u| - dz holds (g(v) + s2 v) / a3 for the paper's measured v at that amplitude u, so a
  // held pulse settles at the paper's velocity (a near-identity map: corrections of <= 4 %).
  ad.drive_map_in_v = {-10.0, -2.35, -2.15, -1.95, -1.85, -1.65, 0.0,
                       1.15,  1.35,  1.45,  1.55,  1.85,  10.0};
  ad.drive_map_out_v = {-10.0,  -2.37173, -2.06792, -1.95658, -1.88462, -1.64497, 0.0,
                        1.1406, 1.36195,  1.44515,  1.55625,  1.84329,  10.0};
  return p;
}

}  // namespace sysid
