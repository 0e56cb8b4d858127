// DelayTuningOptions state their own bounds (the CLI reads them from there).
#include <catch2/catch.hpp>

#include "sysid/delay.hpp"
#include "sysid/error.hpp"

TEST_CASE("delay tuning options bound tau and the cost curve", "[delay]") {
  sysid::DelayTuningOptions o;
  CHECK_NOTHROW(o.Validate());
  o.tau_max_s = sysid::DelayTuningOptions::kMaxTau_s;
  CHECK_NOTHROW(o.Validate());
  o.tau_max_s = 1.5;
  CHECK_THROWS_WITH(o.Validate(), Catch::Contains("tau_max_s = 1.5. Violated constraint: "
                                                  "tau_max_s <= 1 [s]"));
  o.tau_max_s = 0.02;
  o.curve_points = sysid::DelayTuningOptions::kMaxCurvePoints;
  CHECK_NOTHROW(o.Validate());
  o.curve_points = 10001;
  CHECK_THROWS_AS(o.Validate(), sysid::OptionsError);
}
