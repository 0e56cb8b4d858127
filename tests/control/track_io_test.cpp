// What `sysid track` needs from the library: the scheme list, the stage's profile with its
// travel check, the traces as a recording and the summary JSON.
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>
#include <string>

#include "control/control_json.hpp"
#include "core/json_fields.hpp"
#include "sysid/control.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"
#include "sysid/stage.hpp"

using sysid::FeedforwardScheme;

TEST_CASE("feedforward scheme lists parse in order and name their field", "[control]") {
  const auto s = sysid::ParseFeedforwardSchemes("nn,none,analytic");
  REQUIRE(s.size() == 3);
  CHECK(s[0] == FeedforwardScheme::kNetwork);
  CHECK(s[1] == FeedforwardScheme::kNone);
  CHECK(s[2] == FeedforwardScheme::kAnalytic);
  CHECK(sysid::Uses(s, FeedforwardScheme::kAnalytic));
  CHECK_FALSE(sysid::Uses({FeedforwardScheme::kNone}, FeedforwardScheme::kNetwork));
  for (const char* bad : {"", "none,pid"}) {
    try {
      sysid::ParseFeedforwardSchemes(bad);
      FAIL("accepted '" << bad << "'");
    } catch (const sysid::OptionsError& e) {
      CHECK(e.field() == "schemes");
    }
  }
}

TEST_CASE("the stage's profile runs at the stage's rate and stays inside its travel",
          "[control]") {
  sysid::StageParameters stage;
  stage.rig.sample_rate_hz = 2000;
  stage.rig.initial_position_m = 0.05;
  stage.rig.travel_max_m = 0.0575;
  sysid::SmoothProfileOptions p;
  p.amplitude_m = 0.005;  // ends at 0.055 m, inside
  p.sample_rate_hz = 1000;
  const auto ref = sysid::MakeStageProfile(stage, p);
  // Sampled at the stage's 2 kHz, not the options' 1 kHz: cycles / f * rate + 1 samples.
  CHECK(ref.t_s.size() == static_cast<Eigen::Index>(p.cycles / p.frequency_hz * 2000) + 1);
  CHECK(ref.t_s[1] == Approx(1.0 / 2000));
  p.amplitude_m = 0.01;  // ends at 0.06 m, past the end stop
  try {
    sysid::MakeStageProfile(stage, p);
    FAIL("a stroke past the end stop was accepted");
  } catch (const sysid::OptionsError& e) {
    CHECK(e.field() == "amplitude_m");
    CHECK_THAT(e.what(), Catch::Contains("stage's travel [-0.0575, 0.0575] m"));
  }
}

TEST_CASE("tracking traces, scheme entries and the summary JSON", "[control][json]") {
  sysid::SchemeTracking run;
  run.scheme = FeedforwardScheme::kAnalytic;
  run.stage_limits = "none";
  auto& r = run.result;
  r.t_s = Eigen::Vector3d(0, 0.001, 0.002);
  r.x_ref_m = Eigen::Vector3d(0, 1e-3, 2e-3);
  r.x_m = Eigen::Vector3d(0, 0.5e-3, 1.5e-3);
  r.e_m = r.x_ref_m - r.x_m;
  r.u_v = Eigen::Vector3d(0, 1, 2);
  r.u_ff_v = Eigen::Vector3d(0, 0.5, 0.5);
  r.max_error_m = 0.5e-3;
  r.rms_error_m = 0.4e-3;

  const sysid::Recording rec = sysid::TrackingRecording(r, "analytic");
  CHECK(rec.names == std::vector<std::string>{"t", "x_ref", "x", "e", "u", "u_ff"});
  CHECK(rec.column("e")[2] == Approx(0.5e-3));
  CHECK(rec.column("u_ff")[1] == 0.5);
  REQUIRE(!rec.metadata.empty());
  CHECK(rec.metadata[0] == std::pair<std::string, std::string>{"ff", "analytic"});

  const auto entry = nlohmann::ordered_json::parse(sysid::ToJson(run));
  CHECK(entry.begin().key() == "ff");
  CHECK(entry["ff"] == "analytic");
  CHECK(entry["max_error_m"] == 0.5e-3);
  CHECK(entry["stage_limits"] == "none");

  sysid::PositionReference ref;
  ref.description = "smooth 0.5 Hz";
  sysid::PiOptions pi;
  auto one = nlohmann::json::parse(sysid::TrackingSummaryToJson("virtual", ref, pi, {run}));
  CHECK(one["plant"] == "virtual");
  CHECK(one["reference"] == "smooth 0.5 Hz");
  CHECK(one["kp_v_per_m"] == pi.kp_v_per_m);
  CHECK(one["ki_v_per_m_s"] == pi.ki_v_per_m_s);
  CHECK(one["schemes"].size() == 1);
  CHECK(one["max_error_m"] == 0.5e-3);  // a single run's headline metrics
  CHECK(one["rms_error_m"] == 0.4e-3);
  auto two = nlohmann::json::parse(sysid::TrackingSummaryToJson("virtual", ref, pi, {run, run}));
  CHECK(two["schemes"].size() == 2);
  CHECK_FALSE(two.contains("max_error_m"));
}

TEST_CASE("tracking: FullReport adds every metric", "[control][report]") {
  sysid::TrackingResult r;
  r.t_s = Eigen::VectorXd::Zero(5);
  r.max_error_m = 0.00125;
  r.total_variation_v = 17.5;
  r.saturated_samples = 3;
  const std::string full = r.FullReport();
  CHECK(full.rfind(r.BriefReport(), 0) == 0);
  CHECK_THAT(full, Catch::Contains("samples 5"));
  CHECK_THAT(full, Catch::Contains("max |e| 0.00125 m"));
  CHECK_THAT(full, Catch::Contains("total variation of u 17.5 V"));
  CHECK_THAT(full, Catch::Contains("saturated samples 3"));
}

TEST_CASE("a scheme entry read through its description: the scheme by name, a bad one placed",
          "[control][json]") {
  sysid::SchemeTracking run;
  run.scheme = FeedforwardScheme::kHysteresis;
  run.stage_limits = "none";
  run.result.saturated_samples = 7;
  const std::string text = sysid::ToJson(run);
  {
    const sysid::internal::JsonDocument doc(text, "entry.json");
    sysid::SchemeTracking back;
    sysid::internal::ReadFields(doc.Root(), back);
    CHECK(back.scheme == FeedforwardScheme::kHysteresis);
    CHECK(back.result.saturated_samples == 7);
    CHECK(sysid::ToJson(back) == text);
  }
  auto j = nlohmann::ordered_json::parse(text);
  j["ff"] = "fast";
  const std::string bad = j.dump(2);  // the document keeps a reference to its text
  const sysid::internal::JsonDocument doc(bad, "bad.json");
  sysid::SchemeTracking back;
  CHECK_THROWS_WITH(sysid::internal::ReadFields(doc.Root(), back),
                    Catch::StartsWith("bad.json:2:") && Catch::Contains("ff") &&
                        Catch::Contains("\"analytic\"") && Catch::Contains("\"fast\""));
}
