// The data-collection procedures: timing, cuts, determinism, the CLI and the bundled datasets.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>

#include "support/test_support.hpp"
#include "sysid/stage.hpp"

TEST_CASE("pulse excitation timing", "[stage][procedure]") {
  sysid::PulseProcedure p;
  p.amplitudes_v = {1.5, -2.0};
  p.on_s = 0.4;
  p.rest_s = 0.3;
  p.lead_s = 0.1;
  const Eigen::VectorXd u = p.Voltage(1000);
  REQUIRE(u.size() == 1500);  // 0.1 + 2 x 0.7 s
  CHECK(u[99] == 0.0);
  CHECK(u[100] == 1.5);
  CHECK(u[499] == 1.5);
  CHECK(u[500] == 0.0);
  CHECK(u[800] == -2.0);
  CHECK(u[1199] == -2.0);
  CHECK(u[1200] == 0.0);
  p.on_s = 0;
  CHECK_THROWS_WITH(p.Voltage(1000), Catch::Contains("Violated constraint: on_s > 0"));
  // A pulse shorter than half a sample rounds to none; one sample is the shortest pulse.
  p.on_s = 0.4e-3;
  CHECK_THROWS_WITH(p.Voltage(1000), Catch::Contains("on_s >= one sample interval"));
  p.on_s = 1e-3;
  CHECK(p.Voltage(1000).cwiseAbs().maxCoeff() == 2.0);
  // A rate that leaves the whole test a single sample.
  p.on_s = 0.4;
  CHECK_THROWS_WITH(p.Voltage(1e-300), Catch::Contains("Violated constraint"));
}

TEST_CASE("the paper's waveforms integrate to their position references", "[stage][procedure]") {
  for (const auto& w : sysid::PaperTestWaveforms()) {
    // Trapezoid integral of v over one period (1e5 steps) against the closed-form x.
    const int m = 100000;
    const double h = w.period_s / m;
    double x = 0;
    for (int i = 0; i < m; ++i) x += 0.5 * h * (w.Velocity(i * h) + w.Velocity((i + 1) * h));
    CHECK(x == Approx(w.Position(w.period_s)).margin(1e-9));  // [m] O(h^2) trapezoid error
    CHECK(std::abs(w.Position(w.period_s)) < 1e-12);          // periodic: back at x = 0
    CHECK(w.PeakVelocity() < 0.23);
  }
  CHECK(sysid::TrainingGrid().size() == 11);
}

TEST_CASE("tracking sets are seeded, shuffled and cut at whole cycles", "[stage][procedure]") {
  const auto stage = sysid::StageParameters::Default();
  std::vector<sysid::VelocityWaveform> grid = {sysid::VelocityWaveform::Sine(0.004, 10.0),
                                               sysid::VelocityWaveform::Sine(0.006, 12.0),
                                               sysid::VelocityWaveform::Sine(0.003, 15.0)};
  sysid::TrackingProcedure proc;
  const auto a = sysid::RunTrackingSet(stage, grid, proc, 9, "t");
  const auto b = sysid::RunTrackingSet(stage, grid, proc, 9, "t");
  const auto c = sysid::RunTrackingSet(stage, grid, proc, 10, "t");
  CHECK(a.data == b.data);
  CHECK_FALSE(a.data.col(2) == c.data.col(2));
  long expected = 0;
  for (const auto& w : grid) expected += std::lround(w.period_s * 1000);
  CHECK(a.rows() == expected);
  CHECK(a.names == std::vector<std::string>{"t", "u", "x", "v", "a"});
  // Every segment appears once, in some order.
  const std::string seg = a.meta("segments");
  for (const auto& w : grid) CHECK(seg.find(w.name) != std::string::npos);
  // P control: u = kp (x_ref - x) holds on the kept rows of a single waveform.
  const auto one = sysid::TrackWaveform(stage, grid[0], proc, 4);
  for (Eigen::Index k = 0; k < one.rows(); k += 97)
    CHECK(one.data(k, 1) ==
          Approx(proc.kp_v_per_m * (one.data(k, 5) - one.data(k, 2))).margin(1e-12));
  // The cut is at the reference's cycle boundary, rounded to a sample: |x_ref| <=
  // A (omega dt)^2 / 2 = 0.004 (10 x 0.5e-3)^2 / 2 = 5e-8 m at the first kept row.
  CHECK(std::abs(one.data(0, 5)) < 5e-8);
}

// Regression, not a reference: the bundled datasets were made by this code, so equality shows
// that nothing changed, not that anything is right (the plant's references are in plant_test).
TEST_CASE("regression: sysid generate reproduces the bundled datasets byte for byte",
          "[stage][cli][regression]") {
  sysid::test::TempDir dir;
  const auto r = sysid::test::RunCli({"generate", "all", "--seed", "1", "-o", dir.path().string()});
  REQUIRE(r.exit_code == 0);
  const std::filesystem::path bundled = sysid::test::SourcePath("datasets/virtual");
  int compared = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir.path())) {
    const auto name = e.path().filename().string();
    INFO(name);
    REQUIRE(std::filesystem::exists(bundled / name));
    CHECK(sysid::test::ReadText(e.path().string()) ==
          sysid::test::ReadText((bundled / name).string()));
    ++compared;
  }
  CHECK(compared == 11);  // stage.json, pulses, training, test, triangle loop, six waveforms
}

TEST_CASE("generate --json lists each file with the library's shape of it", "[stage][cli]") {
  sysid::test::TempDir dir;
  const auto r = sysid::test::RunCli(
      {"generate", "pulses", "--seed", "3", "--json", "-o", dir.path().string()});
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const auto j = nlohmann::json::parse(r.out);
  REQUIRE(j["files"].size() == 1);
  const auto& f = j["files"][0];
  const sysid::Recording rec = sysid::ReadRecording(f["path"].get<std::string>());
  const auto shape = nlohmann::json::parse(sysid::RecordingShapeToJson(rec));
  for (const char* key : {"samples", "duration_s", "columns", "units"}) {
    INFO(key);
    CHECK(f[key] == shape[key]);
  }
  CHECK(f["samples"] == rec.rows());
  CHECK(f["limits"] == rec.meta("limits", "none"));
}

TEST_CASE("generate and excite report bad input with the documented exit codes", "[stage][cli]") {
  sysid::test::TempDir dir;
  sysid::test::WriteText(dir / "bad.json", "{\"rig\": {\"sample_rate\": 1000}}");
  auto r =
      sysid::test::RunCli({"generate", "pulses", "--stage", dir / "bad.json", "-o", dir / "out"});
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Catch::Contains("bad.json:1:10: unknown key 'sample_rate'"));
  CHECK_FALSE(std::filesystem::exists(dir / "out"));  // no partial output
  r = sysid::test::RunCli({"generate", "sweep"});
  CHECK(r.exit_code == 1);
  r = sysid::test::RunCli({"excite", "pulses", "--amplitudes", "1.5,-2", "-o", dir / "p.csv"});
  REQUIRE(r.exit_code == 0);
  const std::string text = sysid::test::ReadText(dir / "p.csv");
  CHECK_THAT(text, Catch::Contains("t,u\n"));
  r = sysid::test::RunCli({"excite", "pulses", "--on", "0"});
  CHECK(r.exit_code == 1);
  r = sysid::test::RunCli({"excite", "waveforms", "--cycles", "1"});
  CHECK(r.exit_code == 0);
  CHECK_THAT(r.out, Catch::Contains("t,waveform,x_ref,v_ref,a_ref"));
}
