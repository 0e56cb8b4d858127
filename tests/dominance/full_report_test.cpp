// FullReport of a dominance analysis: the brief paragraph plus every term's statistics.
#include <catch2/catch.hpp>

#include "sysid/dominance.hpp"

using Catch::Contains;

TEST_CASE("dominance: FullReport adds every term's and variable's statistics",
          "[dominance][report]") {
  sysid::DominanceResult r;
  r.source = "rec.csv";
  r.dominant = "v";
  sysid::TermStats viscous{"viscous", 2.5, 4.25, 1.0, 0.875, 1.5, false};
  sysid::TermStats accel{"acceleration", 0.125, 0.5, 0.05, 0.0625, 0.75, true};
  r.terms = {accel, viscous};
  r.ranking = {{"v", 2.5, 4.25, 1.0, 1.0, 1.0, false}};
  const std::string full = r.FullReport();
  CHECK(full.rfind(r.BriefReport(), 0) == 0);
  CHECK_THAT(full, Contains("acceleration   rms 0.125 peak 0.5 ratio 0.05 bound 0.0625 max 0.75 (negligible)"));
  CHECK_THAT(full, Contains("viscous        rms 2.5 peak 4.25 ratio 1 bound 0.875 max 1.5"));
  CHECK_THAT(full, Contains("variables by rms:"));
}
