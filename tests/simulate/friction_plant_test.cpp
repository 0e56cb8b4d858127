// The stepped plant (FrictionModelPlant) against the whole-run simulator on the same voltages
// and against the exact zero-order-hold step of the frictionless, delay-free model.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <vector>

#include "sysid/error.hpp"
#include "sysid/input.hpp"
#include "sysid/simulate.hpp"

namespace sysid {
namespace {

// A loop that keeps the plant busy (reversals, stops, releases): a proportional law on a
// sine of 1 mm, u decided from the last sample as a controller does.
std::vector<double> DriveInLoop(FrictionModelPlant& plant, double ts, int samples,
                                std::vector<double>* x_out) {
  std::vector<double> u;
  double x = plant.position_m();
  for (int k = 0; k < samples; ++k) {
    x_out->push_back(x);
    const double t = k * ts;
    const double e = 1e-3 * std::sin(2 * M_PI * 2 * t) - x;
    u.push_back(std::clamp(3000 * e, -10.0, 10.0));
    x = plant.Step(u.back());
  }
  x_out->push_back(x);
  return u;
}

TEST_CASE("stepped plant equals Simulate on the zero-order hold of its voltages",
          "[simulate][plant]") {
  const FrictionModel model = FrictionModel::Paper();  // tau = 3.5 ms, Coulomb both ways
  for (const double ts : {1e-3, 1e-4}) {
    const int n = static_cast<int>(std::lround(0.6 / ts));
    FrictionModelPlant plant(model, ts);
    std::vector<double> x;
    const std::vector<double> u = DriveInLoop(plant, ts, n, &x);
    CHECK(plant.events() > 4);  // it did stick and slip
    std::vector<double> t(u.size());
    for (std::size_t k = 0; k < t.size(); ++k) t[k] = static_cast<double>(k) * ts;
    SimulationOptions o;
    o.t_end_s = static_cast<double>(n) * ts;
    o.dt_out_s = ts;
    const SimulationResult r = Simulate(model, PiecewiseConstantInput(t, u), o);
    REQUIRE(r.summary.IsSolutionUsable());
    REQUIRE(r.trajectory.x_m.size() == static_cast<Eigen::Index>(x.size()));
    double worst = 0;
    for (std::size_t k = 0; k < x.size(); ++k)
      worst = std::max(worst, std::abs(x[k] - r.trajectory.x_m[static_cast<Eigen::Index>(k)]));
    INFO("Ts = " << ts << " s, max |x_step - x_simulate| = " << worst << " m");
    CHECK(worst < 1e-9);  // both at rtol 1e-10 on mm positions
    CHECK(std::abs(plant.time_s() - o.t_end_s) < 1e-12);
  }
}

TEST_CASE("stepped plant: a release at a sample edge happens at that edge", "[simulate][plant]") {
  // At rest, pulses above and below the breakaway levels (a3 u vs a2p = 3.1, a2n = 6.8 m/s^2):
  // the stick/slip decision at t_k must see u_k, not the voltage before it.
  const FrictionModel model = FrictionModel::Paper();
  const double ts = 1e-3;
  std::vector<double> t, u;
  // Each 60 samples: 0.8 V (slides), 0 V for 4 samples (stops within tau = 3.5 samples, so
  // v(t - tau) is still moving when 1.5 V releases it), 0 V, then -1.5 V and -0.9 V from rest.
  for (int k = 0; k < 300; ++k) {
    t.push_back(k * ts);
    const int j = k % 60;
    u.push_back(j < 20 ? 0.8 : j < 24 ? 0.0 : j < 30 ? 1.5 : j < 40 ? 0.0 : j < 50 ? -1.5 : -0.9);
  }
  FrictionModelPlant plant(model, ts);
  std::vector<double> x = {plant.position_m()};
  for (double uk : u) x.push_back(plant.Step(uk));
  SimulationOptions o;
  o.t_end_s = 300 * ts;
  o.dt_out_s = ts;
  const SimulationResult r = Simulate(model, PiecewiseConstantInput(t, u), o);
  REQUIRE(r.summary.IsSolutionUsable());
  REQUIRE(r.events.size() >= 4);
  double worst = 0;
  for (std::size_t k = 0; k < x.size(); ++k)
    worst = std::max(worst, std::abs(x[k] - r.trajectory.x_m[static_cast<Eigen::Index>(k)]));
  INFO("max |x_step - x_simulate| = " << worst << " m");
  CHECK(worst < 1e-10);
}

TEST_CASE("stepped plant without friction or delay: the exact ZOH step", "[simulate][plant]") {
  FrictionModel m;
  m.a1p = m.a1n = 80;
  m.a2p = m.a2n = 0;
  m.a3 = 6;
  m.tau_s = 0;
  const double ts = 2e-3;
  FrictionModelPlant plant(m, ts);
  double x = 0, v = 0, worst = 0;
  for (int k = 0; k < 400; ++k) {
    const double u = 2 * std::sin(0.05 * k) + (k % 7 == 0 ? -1.5 : 0.0);
    const double v_inf = m.a3 * u / m.a1p, e = std::exp(-m.a1p * ts);
    x += v_inf * ts + (v - v_inf) * (1 - e) / m.a1p;
    v = v_inf + (v - v_inf) * e;
    worst = std::max(worst, std::abs(plant.Step(u) - x));
  }
  INFO("max |x - closed form| = " << worst << " m");
  CHECK(worst < 1e-10);
}

TEST_CASE("stepped plant refuses what it cannot run", "[simulate][plant]") {
  CHECK_THROWS_AS(FrictionModelPlant(FrictionModel::Paper(), 0.0), OptionsError);
  FrictionModelPlant plant(FrictionModel::Paper(), 1e-3);
  CHECK_THROWS_AS(plant.Step(NAN), OptionsError);
}

}  // namespace
}  // namespace sysid
