// control_json.cpp: a tracking run's metrics as JSON (the traces stay out).
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "sysid/control.hpp"

TEST_CASE("tracking metrics JSON", "[control][json]") {
  sysid::TrackingResult r;
  r.t_s = Eigen::VectorXd::LinSpaced(3, 0.0, 0.002);
  r.max_error_m = 2e-6;
  r.rms_error_m = 1e-6;
  r.rms_u_v = 1.5;
  r.max_abs_u_v = 3.25;
  r.total_variation_v = 12.0;
  r.saturated_samples = 4;
  const auto j = nlohmann::json::parse(sysid::ToJson(r));
  CHECK(j.size() == 6);
  CHECK(j["max_error_m"] == 2e-6);
  CHECK(j["rms_error_m"] == 1e-6);
  CHECK(j["rms_u_v"] == 1.5);
  CHECK(j["max_abs_u_v"] == 3.25);
  CHECK(j["total_variation_v"] == 12.0);
  CHECK(j["saturated_samples"] == 4);
}
