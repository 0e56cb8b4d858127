// FullReport of the identifications: the brief paragraph plus the fit and every pulse.
#include <catch2/catch.hpp>

#include "sysid/identify.hpp"

using Catch::Contains;

namespace {
sysid::LinearFit Fit() {
  sysid::LinearFit f;
  f.rows = 2;
  f.rank = 2;
  f.dof = 0;
  f.condition_number = 12.5;
  f.rms_residual = 0.0625;
  f.relative_error = 0.03125;
  f.residuals = Eigen::Vector2d(0.125, -0.25);
  f.r_diagonal = {{"a1p", 3.5}, {"a2p", 0.25}};
  return f;
}
}  // namespace

TEST_CASE("pulse identification: FullReport adds the fit, equations and pulses",
          "[identify][report]") {
  sysid::PulseIdentificationResult r;
  r.fit = Fit();
  r.points = {{1.5, 0.01, "table.csv:2"}, {-2.0, -0.02, "table.csv:3"}};
  sysid::PulseEstimate e;
  e.pulse.source = "rec.csv";
  e.pulse.amplitude_v = 1.75;
  e.window_samples = 321;
  e.status = sysid::PulseStatus::kStuck;
  e.reason = "never moved";
  r.pulses = {e};
  const std::string full = r.FullReport();
  CHECK(full.rfind(r.BriefReport(), 0) == 0);
  CHECK_THAT(full, Contains("rank 2, dof 0, condition 12.5"));
  CHECK_THAT(full, Contains("relative error 0.03125"));
  CHECK_THAT(full, Contains("a1p 3.5 a2p 0.25"));
  CHECK_THAT(full, Contains("table.csv:3 u -2 v -0.02 r -0.25"));
  CHECK_THAT(full, Contains("pulses: 1"));
  CHECK_THAT(full, Contains("u 1.75 V"));
  CHECK_THAT(full, Contains("321 samples, stuck: never moved"));
}

TEST_CASE("trajectory identification: FullReport adds the fit, filter and delay curve",
          "[identify][report]") {
  sysid::TrajectoryIdentificationResult r;
  r.fit = Fit();
  r.offset_mps2 = 0.375;
  r.derivative = sysid::DerivativeMethod::kSavitzkyGolay;
  r.tau_curve = {{0.002, 4.5}, {0.004, 3.25}};
  const std::string full = r.FullReport();
  CHECK(full.rfind(r.BriefReport(), 0) == 0);
  CHECK_THAT(full, Contains("condition 12.5"));
  CHECK_THAT(full, Contains("velocity filter: savgol"));
  CHECK_THAT(full, Contains("offset c0 0.375 m/s^2"));
  CHECK_THAT(full, Contains("delay curve: 2 points"));
  CHECK_THAT(full, Contains("0.004 3.25"));
}
