// Option and model checks, failure reporting, thread safety.
#include <catch2/catch.hpp>
#include <thread>
#include <vector>

#include "sysid/error.hpp"
#include "sysid/input.hpp"
#include "sysid/simulate.hpp"

namespace sysid {
namespace {

TEST_CASE("invalid options name the field and the rule", "[simulate][options]") {
  const FrictionModel m = FrictionModel::Paper();
  const PiecewiseConstantInput u({0.0}, {1.0});
  SimulationOptions o;
  o.t_end_s = -1;
  CHECK_THROWS_WITH(Simulate(m, u, o), Catch::Contains("SimulationOptions::t_end_s = -1") &&
                                           Catch::Contains("t_end_s > t0_s"));
  o = {};
  o.rtol = 0;
  CHECK_THROWS_AS(Simulate(m, u, o), OptionsError);
  o = {};
  o.output_times_s = {0.0, 0.5, 0.4};
  CHECK_THROWS_WITH(Simulate(m, u, o),
                    Catch::Contains("output_times_s[2]") && Catch::Contains("strictly ascending"));
  o = {};
  o.breakpoint_order = 0;
  CHECK_THROWS_WITH(Simulate(m, u, o), Catch::Contains("breakpoint_order"));
  o = {};
  o.method = IntegratorMethod::kBdf;
  o.max_order = 6;
  CHECK_THROWS_WITH(Simulate(m, u, o), Catch::Contains("max_order <= 5 for BDF"));
  FrictionModel bad = m;
  bad.tau_s = -1e-3;
  CHECK_THROWS_WITH(Simulate(bad, u, {}), Catch::Contains("FrictionModel::tau"));
}

TEST_CASE("running out of steps is reported, not thrown", "[simulate][options]") {
  SimulationOptions o;
  o.t_end_s = 2;
  o.max_steps = 50;
  const SimulationResult r = Simulate(FrictionModel::Paper(), MakePulseTrain({}), o);
  CHECK_FALSE(r.summary.IsSolutionUsable());
  CHECK(r.summary.termination == Termination::kBudgetExhausted);
  CHECK(r.summary.cvode_flag == "CV_TOO_MUCH_WORK");
  CHECK(r.summary.failure_time_s > 0);
  CHECK(r.summary.failure_time_s < 2);
  CHECK(r.summary.message.find("max_steps = 50") != std::string::npos);
  // The samples reached are kept, and only those.
  CHECK(r.trajectory.t_s.size() > 0);
  CHECK(r.trajectory.t_s[r.trajectory.t_s.size() - 1] <= r.summary.failure_time_s);
}

TEST_CASE("simulations in parallel threads equal the serial ones", "[simulate][threads]") {
  std::vector<FrictionModel> models(4, FrictionModel::Paper());
  for (size_t i = 0; i < models.size(); ++i) models[i].tau_s *= 1 + 0.1 * static_cast<double>(i);
  const PiecewiseConstantInput u = MakePulseTrain({});
  SimulationOptions o;
  o.t_end_s = 2;
  std::vector<SimulationResult> serial, parallel(models.size());
  for (const auto& m : models) serial.push_back(Simulate(m, u, o));
  std::vector<std::thread> threads;
  for (size_t i = 0; i < models.size(); ++i)
    threads.emplace_back([&, i] { parallel[i] = Simulate(models[i], u, o); });
  for (auto& t : threads) t.join();
  for (size_t i = 0; i < models.size(); ++i) {
    CHECK(parallel[i].summary.steps == serial[i].summary.steps);
    CHECK(parallel[i].trajectory.v_mps == serial[i].trajectory.v_mps);  // bit-identical
  }
}

TEST_CASE("the summary counts the work", "[simulate]") {
  SimulationOptions o;
  o.t_end_s = 10;
  const SimulationResult r = Simulate(FrictionModel::Paper(), MakePulseTrain({}), o);
  REQUIRE(r.summary.IsSolutionUsable());
  CHECK(r.summary.steps > 100);
  CHECK(r.summary.rhs_evaluations >= r.summary.steps);
  CHECK(r.summary.root_evaluations > 0);
  CHECK(r.summary.events == static_cast<long>(r.events.size()));
  CHECK(r.summary.reinitialisations > 0);
  CHECK(r.trajectory.t_s.size() == 10001);
  CHECK(r.summary.BriefReport().find("converged") == 0);
}

}  // namespace
}  // namespace sysid
