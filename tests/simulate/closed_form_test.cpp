// The simulator against closed forms: tau = 0 exponentials, stopping times under viscous and
// Coulomb friction, and the classic delay equation y' = -y(t - 1) by the method of steps.
#include <catch2/catch.hpp>
#include <cmath>

#include "sysid/input.hpp"
#include "sysid/simulate.hpp"

namespace sysid {
namespace {

FrictionModel Model(double a1, double a2p, double a2n, double a3, double tau) {
  FrictionModel m;
  m.a1p = m.a1n = a1;
  m.a2p = a2p;
  m.a2n = a2n;
  m.a3 = a3;
  m.tau_s = tau;
  return m;
}

PiecewiseConstantInput Constant(double u) { return PiecewiseConstantInput({0.0}, {u}); }

TEST_CASE("tau = 0: v(t) = v_inf + (v0 - v_inf) e^{-a1 t}", "[simulate][closed-form]") {
  const FrictionModel m = Model(100, 3, 7, 6, 0);
  const double u = 1.6, v0 = 0.2;
  const double v_inf = (m.a3 * u - m.a2p) / m.a1p;
  SimulationOptions o;
  o.t_end_s = 0.1;
  o.dt_out_s = 1e-3;
  o.v0_mps = v0;
  const SimulationResult r = Simulate(m, Constant(u), o);
  REQUIRE(r.summary.IsSolutionUsable());
  CHECK(r.events.empty());
  const Trajectory& tr = r.trajectory;
  for (Eigen::Index k = 0; k < tr.t_s.size(); ++k) {
    const double t = tr.t_s[k], e = std::exp(-m.a1p * t);
    // Default tolerances rtol 1e-10 / atol 1e-12 on states of size ~0.1: a few 1e-11 globally.
    CHECK(tr.v_mps[k] == Approx(v_inf + (v0 - v_inf) * e).margin(1e-10));
    CHECK(tr.x_m[k] == Approx(v_inf * t + (v0 - v_inf) * (1 - e) / m.a1p).margin(1e-10));
    CHECK(tr.a_mps2[k] == Approx(-m.a1p * (v0 - v_inf) * e).margin(1e-7));
  }
}

TEST_CASE("tau = 0: exact stopping time, then stuck", "[simulate][closed-form]") {
  const double v0 = 0.1;
  SECTION("viscous and Coulomb friction") {
    const FrictionModel m = Model(50, 3, 7, 6, 0);
    const double v_inf = -m.a2p / m.a1p;
    const double t_stop = std::log((v0 - v_inf) / -v_inf) / m.a1p;
    const double x_stop = v_inf * t_stop + (v0 - v_inf) * (1 - std::exp(-m.a1p * t_stop)) / m.a1p;
    SimulationOptions o;
    o.t_end_s = 0.2;
    o.v0_mps = v0;
    const SimulationResult r = Simulate(m, Constant(0.0), o);
    REQUIRE(r.summary.IsSolutionUsable());
    REQUIRE(r.events.size() == 1);
    CHECK(r.events[0].kind == EventKind::kStick);
    // Root location: CVODE's interpolant is good to ~1e-11 m/s, |v'| = a2p at the stop.
    CHECK(r.events[0].t_s == Approx(t_stop).margin(1e-10));
    const Trajectory& tr = r.trajectory;
    for (Eigen::Index k = 0; k < tr.t_s.size(); ++k)
      if (tr.t_s[k] > t_stop) {
        CHECK(tr.v_mps[k] == 0.0);  // stuck means exactly zero, no creep
        CHECK(tr.a_mps2[k] == 0.0);
        CHECK(tr.x_m[k] == Approx(x_stop).margin(1e-11));
      }
  }
  SECTION("Coulomb friction alone (a1 -> 0): t = v0 / a2p, x = v0^2 / (2 a2p)") {
    const FrictionModel m = Model(1e-9, 2, 7, 6, 0);
    SimulationOptions o;
    o.t_end_s = 0.1;
    o.v0_mps = v0;
    const SimulationResult r = Simulate(m, Constant(0.0), o);
    REQUIRE(r.summary.IsSolutionUsable());
    REQUIRE(r.events.size() == 1);
    // a1 = 1e-9 shifts the stop by ~a1 t^2 / 2 ~ 1e-12 s.
    CHECK(r.events[0].t_s == Approx(v0 / m.a2p).margin(1e-10));
    CHECK(r.trajectory.x_m[r.trajectory.x_m.size() - 1] ==
          Approx(v0 * v0 / (2 * m.a2p)).margin(1e-11));
  }
}

// y(t) of y' = -y(t - 1), y = 1 for t <= 0, by the method of steps (s = t - floor(t)).
double ClassicDde(double t) {
  if (t <= 1) return 1 - t;
  if (t <= 2) {
    const double s = t - 1;
    return -s + s * s / 2;
  }
  if (t <= 3) {
    const double s = t - 2;
    return -0.5 + s * s / 2 - s * s * s / 6;
  }
  const double s = t - 3;
  return -1.0 / 6 + s / 2 - s * s * s / 6 + s * s * s * s / 24;
}

TEST_CASE("classic delay equation y' = -y(t - 1) with history y = 1", "[simulate][closed-form]") {
  // v' = -a1 v(t - tau) with a1 = 1, tau = 1 and no Coulomb friction: v crosses 0 and reverses.
  const FrictionModel m = Model(1, 0, 0, 1, 1);
  SimulationOptions o;
  o.t_end_s = 4;
  o.dt_out_s = 0.01;
  o.v0_mps = 1;
  o.history_v_mps = 1;
  const SimulationResult r = Simulate(m, Constant(0.0), o);
  REQUIRE(r.summary.IsSolutionUsable());
  const Trajectory& tr = r.trajectory;
  double max_err = 0;
  for (Eigen::Index k = 0; k < tr.t_s.size(); ++k)
    max_err = std::max(max_err, std::abs(tr.v_mps[k] - ClassicDde(tr.t_s[k])));
  // Default tolerances on a solution of size 1: global error ~1e-10.
  CHECK(max_err < 1e-8);
  CHECK(tr.v_mps[100] == Approx(0.0).margin(1e-9));          // y(1) = 0
  CHECK(tr.v_mps[200] == Approx(-0.5).margin(1e-9));         // y(2) = -1/2
  CHECK(tr.v_mps[300] == Approx(-1.0 / 6).margin(1e-9));     // y(3) = -1/6
  CHECK(tr.v_mps[400] == Approx(5.0 / 24).margin(1e-9));     // y(4) = 5/24
  CHECK(tr.x_m[100] == Approx(0.5).margin(1e-9));            // x(1) = 1/2
  CHECK(tr.x_m[200] == Approx(0.5 - 1.0 / 3).margin(1e-9));  // x(2) = 1/6
  // The zero crossings are reversals (no friction holds it), at t = 1 and inside (3, 4).
  int reversals = 0;
  for (const auto& e : r.events) reversals += e.kind == EventKind::kReverse;
  CHECK(reversals == 2);
}

}  // namespace
}  // namespace sysid
