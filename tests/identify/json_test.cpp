// The identification results' JSON (identify_json.cpp): ToJson -> FromJson -> the same result,
// positioned errors, and `sysid identify --json` printing exactly the library's text.
#include <catch2/catch.hpp>
#include <cmath>
#include <string>

#include "support/test_support.hpp"
#include "sysid/error.hpp"
#include "sysid/identify.hpp"
#include "sysid/io.hpp"

using sysid::test::RunCli;
using sysid::test::SourcePath;

namespace {

void CheckSameFit(const sysid::LinearFit& a, const sysid::LinearFit& b) {
  CHECK(a.names == b.names);
  CHECK(a.theta == b.theta);
  CHECK(a.rows == b.rows);
  CHECK(a.rank == b.rank);
  CHECK(a.dof == b.dof);
  CHECK(a.condition_number == b.condition_number);
  CHECK(a.rms_residual == b.rms_residual);
  CHECK(a.relative_error == b.relative_error);
  CHECK(a.r_diagonal == b.r_diagonal);
}

std::string Replace(std::string text, const std::string& from, const std::string& to) {
  const size_t p = text.find(from);
  REQUIRE(p != std::string::npos);
  return text.replace(p, from.size(), to);
}

}  // namespace

TEST_CASE("pulse identification JSON round-trips and is what identify --json prints",
          "[identify][json]") {
  const std::string recording = SourcePath("datasets/virtual/pulses.csv");
  const auto r = sysid::IdentifyFromPulses({sysid::ReadRecording(recording)});
  REQUIRE(r.pulses.size() == 10);
  const std::string text = sysid::ToJson(r);
  const auto back = sysid::PulseIdentificationResultFromJson(text, "r.json");
  CHECK(sysid::ModelToJson(back.model) == sysid::ModelToJson(r.model));
  CheckSameFit(back.fit, r.fit);
  CHECK(back.fit.std_error == r.fit.std_error);
  CHECK(back.fit.covariance == r.fit.covariance);
  CHECK(back.fit.residuals == r.fit.residuals);
  REQUIRE(back.points.size() == r.points.size());
  CHECK(back.points.back().label == r.points.back().label);
  CHECK(back.points.back().v_mps == r.points.back().v_mps);
  REQUIRE(back.pulses.size() == r.pulses.size());
  for (size_t i = 0; i < r.pulses.size(); ++i) {
    CHECK(back.pulses[i].status == r.pulses[i].status);
    CHECK(back.pulses[i].reason == r.pulses[i].reason);
    CHECK(back.pulses[i].v_mps == r.pulses[i].v_mps);
    CHECK(back.pulses[i].pulse.t_start_s == r.pulses[i].pulse.t_start_s);
  }
  CHECK(sysid::ToJson(back) == text);
  // The text is a model file too, and the CLI prints exactly this text.
  CHECK(sysid::ModelToJson(sysid::ParseModel(text, "r.json")) == sysid::ModelToJson(r.model));
  const auto cli = RunCli({"identify", "--json", recording});
  REQUIRE(cli.exit_code == 0);
  CHECK(cli.out == text);
}

TEST_CASE("pulse-table JSON writes NaN standard errors as null and reads them back",
          "[identify][json]") {
  // Four equations for four parameters: no degrees of freedom, so no standard errors.
  const std::vector<sysid::PulsePoint> points = {
      {1.3, 0.04465, "a"}, {2.0, 0.08519, "b"}, {-1.5, -0.05, "c"}, {-2.4, -0.09, "d"}};
  const auto r = sysid::FitPulseTable(points);
  REQUIRE(r.fit.dof == 0);
  REQUIRE(std::isnan(r.fit.std_error[0]));
  const std::string text = sysid::ToJson(r);
  CHECK_THAT(text, Catch::Contains("\"std_error\": null"));
  const auto back = sysid::PulseIdentificationResultFromJson(text, "t.json");
  CHECK(std::isnan(back.fit.std_error[0]));
  CHECK(back.pulses.empty());
  CHECK(sysid::ToJson(back, -1) == sysid::ToJson(r, -1));
  const auto cli =
      RunCli({"identify", "--json", "--table", SourcePath("datasets/paper/pulse_table.csv")});
  REQUIRE(cli.exit_code == 0);
  CHECK(cli.out == sysid::ToJson(sysid::FitPulseTable(
                       sysid::ReadPulseTable(SourcePath("datasets/paper/pulse_table.csv")))));
}

TEST_CASE("trajectory identification JSON round-trips and is what identify --json prints",
          "[identify][json]") {
  const std::string recording = SourcePath("datasets/virtual/training.csv");
  sysid::TrajectoryOptions o;
  o.tune_delay = true;
  const auto r = sysid::IdentifyFromTrajectory({sysid::ReadRecording(recording)}, o);
  REQUIRE_FALSE(r.tau_curve.empty());
  const std::string text = sysid::ToJson(r);
  const auto back = sysid::TrajectoryIdentificationResultFromJson(text, "r.json");
  CHECK(sysid::ModelToJson(back.model) == sysid::ModelToJson(r.model));
  CHECK(back.names == r.names);
  CHECK(back.estimate == r.estimate);
  CHECK(back.std_error == r.std_error);
  CHECK(back.covariance == r.covariance);
  CheckSameFit(back.fit, r.fit);
  CHECK(back.samples_used == r.samples_used);
  CHECK(back.tau_curve == r.tau_curve);
  CHECK(back.derivative == r.derivative);
  CHECK(sysid::ToJson(back) == text);
  const auto cli =
      RunCli({"identify", "--json", "--method", "trajectory", "--tune-delay", recording});
  REQUIRE(cli.exit_code == 0);
  CHECK(cli.out == text);
}

TEST_CASE("identification JSON errors name the file, line and column", "[identify][json]") {
  const auto r =
      sysid::FitPulseTable(sysid::ReadPulseTable(SourcePath("datasets/paper/pulse_table.csv")));
  const std::string text = sysid::ToJson(r);
  CHECK_THROWS_WITH(sysid::PulseIdentificationResultFromJson(
                        Replace(text, "\"method\": \"pulse\"", "\"method\": \"magic\""), "r.json"),
                    Catch::Contains("r.json:") && Catch::Contains("diagnostics.method") &&
                        Catch::Contains("expected \"pulse\""));
  CHECK_THROWS_AS(sysid::TrajectoryIdentificationResultFromJson(text, "r.json"), sysid::InputError);
  CHECK_THROWS_WITH(sysid::PulseIdentificationResultFromJson(
                        Replace(text, "\"rank\": 4", "\"rank\": \"four\""), "r.json"),
                    Catch::Contains("diagnostics.rank: expected an integer"));
}
