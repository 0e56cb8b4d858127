// control_json.cpp: a tracking run's metrics as JSON (the traces stay out).
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "sysid/control.hpp"
#include "sysid/error.hpp"

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

TEST_CASE("tracking metrics JSON round trip and positioned errors", "[control][json]") {
  sysid::TrackingResult r;
  r.max_error_m = 2.5e-6;
  r.rms_error_m = 1.25e-6;
  r.rms_u_v = 1.5;
  r.max_abs_u_v = 3.25;
  r.total_variation_v = 12.0;
  r.saturated_samples = 4;
  const std::string text = sysid::ToJson(r);
  const sysid::TrackingResult back = sysid::TrackingResultFromJson(text, "track.json");
  CHECK(back.max_error_m == r.max_error_m);
  CHECK(back.rms_error_m == r.rms_error_m);
  CHECK(back.rms_u_v == r.rms_u_v);
  CHECK(back.max_abs_u_v == r.max_abs_u_v);
  CHECK(back.total_variation_v == r.total_variation_v);
  CHECK(back.saturated_samples == r.saturated_samples);
  CHECK(sysid::ToJson(back) == text);
  auto j = nlohmann::json::parse(text);
  j["rms_u_v"] = -1.0;
  try {
    sysid::TrackingResultFromJson(j.dump(1), "bad.json");
    FAIL("a negative rms was read");
  } catch (const sysid::InputError& e) {
    CHECK_THAT(e.what(), Catch::StartsWith("bad.json:"));
    CHECK_THAT(e.what(), Catch::Contains("rms_u_v"));
  }
}
