// delay_json.cpp: the delay-tuning, segment and refinement options round-trip through JSON;
// bad keys, types and rules are positioned errors.
#include <catch2/catch.hpp>
#include <string>

#include "sysid/delay.hpp"
#include "sysid/error.hpp"

TEST_CASE("delay tuning options round-trip through JSON", "[delay][json]") {
  sysid::DelayTuningOptions o;
  o.tau_min_s = 0.001;
  o.tau_max_s = 0.015;
  o.x_tolerance_s = 1e-8;
  o.coarse_evaluations = 9;
  o.max_evaluations = 30;
  o.curve_points = 25;
  o.motion.derivative.method = sysid::DerivativeMethod::kButterworthCentral;
  o.segments.detection.min_duration_s = 0.3;
  o.segments.rest_speed_mps = 4e-3;
  o.segments.reuse_identical_segments = false;
  o.sim_rtol = 1e-7;
  o.sim_atol = 1e-10;
  o.threads = 3;
  const std::string text = sysid::ToJson(o);
  const auto back = sysid::DelayTuningOptionsFromJson(text, "d.json");
  CHECK(back.tau_min_s == 0.001);
  CHECK(back.tau_max_s == 0.015);
  CHECK(back.coarse_evaluations == 9);
  CHECK(back.curve_points == 25);
  CHECK(back.motion.derivative.method == sysid::DerivativeMethod::kButterworthCentral);
  CHECK(back.segments.detection.min_duration_s == 0.3);
  CHECK_FALSE(back.segments.reuse_identical_segments);
  CHECK(back.sim_atol == 1e-10);
  CHECK(back.threads == 3);
  CHECK(sysid::ToJson(back) == text);
  CHECK(sysid::ToJson(sysid::SegmentOptionsFromJson(sysid::ToJson(o.segments), "s.json")) ==
        sysid::ToJson(o.segments));
}

TEST_CASE("refine options round-trip through JSON", "[delay][json]") {
  sysid::RefineOptions o;
  o.motion.prefer_velocity_column = false;  // not the default (true)
  o.detection.zero_tolerance_v = 0.01;
  o.refine_a3 = false;
  o.refine_tau = false;
  o.tau_max_s = 0.03;
  o.max_iterations = 7;
  o.threads = 2;
  o.sim_rtol = 1e-6;
  const std::string text = sysid::ToJson(o);
  const auto back = sysid::RefineOptionsFromJson(text, "r.json");
  CHECK_FALSE(back.motion.prefer_velocity_column);
  CHECK(back.detection.zero_tolerance_v == 0.01);
  CHECK_FALSE(back.refine_a3);
  CHECK_FALSE(back.refine_tau);
  CHECK(back.max_iterations == 7);
  CHECK(sysid::ToJson(back) == text);
}

TEST_CASE("delay options JSON: bad input names the place", "[delay][json]") {
  using Catch::Contains;
  // A cross-field rule is reported at the field Validate() names.
  CHECK_THROWS_WITH(
      sysid::DelayTuningOptionsFromJson("{\"tau_min_s\": 0.01,\n \"tau_max_s\": 0.005}", "d.json"),
      Contains("d.json:2:2: tau_max_s: expected tau_max_s > tau_min_s [s], found 0.005"));
  CHECK_THROWS_WITH(
      sysid::DelayTuningOptionsFromJson("{\"segments\": {\"rest_speed_mps\": 0}}", "d.json"),
      Contains("d.json:1:15: segments.rest_speed_mps: expected rest_speed_mps > 0"));
  CHECK_THROWS_WITH(sysid::DelayTuningOptionsFromJson("{\"tau\": 0.01}", "d.json"),
                    Contains("d.json:1:2: unknown key 'tau'"));
  CHECK_THROWS_WITH(sysid::RefineOptionsFromJson("{\"max_iterations\": \"50\"}", "r.json"),
                    Contains("max_iterations: expected an integer"));
  CHECK_THROWS_WITH(sysid::RefineOptionsFromJson("{\"max_iterations\": 0}", "r.json"),
                    Contains("r.json:1:2: max_iterations: expected max_iterations >= 1"));
}
