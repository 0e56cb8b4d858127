// control_json.cpp: a tracking run's metrics as JSON (the traces stay out), and the gains'
// behaviour as tune-pi --json writes it.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "sysid/control.hpp"
#include "sysid/control_tuning.hpp"
#include "sysid/error.hpp"

namespace {

std::vector<std::string> Keys(const nlohmann::ordered_json& j) {
  std::vector<std::string> keys;
  for (auto it = j.begin(); it != j.end(); ++it) keys.push_back(it.key());
  return keys;
}

}  // namespace

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

TEST_CASE("PI behaviour JSON: the step and sine objects tune-pi publishes", "[control][json]") {
  sysid::PiBehaviour b;
  b.step.step_m = 1e-3;
  b.step.rise_time_s = 0.02;
  b.step.settling_time_s = std::numeric_limits<double>::quiet_NaN();  // outside at the end
  b.step.saturated_samples = 3;
  b.sine.amplitude_m = 2e-3;
  b.sine.frequency_hz = 1;
  b.sine.run.rms_error_m = 4e-6;
  b.sine.limit_cycle.limit_cycle = true;
  const auto j = nlohmann::ordered_json::parse(sysid::ToJson(b));
  CHECK(Keys(j) == std::vector<std::string>{"step", "sine"});
  CHECK(Keys(j["step"]) ==
        std::vector<std::string>{"step_m", "overshoot", "rise_time_s", "settling_time_s",
                                 "final_error_m", "saturated_samples", "max_abs_u_v"});
  CHECK(Keys(j["sine"]) ==
        std::vector<std::string>{"amplitude_m", "frequency_hz", "max_error_m", "rms_error_m",
                                 "rms_u_v", "max_abs_u_v", "total_variation_v",
                                 "saturated_samples", "limit_cycle"});
  CHECK(Keys(j["sine"]["limit_cycle"]) ==
        std::vector<std::string>{"window_s", "threshold_m", "error_peak_to_peak_m",
                                 "control_peak_to_peak_v", "limit_cycle"});
  CHECK(j["step"]["settling_time_s"].is_null());
  CHECK(j["step"]["rise_time_s"] == 0.02);
  CHECK(j["step"]["saturated_samples"] == 3);
  CHECK(j["sine"]["rms_error_m"] == 4e-6);
  CHECK(j["sine"]["limit_cycle"]["limit_cycle"] == true);
}
