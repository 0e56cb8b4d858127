// identify_json.cpp: the identification options round-trip through JSON; bad keys, types and
// rules are positioned errors.
#include <catch2/catch.hpp>
#include <limits>
#include <string>

#include "sysid/error.hpp"
#include "sysid/identify.hpp"

TEST_CASE("pulse identification options round-trip through JSON", "[identify][json]") {
  sysid::PulseIdentificationOptions o;
  o.motion.velocity_column = "vm";
  o.detection.min_duration_s = 0.35;
  o.detection.u_tolerance_v = 2e-3;
  o.detection.zero_tolerance_v = 5e-3;
  o.plateau.window_fraction = 0.4;
  o.plateau.settle_tolerance = 0.03;
  o.plateau.min_speed_mps = 2e-4;
  o.plateau.max_speed_mps = 0.8;
  o.plateau.travel_max_m = 0.25;  // travel_min_m stays -infinity: written as null
  o.plateau.min_window_samples = 12;
  o.fit.a3 = 5.5;
  const std::string text = sysid::ToJson(o);
  const auto back = sysid::PulseIdentificationOptionsFromJson(text, "p.json");
  CHECK(back.motion.velocity_column == "vm");
  CHECK(back.detection.min_duration_s == 0.35);
  CHECK(back.detection.zero_tolerance_v == 5e-3);
  CHECK(back.plateau.window_fraction == 0.4);
  CHECK(back.plateau.max_speed_mps == 0.8);
  CHECK(back.plateau.travel_max_m == 0.25);
  CHECK(back.plateau.travel_min_m == -std::numeric_limits<double>::infinity());
  CHECK(back.plateau.min_window_samples == 12);
  CHECK(back.fit.a3 == 5.5);
  CHECK(sysid::ToJson(back) == text);
  // The parts read on their own too.
  CHECK(sysid::ToJson(sysid::PlateauOptionsFromJson(sysid::ToJson(o.plateau), "pl.json")) ==
        sysid::ToJson(o.plateau));
  CHECK(sysid::PulseDetectionOptionsFromJson(sysid::ToJson(o.detection), "d.json").u_tolerance_v ==
        2e-3);
  CHECK(sysid::PulseFitOptionsFromJson(sysid::ToJson(o.fit), "f.json").a3 == 5.5);
  // Null is the "no limit" default.
  CHECK(sysid::PlateauOptionsFromJson("{\"max_speed_mps\": null}", "pl.json").max_speed_mps ==
        std::numeric_limits<double>::infinity());
}

TEST_CASE("trajectory options round-trip through JSON", "[identify][json]") {
  sysid::TrajectoryOptions o;
  o.motion.derivative.cutoff_hz = 30;
  o.tau_s = 0.002;
  o.tune_delay = true;
  o.tau_min_s = 0.001;
  o.tau_max_s = 0.01;
  o.decimation = 4;
  o.min_speed_mps = 5e-3;
  o.trim_samples = 7;
  o.offset = true;
  o.symmetric_viscous = true;
  const std::string text = sysid::ToJson(o);
  const auto back = sysid::TrajectoryOptionsFromJson(text, "t.json");
  CHECK(back.motion.derivative.cutoff_hz == 30);
  CHECK(back.tau_s == 0.002);
  CHECK(back.tune_delay);
  CHECK(back.decimation == 4);
  CHECK(back.trim_samples == 7);
  CHECK(back.offset);
  CHECK(back.symmetric_viscous);
  CHECK(sysid::ToJson(back) == text);
  // The trajectory method's own default motion (Butterworth) is what an absent key gives.
  CHECK(sysid::TrajectoryOptionsFromJson("{}", "t.json").motion.derivative.method ==
        sysid::TrajectoryOptions::DefaultMotion().derivative.method);
}

TEST_CASE("identification options JSON: bad input names the place", "[identify][json]") {
  using Catch::Contains;
  CHECK_THROWS_WITH(
      sysid::PulseIdentificationOptionsFromJson("{\"plateau\": {\n  \"window_fraction\": 0}}",
                                                "p.json"),
      Contains("p.json:2:3: plateau.window_fraction: expected"));
  CHECK_THROWS_WITH(
      sysid::PulseIdentificationOptionsFromJson("{\"fit\": {\"a3\": 1, \"a4\": 2}}", "p.json"),
      Contains("p.json:1:19: unknown key 'a4' in 'fit'"));
  CHECK_THROWS_WITH(sysid::PulseIdentificationOptionsFromJson("{\"fit\": {\"a3\": -6}}", "p.json"),
                    Contains("p.json:1:10: fit.a3: expected a3 > 0"));
  CHECK_THROWS_WITH(sysid::PulseIdentificationOptionsFromJson("{\"detection\": 3}", "p.json"),
                    Contains("detection: expected an object"));
  CHECK_THROWS_WITH(sysid::TrajectoryOptionsFromJson("{\"decimation\": 0}", "t.json"),
                    Contains("t.json:1:2: decimation: expected"));
  CHECK_THROWS_WITH(sysid::TrajectoryOptionsFromJson("{\"tune_delay\": \"yes\"}", "t.json"),
                    Contains("tune_delay: expected true or false"));
  CHECK_THROWS_WITH(sysid::PlateauOptionsFromJson("{\"min_window_samples\": 1e3}", "pl.json"),
                    Contains("min_window_samples: expected an integer"));
}
