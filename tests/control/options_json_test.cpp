// control_json.cpp: the PI and reference-profile options round-trip through JSON; bad keys,
// types and rules are positioned errors.
#include <catch2/catch.hpp>
#include <string>

#include "sysid/control.hpp"
#include "sysid/error.hpp"

TEST_CASE("PI and profile options round-trip through JSON", "[control][json]") {
  sysid::PiOptions pi = sysid::PiOptions::ForActuatorDelayStage();
  pi.sample_time_s = 5e-4;
  pi.u_max_v = 8;
  pi.anti_windup = sysid::AntiWindup::kNone;
  const std::string text = sysid::ToJson(pi);
  const auto back = sysid::PiOptionsFromJson(text, "pi.json");
  CHECK(back.kp_v_per_m == 3000);
  CHECK(back.ki_v_per_m_s == 104100);
  CHECK(back.sample_time_s == 5e-4);
  CHECK(back.u_max_v == 8);
  CHECK(back.anti_windup == sysid::AntiWindup::kNone);
  CHECK(sysid::ToJson(back) == text);

  sysid::SmoothProfileOptions p;
  p.frequency_hz = 2;
  p.amplitude_m = -0.004;
  p.dwell_fraction = 0.2;
  p.cycles = 3;
  p.sample_rate_hz = 2000;
  const std::string ptext = sysid::ToJson(p);
  const auto pback = sysid::SmoothProfileOptionsFromJson(ptext, "p.json");
  CHECK(pback.frequency_hz == 2);
  CHECK(pback.amplitude_m == -0.004);
  CHECK(pback.cycles == 3);
  CHECK(sysid::ToJson(pback) == ptext);
}

TEST_CASE("control options JSON: bad input names the place", "[control][json]") {
  using Catch::Contains;
  CHECK_THROWS_WITH(sysid::PiOptionsFromJson("{\n\"u_max_v\": 0}", "pi.json"),
                    Contains("pi.json:2:1: u_max_v: expected u_max_v > 0, found 0"));
  CHECK_THROWS_WITH(sysid::PiOptionsFromJson("{\"anti_windup\": \"clamp\"}", "pi.json"),
                    Contains("anti_windup: expected \"none\" or \"conditional-integration\""));
  CHECK_THROWS_WITH(sysid::PiOptionsFromJson("{\"kp\": 1}", "pi.json"),
                    Contains("pi.json:1:2: unknown key 'kp'"));
  CHECK_THROWS_WITH(sysid::SmoothProfileOptionsFromJson("{\"dwell_fraction\": 0.5}", "p.json"),
                    Contains("p.json:1:2: dwell_fraction: expected 0 <= dwell_fraction < 0.5"));
  CHECK_THROWS_WITH(sysid::SmoothProfileOptionsFromJson("{\"cycles\": true}", "p.json"),
                    Contains("cycles: expected an integer"));
}
