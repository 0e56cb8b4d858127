// The voltage-velocity loop against a synthetic loop with known branches (closed forms), and
// `sysid loop` on the bundled triangle test.
#include <catch2/catch.hpp>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "support/test_support.hpp"
#include "sysid/error.hpp"
#include "sysid/identify.hpp"

namespace {

// The branches of the synthetic loop [m/s]: forward the stage starts at 1.0 V on the way up and
// stops at 0.9 V on the way down; backward at -1.5 V and -1.3 V (asymmetric, as the paper's).
double Rising(double u) {
  return u > 0 ? std::max(0.1 * (u - 1.0), 0.0) : std::min(0.08 * (u + 1.5), 0.0);
}
double Falling(double u) {
  return u > 0 ? std::max(0.1 * (u - 0.9), 0.0) : std::min(0.08 * (u + 1.3), 0.0);
}

// A triangle 0 -> +1.5 -> 0 -> -2.0 -> 0 V in 1 mV steps at 1 kHz, with v on the branch of the
// direction |u| moves in (t, u, v: the velocity column, no position).
sysid::Recording SyntheticLoop() {
  std::vector<double> u;
  for (int i = 0; i <= 1500; ++i) u.push_back(1e-3 * i);
  for (int i = 1499; i >= 0; --i) u.push_back(1e-3 * i);
  for (int i = 1; i <= 2000; ++i) u.push_back(-1e-3 * i);
  for (int i = 1999; i >= 0; --i) u.push_back(-1e-3 * i);
  sysid::Recording rec;
  rec.source = "synthetic";
  rec.names = {"t", "u", "v"};
  rec.data.resize(static_cast<Eigen::Index>(u.size()), 3);
  for (std::size_t k = 0; k < u.size(); ++k) {
    const bool rising = k == 0 || std::abs(u[k]) >= std::abs(u[k - 1]);
    rec.data(static_cast<Eigen::Index>(k), 0) = 1e-3 * static_cast<double>(k);
    rec.data(static_cast<Eigen::Index>(k), 1) = u[k];
    rec.data(static_cast<Eigen::Index>(k), 2) = rising ? Rising(u[k]) : Falling(u[k]);
  }
  return rec;
}

}  // namespace

TEST_CASE("voltage loop: the branches, starts and stops of a known loop", "[identify][loop]") {
  sysid::VoltageLoopOptions o;
  o.levels_v = {1.2, 1.4, -1.7, -1.9};
  const sysid::VoltageLoop loop = sysid::AnalyzeVoltageLoop(SyntheticLoop(), o);
  REQUIRE(loop.levels.size() == 4);
  for (const auto& l : loop.levels) {
    INFO("level " << l.level_v);
    CHECK(l.rising_crossings == 1);
    CHECK(l.falling_crossings == 1);
    // Each branch is linear over the +-10-sample window, and every level is a sample: the
    // window mean is the branch's value at the level.
    CHECK(l.v_rising_mps == Approx(Rising(l.level_v)).margin(1e-12));
    CHECK(l.v_falling_mps == Approx(Falling(l.level_v)).margin(1e-12));
    CHECK(l.WidthMps() > 0);  // faster on the way down: the loop of a lagging stage
  }
  CHECK(loop.levels[0].WidthMps() == Approx(0.01).margin(1e-12));   // 0.1 m/(s V) x 0.1 V
  CHECK(loop.levels[2].WidthMps() == Approx(0.016).margin(1e-12));  // 0.08 x 0.2 V
  // |v| passes 1 mm/s at 1.01 V going up, 0.91 V going down; backward at -1.5125 / -1.3125 V.
  CHECK(loop.start_forward_v == Approx(1.01).margin(1.5e-3));
  CHECK(loop.stop_forward_v == Approx(0.91).margin(1.5e-3));
  CHECK(loop.start_backward_v == Approx(-1.5125).margin(1.5e-3));
  CHECK(loop.stop_backward_v == Approx(-1.3125).margin(1.5e-3));
  CHECK(loop.peak_forward_v == 1.5);
  CHECK(loop.peak_backward_v == -2.0);
}

TEST_CASE("voltage loop: the enclosed areas of a known loop, per period", "[identify][loop]") {
  // Closed forms of the synthetic loop's areas above |v| = 1 mm/s (the excluded slivers at the
  // start and stop cancel: the two branches are parallel). Forward: the falling branch
  // 0.1 (u - 0.9) from 0.9 to 1.5 V minus the rising 0.1 (u - 1.0) from 1.0 to 1.5 V:
  // 0.05 (0.6^2 - 0.5^2) = 0.0055 V m/s. Backward: 0.04 (0.7^2 - 0.5^2) = 0.0096 V m/s.
  // The sampled loop jumps from one branch to the other at the peak, and the trapezoid across
  // that step costs half a step times the jump: 0.5 mV x 10 mm/s = 5e-6 V m/s forward,
  // 0.5 mV x 16 mm/s = 8e-6 V m/s backward.
  const sysid::VoltageLoop one = sysid::AnalyzeVoltageLoop(SyntheticLoop());
  CHECK(one.area_forward_v_mps == Approx(0.0055 - 5e-6).margin(1e-7));
  CHECK(one.area_backward_v_mps == Approx(0.0096 - 8e-6).margin(1e-7));
  // Moving forward from 0.911 V (falling) to 1.5 V; backward from -1.3125 to -2.0 V.
  CHECK(one.span_forward_v == Approx(0.589).margin(1.5e-3));
  CHECK(one.span_backward_v == Approx(0.6875).margin(1.5e-3));
  CHECK(one.MeanWidthForwardMps() == Approx(0.0055 / 0.589).epsilon(3e-3));
  CHECK(one.MeanWidthBackwardMps() == Approx(0.0096 / 0.6875).epsilon(3e-3));
  // Two periods back to back with cycles = 2: the same areas per period.
  const sysid::Recording a = SyntheticLoop();
  sysid::Recording two = a;
  two.data.resize(2 * a.data.rows(), 3);
  two.data << a.data, a.data;
  two.data.col(0).tail(a.data.rows()).array() += a.data(a.data.rows() - 1, 0) + 1e-3;
  sysid::VoltageLoopOptions o;
  o.cycles = 2;
  const sysid::VoltageLoop per = sysid::AnalyzeVoltageLoop(two, o);
  CHECK(per.area_forward_v_mps == Approx(one.area_forward_v_mps).margin(1e-9));
  CHECK(per.area_backward_v_mps == Approx(one.area_backward_v_mps).margin(1e-9));
  // A static map (one branch both ways) encloses nothing, however curved; a sweep that never
  // moves has no span and no mean width.
  sysid::Recording map = SyntheticLoop();
  for (Eigen::Index k = 0; k < map.data.rows(); ++k) {
    const double u = map.data(k, 1);
    map.data(k, 2) = u > 0 ? 0.1 * std::pow(std::max(u - 1.0, 0.0), 1.5)
                           : -0.08 * std::pow(std::max(-u - 1.5, 0.0), 0.7);
  }
  const sysid::VoltageLoop flat = sysid::AnalyzeVoltageLoop(map);
  CHECK(flat.area_forward_v_mps == Approx(0).margin(1e-12));
  CHECK(flat.area_backward_v_mps == Approx(0).margin(1e-12));
  map.data.col(2).setZero();
  const sysid::VoltageLoop still = sysid::AnalyzeVoltageLoop(map);
  CHECK(still.span_forward_v == 0);
  CHECK(std::isnan(still.MeanWidthForwardMps()));
  o.cycles = 0;
  CHECK_THROWS_WITH(sysid::AnalyzeVoltageLoop(a, o), Catch::Contains("cycles"));
}

TEST_CASE("voltage loop: default levels, and bad input", "[identify][loop]") {
  const sysid::VoltageLoop loop = sysid::AnalyzeVoltageLoop(SyntheticLoop());
  // Six per direction, from 2 % of the peak past the start voltage to 95 % of the peak.
  REQUIRE(loop.levels.size() == 12);
  CHECK(loop.levels.front().level_v == Approx(loop.start_forward_v + 0.03));
  CHECK(loop.levels[5].level_v == Approx(1.425));
  CHECK(loop.levels[6].level_v == Approx(loop.start_backward_v - 0.04));
  CHECK(loop.levels.back().level_v == Approx(-1.9));
  for (const auto& l : loop.levels) CHECK(std::abs(l.v_rising_mps) > 1e-3);  // all in motion
  // A sweep that never starts the stage: from 50 % of the peak.
  sysid::Recording still = SyntheticLoop();
  still.data.col(2).setZero();
  const auto rest = sysid::AnalyzeVoltageLoop(still);
  CHECK(std::isnan(rest.start_forward_v));
  CHECK(rest.levels.front().level_v == Approx(0.75));
  sysid::VoltageLoopOptions o;
  o.levels_v = {0.0};
  CHECK_THROWS_AS(sysid::AnalyzeVoltageLoop(SyntheticLoop(), o), sysid::OptionsError);
  o.levels_v = {};
  o.moving_speed_mps = 0;
  CHECK_THROWS_AS(sysid::AnalyzeVoltageLoop(SyntheticLoop(), o), sysid::OptionsError);
  sysid::Recording no_u = SyntheticLoop();
  no_u.names[1] = "w";
  CHECK_THROWS_WITH(sysid::AnalyzeVoltageLoop(no_u),
                    Catch::Contains("synthetic") && Catch::Contains("u [V]"));
}

TEST_CASE("sysid loop on the bundled triangle test", "[identify][loop][cli]") {
  const std::string file = sysid::test::SourcePath("datasets/virtual/loop_triangle.csv");
  const auto r = sysid::test::RunCli({"loop", file, "--levels", "1.25,-1.75", "--json"});
  REQUIRE(r.exit_code == 0);
  const auto j = nlohmann::json::parse(r.out);
  REQUIRE(j["levels"].size() == 2);
  // The twin's asymmetric loop: it starts forward near its breakaway (1.182 V, plus the ramp
  // through the driver lag) and backward near -1.692 V, and runs faster on the way down.
  CHECK(j["start_forward_v"].get<double>() == Approx(1.19).margin(0.01));
  CHECK(j["start_backward_v"].get<double>() == Approx(-1.70).margin(0.01));
  for (const auto& l : j["levels"]) CHECK(l["width_mps"].get<double>() > 0);
  // The enclosed areas: a lagging loop both ways, and the mean width is area over span.
  for (const char* d : {"forward", "backward"}) {
    const double area = j[std::string("area_") + d + "_v_mps"].get<double>();
    const double span = j[std::string("span_") + d + "_v"].get<double>();
    CHECK(area > 0);
    CHECK(j[std::string("mean_width_") + d + "_mps"].get<double>() == Approx(area / span));
  }
  // The file holds one period: --cycles 2 would halve its areas by a period that is not there
  // (the library test above divides two real periods), and a window wider than the file
  // would average the same samples at every level.
  const auto two = sysid::test::RunCli({"loop", file, "--cycles", "2", "--json"});
  CHECK(two.exit_code == 2);
  CHECK_THAT(two.err, Catch::Contains("cycles = 2, but the sweep crosses each level at most 1"));
  const auto wide = sysid::test::RunCli({"loop", file, "--half-window", "100000"});
  CHECK(wide.exit_code == 2);
  CHECK_THAT(wide.err, Catch::Contains("wider than the recording's 6000 samples"));
  CHECK_THAT(sysid::test::RunCli({"loop", file}).out, Catch::Contains("enclosed area per period"));
  CHECK(sysid::test::RunCli({"loop", file, "--cycles", "0"}).exit_code == 1);
  CHECK(sysid::test::RunCli({"loop", file, "--levels", "0"}).exit_code == 1);
  sysid::test::TempDir dir;
  sysid::test::WriteText(dir / "bad.csv", "t,u,x\n0,0,0\n0.001,zero,0\n");
  const auto bad = sysid::test::RunCli({"loop", dir / "bad.csv"});
  CHECK(bad.exit_code == 2);
  CHECK_THAT(bad.err, Catch::Contains("bad.csv:3:"));
}
