// FullReport of the fits by simulation: the brief paragraph plus every diagnostic field.
#include <catch2/catch.hpp>

#include "sysid/delay.hpp"

using Catch::Contains;

TEST_CASE("delay tuning: FullReport adds the model, warnings and cost curve", "[delay][report]") {
  sysid::DelayTuningResult r;
  r.tau_s = 0.0123;
  r.model.tau_s = 0.0123;
  r.model.a1p = 41.5;
  r.samples = 777;
  r.curve = {{0.001, 2.5}, {0.0123, 0.75}};
  r.warnings = {"tau = 0.0123 s is at the search bound"};
  r.message = "xtol reached";
  const std::string brief = r.BriefReport(), full = r.FullReport();
  CHECK(full.rfind(brief, 0) == 0);  // starts with the brief paragraph
  CHECK(full.size() > brief.size());
  CHECK_THAT(full, Contains("a1p 41.5"));
  CHECK_THAT(full, Contains("tau 0.0123 s"));
  CHECK_THAT(full, Contains("samples compared per evaluation: 777"));
  CHECK_THAT(full, Contains("warnings: 1"));
  CHECK_THAT(full, Contains("at the search bound"));
  CHECK_THAT(full, Contains("cost curve: 2 points"));
  CHECK_THAT(full, Contains("0.001 2.5"));
  CHECK_THAT(full, Contains("0.0123 0.75"));
}

TEST_CASE("refinement: FullReport adds each parameter's change and the warnings",
          "[delay][report]") {
  sysid::RefineResult r;
  r.initial.a3 = 6.0;
  r.model.a3 = 7.5;
  r.initial.tau_s = 0.01;
  r.model.tau_s = 0.02;
  r.names = {"a3", "tau"};
  r.std_error = Eigen::Vector2d(0.75, 0.001);
  r.warnings = {"a3 moved from 6 to 7.5"};
  const std::string full = r.FullReport();
  CHECK(full.rfind(r.BriefReport(), 0) == 0);
  CHECK_THAT(full, Contains("a3   6 -> 7.5 (0.1)"));      // relative error 0.75 / 7.5
  CHECK_THAT(full, Contains("tau  0.01 -> 0.02 (0.05)"));  // 0.001 / 0.02
  CHECK_THAT(full, Contains("warnings: 1"));
  CHECK_THAT(full, Contains("a3 moved from 6 to 7.5"));
}
