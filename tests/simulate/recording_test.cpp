// simulation_recording.cpp: a run as the files `sysid simulate` writes.
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "sysid/io.hpp"
#include "sysid/simulate.hpp"

TEST_CASE("a run's trajectory as a recording, its events as CSV", "[simulate]") {
  sysid::SimulationResult r;
  r.trajectory.t_s = Eigen::Vector2d(0, 0.1);
  r.trajectory.u_v = Eigen::Vector2d(1, 1);
  r.trajectory.x_m = Eigen::Vector2d(0, 2e-4);
  r.trajectory.v_mps = Eigen::Vector2d(0, 4e-3);
  r.trajectory.a_mps2 = Eigen::Vector2d(0.5, 0);
  r.events = {{0.025, sysid::EventKind::kSlipForward}, {0.1, sysid::EventKind::kStick}};
  sysid::SimulationOptions o;
  o.method = sysid::IntegratorMethod::kBdf;
  o.rtol = 1e-7;
  o.atol = 1e-10;
  const sysid::FrictionModel m = sysid::FrictionModel::Paper();

  const sysid::Recording rec = sysid::TrajectoryRecording(r, m, "pulses 1 V", o);
  CHECK(rec.names == std::vector<std::string>{"t", "u", "x", "v", "a"});
  CHECK(rec.column("x")[1] == 2e-4);
  CHECK(rec.column("a")[0] == 0.5);
  CHECK(rec.meta("input") == "pulses 1 V");
  CHECK(rec.meta("simulator") == "CVODE bdf rtol 1e-07 atol 1e-10");
  const auto model = nlohmann::json::parse(rec.meta("model"));
  CHECK(model["tau"] == m.tau_s);
  CHECK(model["a3"] == m.a3);

  CHECK(sysid::EventsToCsv(r.events) == "t,kind\n0.025000000000000001,slip+\n0.10000000000000001,stick\n");
  CHECK(sysid::EventsToCsv({}) == "t,kind\n");
}

TEST_CASE("simulation summary: FullReport adds the stop's details", "[simulate][report]") {
  sysid::SimulationSummary s;
  CHECK_THAT(s.FullReport(), Catch::Contains("usable: yes"));
  s.termination = sysid::Termination::kBudgetExhausted;
  s.cvode_flag = "CV_TOO_MUCH_WORK";
  s.message = "max_steps reached";
  s.failure_time_s = 0.75;
  const std::string full = s.FullReport();
  CHECK(full.rfind(s.BriefReport(), 0) == 0);
  CHECK_THAT(full, Catch::Contains("usable: no"));
  CHECK_THAT(full, Catch::Contains("stopped at t = 0.75 s: max_steps reached (CV_TOO_MUCH_WORK)"));
}
