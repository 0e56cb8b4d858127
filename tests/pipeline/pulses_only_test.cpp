// sysid pipeline on a folder of pulse recordings alone: the identification part runs on each
// recording's first part, is validated on the rest, and closes the loop on the identified model;
// the steps that need a training and a test set are named with the files that enable them.
// The references are the separate commands a user runs by hand (identify on the cropped part,
// validate --t-start, margins of the tuned gains, track --plant model.json).
#include <fmt/format.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "support/test_support.hpp"
#include "sysid/control.hpp"
#include "sysid/error.hpp"
#include "sysid/identify.hpp"
#include "sysid/io.hpp"
#include "sysid/model.hpp"
#include "sysid/pipeline.hpp"

using Catch::Contains;
using sysid::test::ReadText;
using sysid::test::RunCli;
using sysid::test::SourcePath;
using sysid::test::TempDir;

TEST_CASE(
    "sysid pipeline on pulse recordings alone: identify, validate on the held-out end, "
    "tune PI and track on the model, name what is skipped",
    "[pipeline][cli]") {
  namespace fs = std::filesystem;
  TempDir dir;
  fs::create_directory(dir / "in");
  const std::string pulses = dir / "in/pulses.csv";
  fs::copy_file(SourcePath("datasets/virtual/pulses.csv"), pulses);
  const auto r = RunCli({"pipeline", dir / "in", "-o", dir / "report", "--json"});
  REQUIRE(r.exit_code == 0);
  const auto j = nlohmann::json::parse(r.out);
  CHECK_FALSE(j.contains("network"));
  CHECK_FALSE(j.contains("dominant"));
  REQUIRE(j["skipped"].size() == 3);
  CHECK_THAT(r.err, Contains("sysid pipeline: skipped: dominance analysis: needs a training set "
                             "and a test set (training*.csv and test*.csv"));
  CHECK_THAT(r.err, Contains("skipped: NN hidden-size sweep"));
  const std::string md = ReadText(dir / "report/report.md");
  CHECK_THAT(md, Contains("1 pulse recording(s) alone (no training or test set)"));
  CHECK_THAT(md, Contains("## 3-5. Dominance, networks, inverse comparison: skipped"));
  CHECK_THAT(md, Contains("- inverse-model comparison (analytic vs NN): needs a training set"));
  CHECK_FALSE(fs::exists(dir / "report/nn.json"));

  // The model is the pulse method's and the delay's on the first 70 % of the recording.
  const sysid::Recording rec = sysid::ReadRecording(pulses);
  const auto t = rec.column("t");
  const double first = t[0], last = t[t.size() - 1], cut = first + 0.7 * (last - first);
  const sysid::FrictionModel model = sysid::ReadModel(dir / "report/model.json");
  const sysid::PulseIdentificationResult by_hand =
      sysid::IdentifyFromPulses({sysid::CropRecording(rec, first, cut)});
  CHECK(model.a1p == Approx(by_hand.model.a1p).epsilon(1e-12));
  CHECK(model.a2n == Approx(by_hand.model.a2n).epsilon(1e-12));
  CHECK(model.tau_s > 0);
  // Only pulses before the cut were used (the recording has 10, 7 start before it).
  const std::string table = ReadText(dir / "report/pulses.csv");
  CHECK(std::count(table.begin(), table.end(), '\n') == 1 + 7);

  // The validation is `sysid validate --t-start CUT` of the same recording.
  const auto v = RunCli({"validate", "--model", dir / "report/model.json", "--t-start",
                         fmt::format("{:.17g}", cut), pulses, "--json"});
  REQUIRE(v.exit_code == 0);
  const auto by_validate = nlohmann::json::parse(v.out)["recordings"][0]["outputs"];
  const auto in_report =
      nlohmann::json::parse(ReadText(dir / "report/validation.json"))["recordings"][0]["outputs"];
  REQUIRE(in_report.size() == 2);
  for (int i = 0; i < 2; ++i)
    CHECK(in_report[i]["fit_percent"].get<double>() ==
          Approx(by_validate[i]["fit_percent"].get<double>()).epsilon(1e-12));
  CHECK_THAT(md, Contains("| pulses (held-out end) | v |"));

  // The tuned gains meet the default targets on the model (margins analysis of the gains).
  REQUIRE(j.contains("tuned_pi"));
  sysid::PiOptions pi;
  pi.kp_v_per_m = j["tuned_pi"]["kp_v_per_m"];
  pi.ki_v_per_m_s = j["tuned_pi"]["ki_v_per_m_s"];
  pi.sample_time_s = j["tuned_pi"]["sample_time_s"];
  CHECK(pi.sample_time_s == Approx(1e-3).epsilon(1e-9));  // the recording's 1 kHz
  const sysid::PiMarginsReport margins = sysid::AnalyzePiMargins(model, pi);
  for (const auto& [name, a1, m] : margins.directions) {
    INFO(name);
    CHECK(m.phase_margin_deg >= 45 - 0.1);
    CHECK(20 * std::log10(m.gain_margin) >= 6 - 0.01);
  }

  // Tracking on the model is `sysid track --plant model.json` with those gains, and the
  // analytic feedforward (the plant's own inverse) beats PI alone.
  REQUIRE(j["model_tracking"].size() == 4);  // 0.5 and 1 Hz x none, analytic
  const auto track = RunCli({"track", "--plant", dir / "report/model.json", "--loop-rate", "1000",
                             "--kp", fmt::format("{:.17g}", pi.kp_v_per_m), "--ki",
                             fmt::format("{:.17g}", pi.ki_v_per_m_s), "--ff", "none,analytic",
                             "--freq", "0.5", "--amplitude", "0.01", "--json"});
  REQUIRE(track.exit_code == 0);
  const auto schemes = nlohmann::json::parse(track.out)["schemes"];
  REQUIRE(schemes.size() == 2);
  for (int i = 0; i < 2; ++i) {
    CHECK(j["model_tracking"][i]["frequency_hz"] == 0.5);
    CHECK(j["model_tracking"][i]["ff"] == schemes[i]["ff"]);
    CHECK(j["model_tracking"][i]["max_error_m"].get<double>() ==
          Approx(schemes[i]["max_error_m"].get<double>()).epsilon(1e-9));
  }
  CHECK(j["model_tracking"][1]["max_error_m"].get<double>() <
        0.1 * j["model_tracking"][0]["max_error_m"].get<double>());
}

TEST_CASE(
    "pipeline inputs: pulses alone are a data set, one tracking set without the other "
    "is not",
    "[pipeline]") {
  namespace fs = std::filesystem;
  TempDir dir;
  fs::copy_file(SourcePath("datasets/virtual/pulses.csv"), dir / "pulses.csv");
  const auto in = sysid::PipelineInputs::FromDirectory(dir.path().string());
  CHECK(in.PulsesOnly());
  CHECK_FALSE(in.IsStack());
  fs::copy_file(SourcePath("datasets/virtual/training.csv"), dir / "training.csv");
  CHECK_THROWS_WITH(sysid::PipelineInputs::FromDirectory(dir.path().string()),
                    Contains(": missing a test set (test*.csv|mat|h5)"));
  fs::remove(dir / "training.csv");
  fs::copy_file(SourcePath("datasets/virtual/test.csv"), dir / "test.csv");
  CHECK_THROWS_WITH(sysid::PipelineInputs::FromDirectory(dir.path().string()),
                    Contains(": missing a training set (training*.csv|mat|h5)"));
  CHECK_FALSE(sysid::PipelineInputs::FromDirectory(SourcePath("datasets/virtual")).PulsesOnly());
  // The fraction is checked like every option.
  sysid::PipelineOptions o;
  o.pulse_fit_fraction = 0;
  CHECK_THROWS_AS(o.Validate(), sysid::OptionsError);
  o.pulse_fit_fraction = 1.5;
  CHECK_THROWS_AS(o.Validate(), sysid::OptionsError);
}

TEST_CASE("a pulse-only run's summary JSON round-trips without the network's keys",
          "[pipeline][json]") {
  sysid::PipelineResult r;
  r.model = sysid::FrictionModel::Paper();
  r.skipped = {"dominance analysis: needs a training set", "NN sweep: needs a test set"};
  r.tuning.emplace();
  r.tuning->pi.kp_v_per_m = 1500;
  r.tuning->pi.ki_v_per_m_s = 25000;
  r.tuning->pi.sample_time_s = 1e-3;
  sysid::TrackingRow row;
  row.frequency_hz = 0.5;
  row.scheme = "analytic";
  row.result.max_error_m = 1e-6;
  row.result.rms_error_m = 3e-7;
  r.model_tracking = {row};
  r.step_seconds = {{"identify", 0.5}};
  const std::string text = sysid::ToJson(r);
  const auto j = nlohmann::json::parse(text);
  CHECK_FALSE(j.contains("network"));
  CHECK(j["skipped"].size() == 2);
  const sysid::PipelineResult back = sysid::PipelineResultFromJson(text, "p.json");
  CHECK(back.skipped == r.skipped);
  REQUIRE(back.tuning);
  CHECK(back.tuning->pi.kp_v_per_m == 1500);
  REQUIRE(back.model_tracking.size() == 1);
  CHECK(back.model_tracking[0].result.max_error_m == 1e-6);
  CHECK(sysid::ToJson(back) == text);
  // A network key beside "skipped" contradicts it.
  auto bad = nlohmann::ordered_json::parse(text);
  bad["hidden"] = 4;
  CHECK_THROWS_WITH(sysid::PipelineResultFromJson(bad.dump(1), "p.json"),
                    Contains("hidden: expected no network key"));
}
