// Stack files: the bundled one is the default stack, writing and reading give the same
// parameters, and bad values are errors positioned at their key.
#include <catch2/catch.hpp>
#include <string>

#include "support/test_support.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"
#include "sysid/stack.hpp"

using Catch::Contains;

namespace {

std::string Error(const std::string& text) {
  try {
    sysid::ParseStackParameters(text, "s.json");
  } catch (const sysid::InputError& e) {
    return e.what();
  }
  return "(no error)";
}

void Same(const sysid::StackParameters& a, const sysid::StackParameters& b) {
  CHECK(a.name == b.name);
  CHECK(a.hysteresis.linear_gain_m_per_v == b.hysteresis.linear_gain_m_per_v);
  CHECK(a.hysteresis.thresholds_v == b.hysteresis.thresholds_v);
  CHECK(a.hysteresis.weights_m_per_v == b.hysteresis.weights_m_per_v);
  CHECK(a.hysteresis.rate_weights_m_s_per_v2 == b.hysteresis.rate_weights_m_s_per_v2);
  CHECK(a.creep.time_constants_s == b.creep.time_constants_s);
  CHECK(a.creep.fractions == b.creep.fractions);
  CHECK(a.mechanics.resonance_hz == b.mechanics.resonance_hz);
  CHECK(a.mechanics.damping_ratio == b.mechanics.damping_ratio);
  CHECK(a.rig.control_rate_hz == b.rig.control_rate_hz);
  CHECK(a.rig.voltage_min_v == b.rig.voltage_min_v);
  CHECK(a.rig.voltage_max_v == b.rig.voltage_max_v);
  CHECK(a.rig.dac_bits == b.rig.dac_bits);
  CHECK(a.rig.sensor_resolution_m == b.rig.sensor_resolution_m);
  CHECK(a.rig.sensor_noise_m == b.rig.sensor_noise_m);
  CHECK(a.integrator.method == b.integrator.method);
  CHECK(a.integrator.relative_tolerance == b.integrator.relative_tolerance);
  CHECK(a.integrator.position_tolerance_m == b.integrator.position_tolerance_m);
}

}  // namespace

TEST_CASE("stack file: written and read back, and the bundled file is the default", "[stack]") {
  const auto d = sysid::StackParameters::Default();
  Same(sysid::ParseStackParameters(sysid::StackParametersToJson(d), "d.json"), d);
  Same(sysid::ReadStackParameters(sysid::test::SourcePath("datasets/piezo_stack/stack.json")), d);
  CHECK(sysid::IsStackFileText(sysid::StackParametersToJson(d)));
  CHECK_FALSE(sysid::IsStackFileText("{\"plant\": \"stage\"}"));
  CHECK_FALSE(sysid::IsStackFileText("not json"));
  CHECK(sysid::IsStackPresetName("piezo-stack"));
  Same(sysid::LoadStack("piezo-stack"), d);
  // Keys left out keep the default's values.
  const auto p = sysid::ParseStackParameters(
      "{\"plant\": \"piezo-stack\", \"mechanics\": {\"resonance_hz\": 2000}}", "p.json");
  CHECK(p.mechanics.resonance_hz == 2000);
  CHECK(p.hysteresis.thresholds_v == d.hysteresis.thresholds_v);
}

TEST_CASE("stack file: bad values name the file, line, column and key", "[stack]") {
  CHECK_THAT(
      Error("{\"plant\": \"piezo-stack\",\n \"hysteresis\": {\"thresholds_v\": [1, 3, 2, 4, 5, "
            "6, 7, 8, 9, 10]}}"),
      Contains("s.json:2:") && Contains("hysteresis.thresholds_v[2]: expected thresholds "
                                        "increasing"));
  CHECK_THAT(Error("{\"plant\": \"piezo-stack\",\n \"hysteresis\": {\"weights_m_per_v\": [1e-8]}}"),
             Contains("s.json:2:17: hysteresis.weights_m_per_v: expected one weight per "
                      "threshold (10), found 1"));
  CHECK_THAT(Error("{\"plant\": \"piezo-stack\",\n\"mechanics\": {\"resonance_hz\": 6000}}"),
             Contains("s.json:2:15: mechanics.resonance_hz: expected 0 < resonance_hz < "
                      "control_rate_hz / 2"));
  CHECK_THAT(Error("{\"plant\": \"piezo-stack\",\n\"creep\": {\"fractions\": [0.01, -1, 0.01]}}"),
             Contains("creep.fractions[1]: expected kappa_j in [0, 10], found -1"));
  CHECK_THAT(Error("{\"plant\": \"piezo-stack\", \"rig\": {\"voltage_max_v\": -30}}"),
             Contains("rig.voltage_max_v: expected voltage_max_v > voltage_min_v"));
  CHECK_THAT(Error("{\"plant\": \"piezo-stack\", \"rig\": {\"sensor_nois_m\": 1}}"),
             Contains("sensor_nois_m"));
  CHECK_THAT(Error("{\"name\": \"x\"}"), Contains("missing required key 'plant'"));
  CHECK_THAT(Error("{\"plant\": \"piezo-stack\", \"integrator\": {\"method\": \"rk4\"}}"),
             Contains("integrator.method: expected \"cvode\" or \"exact\", found string \"rk4\""));
  CHECK_THAT(Error("{\"plant\": \"stage\"}"), Contains("plant: expected \"piezo-stack\""));
  CHECK_THAT(Error("{\"plant\": \"piezo-stack\", \"hysteresis\": {\"linear_gain_m_per_v\": 0}}"),
             Contains("hysteresis.linear_gain_m_per_v: expected linear_gain_m_per_v > 0"));
}
