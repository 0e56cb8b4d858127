// motion_json.cpp / signal_json.cpp: MotionOptions (with its DerivativeOptions) round-trips
// through JSON; bad keys, types and rules are positioned errors.
#include <catch2/catch.hpp>
#include <string>

#include "sysid/error.hpp"
#include "sysid/motion.hpp"

TEST_CASE("motion options round-trip through JSON", "[motion][json]") {
  sysid::MotionOptions o;
  o.derivative.method = sysid::DerivativeMethod::kSavitzkyGolay;
  o.derivative.cutoff_hz = 12.5;
  o.derivative.butterworth_order = 6;
  o.derivative.savgol_window = 31;
  o.derivative.savgol_order = 4;
  o.velocity_column = "v_meas";
  o.prefer_velocity_column = false;  // not the default (true)
  o.max_relative_jitter = 0.05;
  const std::string text = sysid::ToJson(o);
  const auto back = sysid::MotionOptionsFromJson(text, "m.json");
  CHECK(back.derivative.method == o.derivative.method);
  CHECK(back.derivative.cutoff_hz == 12.5);
  CHECK(back.derivative.butterworth_order == 6);
  CHECK(back.derivative.savgol_window == 31);
  CHECK(back.derivative.savgol_order == 4);
  CHECK(back.velocity_column == "v_meas");
  CHECK_FALSE(back.prefer_velocity_column);
  CHECK(back.max_relative_jitter == 0.05);
  CHECK(sysid::ToJson(back) == text);
  // Absent keys keep their defaults: an empty object is the default options.
  CHECK(sysid::ToJson(sysid::MotionOptionsFromJson("{}", "e.json")) ==
        sysid::ToJson(sysid::MotionOptions{}));
}

TEST_CASE("motion options JSON: bad input names the place", "[motion][json]") {
  using Catch::Contains;
  CHECK_THROWS_AS(sysid::MotionOptionsFromJson("{\"max_relative_jitter\": -1}", "m.json"),
                  sysid::InputError);
  CHECK_THROWS_WITH(sysid::MotionOptionsFromJson("{\n  \"max_relative_jitter\": -1\n}", "m.json"),
                    Contains("m.json:2:3: max_relative_jitter: expected max_relative_jitter >= 0"));
  CHECK_THROWS_WITH(sysid::MotionOptionsFromJson("{\"jitter\": 1}", "m.json"),
                    Contains("m.json:1:2: unknown key 'jitter'"));
  CHECK_THROWS_WITH(
      sysid::MotionOptionsFromJson("{\"derivative\": {\n \"method\": \"spline\"}}", "m.json"),
      Contains("m.json:2:2: derivative.method: expected \"central\", \"butterworth\" or "
               "\"savgol\", found string \"spline\""));
  CHECK_THROWS_WITH(sysid::MotionOptionsFromJson("{\"derivative\": {\"savgol_window\": 2.5}}",
                                                 "m.json"),
                    Contains("derivative.savgol_window: expected an integer"));
  CHECK_THROWS_WITH(sysid::MotionOptionsFromJson("{\"velocity_column\": \"\"}", "m.json"),
                    Contains("m.json:1:2: velocity_column: expected a column name, found empty"));
  CHECK_THROWS_WITH(sysid::MotionOptionsFromJson("{\"prefer_velocity_column\": 1}", "m.json"),
                    Contains("prefer_velocity_column: expected true or false, found 1"));
}
