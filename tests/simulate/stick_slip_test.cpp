// Stick–slip semantics: stop then stick, stop then reverse, release exactly at an input edge,
// thresholds that differ by direction; and the event log.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

#include "sysid/input.hpp"
#include "sysid/simulate.hpp"

namespace sysid {
namespace {

FrictionModel Model(double a1, double a2p, double a2n, double tau) {
  FrictionModel m;
  m.a1p = m.a1n = a1;
  m.a2p = a2p;
  m.a2n = a2n;
  m.a3 = 6;
  m.tau_s = tau;
  return m;
}

TEST_CASE("a stop followed by sticking: v exactly 0 and x constant afterwards", "[simulate]") {
  // The paper's model: a +1.6 V pulse, then 0 V; Coulomb friction holds the stage.
  const FrictionModel m = FrictionModel::Paper();
  const PiecewiseConstantInput u({0.0, 0.4}, {1.6, 0.0});
  SimulationOptions o;
  o.t_end_s = 1.0;
  o.dt_out_s = 1e-4;
  const SimulationResult r = Simulate(m, u, o);
  REQUIRE(r.summary.IsSolutionUsable());
  REQUIRE(r.events.size() == 2);
  CHECK(r.events[0].kind == EventKind::kSlipForward);
  CHECK(r.events[0].t_s == 0.0);
  CHECK(r.events[1].kind == EventKind::kStick);
  const double t_stick = r.events[1].t_s;
  CHECK(t_stick > 0.4);
  CHECK(t_stick < 0.42);
  const Trajectory& tr = r.trajectory;
  Eigen::Index first = -1;
  for (Eigen::Index k = 0; k < tr.t_s.size(); ++k) {
    if (tr.t_s[k] <= t_stick) {
      CHECK(tr.v_mps[k] >= 0);  // never overshoots into reverse
      continue;
    }
    if (first < 0) first = k;
    CHECK(tr.v_mps[k] == 0.0);
    CHECK(tr.a_mps2[k] == 0.0);
    CHECK(tr.x_m[k] == tr.x_m[first]);  // bit-identical: no creep, no chatter
  }
  REQUIRE(first > 0);
}

TEST_CASE("a stop followed by reversal (tau = 0, closed form)", "[simulate]") {
  // u = -2 V drives backwards harder than a2n holds: the stage slides forward to rest and
  // immediately reverses. Phase 1: v_inf1 = (a3 u - a2p)/a1; phase 2: v_inf2 = (a3 u + a2n)/a1.
  const FrictionModel m = Model(100, 1, 1, 0);
  const double u = -2, v0 = 0.1;
  const double vi1 = (m.a3 * u - m.a2p) / m.a1p, vi2 = (m.a3 * u + m.a2n) / m.a1n;
  const double t_c = std::log((v0 - vi1) / -vi1) / m.a1p;
  SimulationOptions o;
  o.t_end_s = 0.1;
  o.dt_out_s = 1e-3;
  o.v0_mps = v0;
  const SimulationResult r = Simulate(m, PiecewiseConstantInput({0.0}, {u}), o);
  REQUIRE(r.summary.IsSolutionUsable());
  REQUIRE(r.events.size() == 2);  // reverse, and the a1 branch follows v (tau = 0)
  CHECK(r.events[0].kind == EventKind::kReverse);
  CHECK(r.events[0].t_s == Approx(t_c).margin(1e-11));  // root location, |v'| ~ 13 m/s^2
  CHECK(r.events[1].kind == EventKind::kViscousSwitch);
  const Trajectory& tr = r.trajectory;
  for (Eigen::Index k = 0; k < tr.t_s.size(); ++k) {
    const double t = tr.t_s[k];
    const double expected = t < t_c ? vi1 + (v0 - vi1) * std::exp(-m.a1p * t)
                                    : vi2 * (1 - std::exp(-m.a1n * (t - t_c)));
    CHECK(tr.v_mps[k] == Approx(expected).margin(1e-10));  // default tolerances
  }
}

TEST_CASE("a release exactly at an input edge", "[simulate]") {
  const FrictionModel m = FrictionModel::Paper();
  const PiecewiseConstantInput u({0.0, 0.5}, {0.5, 1.0});  // 3 N/kg < a2p, then 6 > a2p
  SimulationOptions o;
  o.t_end_s = 0.51;
  o.dt_out_s = 1e-3;
  const SimulationResult r = Simulate(m, u, o);
  REQUIRE(r.summary.IsSolutionUsable());
  REQUIRE(!r.events.empty());
  CHECK(r.events[0].kind == EventKind::kSlipForward);
  CHECK(r.events[0].t_s == 0.5);  // exactly the edge, not a root near it
  const Trajectory& tr = r.trajectory;
  for (Eigen::Index k = 0; k < tr.t_s.size(); ++k) {
    const double t = tr.t_s[k];
    if (t < 0.5) {
      CHECK(tr.v_mps[k] == 0.0);
      CHECK(tr.x_m[k] == 0.0);
    } else if (t <= 0.5 + m.tau_s) {
      // v(t - tau) = 0 for one delay after the release: v' = a3 u - a2p exactly.
      CHECK(tr.v_mps[k] == Approx((m.a3 - m.a2p) * (t - 0.5)).margin(1e-13));
      CHECK(tr.a_mps2[k] == Approx(m.a3 - m.a2p).margin(1e-12));
    }
  }
}

TEST_CASE("breakaway thresholds differ by direction", "[simulate]") {
  const FrictionModel m = FrictionModel::Paper();  // a2p = 3.1023 < a3 |u| = 4.8 < a2n = 6.8216
  SimulationOptions o;
  o.t_end_s = 0.2;
  SECTION("forward: 0.8 V breaks away") {
    const SimulationResult r = Simulate(m, PiecewiseConstantInput({0.0}, {0.8}), o);
    REQUIRE(r.summary.IsSolutionUsable());
    REQUIRE(!r.events.empty());
    CHECK(r.events[0].kind == EventKind::kSlipForward);
    const double v_end = r.trajectory.v_mps[r.trajectory.v_mps.size() - 1];
    CHECK(v_end == Approx(m.SteadyVelocity(0.8)).epsilon(1e-8));  // decayed by 0.2 s
  }
  SECTION("backward: -0.8 V stays stuck") {
    const SimulationResult r = Simulate(m, PiecewiseConstantInput({0.0}, {-0.8}), o);
    REQUIRE(r.summary.IsSolutionUsable());
    CHECK(r.events.empty());
    CHECK(r.trajectory.v_mps.cwiseAbs().maxCoeff() == 0.0);
    CHECK(r.trajectory.x_m.cwiseAbs().maxCoeff() == 0.0);
  }
  SECTION("backward: -1.2 V breaks away") {
    const SimulationResult r = Simulate(m, PiecewiseConstantInput({0.0}, {-1.2}), o);
    REQUIRE(r.summary.IsSolutionUsable());
    REQUIRE(!r.events.empty());
    CHECK(r.events[0].kind == EventKind::kSlipBackward);
    const double v_end = r.trajectory.v_mps[r.trajectory.v_mps.size() - 1];
    CHECK(v_end == Approx(m.SteadyVelocity(-1.2)).epsilon(1e-8));
  }
}

TEST_CASE("a sinusoid below the breakaway force never moves the stage, one above it does",
          "[simulate]") {
  const FrictionModel m = FrictionModel::Paper();
  SimulationOptions o;
  o.t_end_s = 4;
  const SimulationResult quiet = Simulate(m, SumOfSinesInput({{0.5, 1.0, 0.0}}), o);
  REQUIRE(quiet.summary.IsSolutionUsable());
  CHECK(quiet.events.empty());  // a3 * 0.5 = 3 < a2p
  CHECK(quiet.trajectory.v_mps.cwiseAbs().maxCoeff() == 0.0);
  const SimulationResult moving = Simulate(m, SumOfSinesInput({{1.5, 1.0, 0.0}}), o);
  REQUIRE(moving.summary.IsSolutionUsable());
  // Released forward once per period, a3 * 1.5 sin = a2p at sin = a2p / 9.
  const double pi = std::acos(-1.0);
  const double t_release = std::asin(m.a2p / (m.a3 * 1.5)) / (2 * pi);
  REQUIRE(!moving.events.empty());
  CHECK(moving.events[0].kind == EventKind::kSlipForward);
  CHECK(moving.events[0].t_s == Approx(t_release).margin(1e-9));  // root location
}

TEST_CASE("pure Coulomb friction (a1p = a1n = 0) follows its piecewise-parabolic closed form",
          "[simulate]") {
  // x'' = -a2 sgn(v) + a3 u: constant accelerations between events. u = 1 V from rest gives
  // a = a3 - a2p = 5 until 0.1 s (v 0.5 m/s, x 0.025 m); at 0 V the stage decelerates at a2p
  // and sticks at 0.6 s (x 0.15 m); -2 V from 0.8 s beats a2n: a = -12 + 2 = -10 m/s^2.
  // The delay of the (absent) viscous term must change nothing.
  const double tau = GENERATE(0.0, 0.0035);
  FrictionModel m = Model(0, 1, 2, tau);
  REQUIRE_NOTHROW(m.Validate());
  CHECK(m.SteadyVelocity(1.0) == std::numeric_limits<double>::infinity());
  CHECK(m.SteadyVelocity(0.1) == 0.0);
  const PiecewiseConstantInput u({0.0, 0.1, 0.8}, {1.0, 0.0, -2.0});
  SimulationOptions o;
  o.t_end_s = 1.0;
  o.dt_out_s = 1e-3;
  const SimulationResult r = Simulate(m, u, o);
  REQUIRE(r.summary.IsSolutionUsable());
  REQUIRE(r.events.size() >= 3);
  CHECK(r.events[0].kind == EventKind::kSlipForward);
  CHECK(r.events[1].kind == EventKind::kStick);
  CHECK(r.events[1].t_s == Approx(0.6).margin(1e-9));
  const Trajectory& tr = r.trajectory;
  for (Eigen::Index k = 0; k < tr.t_s.size(); ++k) {
    const double t = tr.t_s[k];
    double x = 0, v = 0;
    if (t <= 0.1) {
      x = 2.5 * t * t, v = 5 * t;
    } else if (t <= 0.6) {
      x = 0.025 + 0.5 * (t - 0.1) - 0.5 * (t - 0.1) * (t - 0.1), v = 0.5 - (t - 0.1);
    } else if (t <= 0.8) {
      x = 0.15, v = 0;
    } else {
      x = 0.15 - 5 * (t - 0.8) * (t - 0.8), v = -10 * (t - 0.8);
    }
    CHECK(tr.x_m[k] == Approx(x).margin(1e-9));
    CHECK(tr.v_mps[k] == Approx(v).margin(1e-9));
  }
}

}  // namespace
}  // namespace sysid
