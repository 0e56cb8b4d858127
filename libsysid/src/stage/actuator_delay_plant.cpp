// The actuator-delay plant's own parameters: their validation (the force actuator and its
// drive map, the LuGre rail's two branches).
#include <cmath>
#include <string>
#include <vector>

#include "stage/stage_rules.hpp"
#include "sysid/stage.hpp"

namespace sysid {

using internal::StageFmt;
using internal::StageRequire;
using internal::StageRequireFinite;

namespace {

void ValidateBranch(const std::string& name, const FrictionBranch& b) {
  StageRequireFinite(name + ".coulomb_mps2", b.coulomb_mps2);
  StageRequireFinite(name + ".static_mps2", b.static_mps2);
  StageRequireFinite(name + ".stribeck_velocity_mps", b.stribeck_velocity_mps);
  StageRequireFinite(name + ".viscous_per_s", b.viscous_per_s);
  StageRequire(b.coulomb_mps2 > 0, name + ".coulomb_mps2", b.coulomb_mps2, "coulomb_mps2 > 0");
  StageRequire(b.static_mps2 >= b.coulomb_mps2, name + ".static_mps2", b.static_mps2,
               "static_mps2 >= coulomb_mps2 (" + StageFmt(b.coulomb_mps2) + ")");
  StageRequire(b.stribeck_velocity_mps > 0, name + ".stribeck_velocity_mps",
               b.stribeck_velocity_mps, "stribeck_velocity_mps > 0");
  StageRequire(b.viscous_per_s >= 0, name + ".viscous_per_s", b.viscous_per_s,
               "viscous_per_s >= 0");
}

void ValidateDriveMap(const std::vector<double>& in, const std::vector<double>& out) {
  StageRequire(
      in.size() == out.size(), "drive_map_out_v", static_cast<double>(out.size()),
      "drive_map_out_v has as many knots as drive_map_in_v (" + std::to_string(in.size()) + ")");
  StageRequire(in.size() >= 2, "drive_map_in_v", static_cast<double>(in.size()),
               "at least 2 knots");
  bool has_zero = false;
  for (size_t i = 0; i < in.size(); ++i) {
    const std::string idx = "[" + std::to_string(i) + "]";
    StageRequireFinite("drive_map_in_v" + idx, in[i]);
    StageRequireFinite("drive_map_out_v" + idx, out[i]);
    if (i > 0) {
      StageRequire(in[i] > in[i - 1], "drive_map_in_v" + idx, in[i],
                   "knots strictly increasing (previous " + StageFmt(in[i - 1]) + ")");
      StageRequire(out[i] >= out[i - 1], "drive_map_out_v" + idx, out[i],
                   "values non-decreasing (previous " + StageFmt(out[i - 1]) + ")");
    }
    if (in[i] == 0) {
      has_zero = true;
      StageRequire(out[i] == 0, "drive_map_out_v" + idx, out[i], "M(0) = 0");
    }
  }
  StageRequire(has_zero, "drive_map_in_v", 0.0, "a knot at 0 V (with M(0) = 0)");
}

}  // namespace

void ActuatorDelayPlant::Validate() const {
  const struct {
    const char* field;
    double value;
  } finite[] = {{"gain_mps2_per_v", gain_mps2_per_v},
                {"dead_zone_v", dead_zone_v},
                {"bristle_stiffness_per_s2", bristle_stiffness_per_s2},
                {"bristle_damping_per_s", bristle_damping_per_s}};
  for (const auto& f : finite) StageRequireFinite(f.field, f.value);
  StageRequire(gain_mps2_per_v > 0, "gain_mps2_per_v", gain_mps2_per_v, "gain_mps2_per_v > 0");
  StageRequire(dead_zone_v >= 0, "dead_zone_v", dead_zone_v, "dead_zone_v >= 0");
  StageRequire(bristle_stiffness_per_s2 > 0, "bristle_stiffness_per_s2", bristle_stiffness_per_s2,
               "bristle_stiffness_per_s2 > 0");
  StageRequire(bristle_damping_per_s >= 0, "bristle_damping_per_s", bristle_damping_per_s,
               "bristle_damping_per_s >= 0");
  ValidateBranch("forward", forward);
  ValidateBranch("backward", backward);
  ValidateDriveMap(drive_map_in_v, drive_map_out_v);
}

void ActuatorDelayPlant::ValidateWithDriver(const DriverSettings& driver) const {
  StageRequire(driver.saturation_v > dead_zone_v, "saturation_v", driver.saturation_v,
               "saturation_v > dead_zone_v (" + StageFmt(dead_zone_v) + ")");
}

}  // namespace sysid
