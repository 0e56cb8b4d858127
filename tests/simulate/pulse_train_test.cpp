// The paper's pulse train against two independent references: the RK4 method-of-steps reference
// of this test suite (reference_integrator.cpp) and the h = 1e-6 s reference trajectory of the
// shared benchmark peer (tests/data/simulate/p1_reference_1ms.csv, written by fricdde.py).
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "reference_integrator.hpp"
#include "support/test_support.hpp"
#include "sysid/input.hpp"
#include "sysid/io.hpp"
#include "sysid/simulate.hpp"

namespace sysid {
namespace {

struct Errors {
  double dv = 0, dx = 0;
};

Errors Compare(const Trajectory& tr, const std::vector<double>& x, const std::vector<double>& v) {
  REQUIRE(static_cast<size_t>(tr.v_mps.size()) == v.size());
  Errors e;
  for (size_t k = 0; k < v.size(); ++k) {
    e.dv = std::max(e.dv, std::abs(tr.v_mps[static_cast<Eigen::Index>(k)] - v[k]));
    e.dx = std::max(e.dx, std::abs(tr.x_m[static_cast<Eigen::Index>(k)] - x[k]));
  }
  return e;
}

// 3 s hold three pulses (+, -, +): slips, a reversal, sticks and both a1 switches.
constexpr double kTEnd = 3.0;

const test::ReferenceTrajectory& Reference() {
  static const test::ReferenceTrajectory ref =
      test::ReferenceRk4(FrictionModel::Paper(), MakePulseTrain({}), kTEnd, 1e-6, 1000);
  return ref;
}

SimulationResult Run(double rtol, double atol, IntegratorMethod method = IntegratorMethod::kAdams,
                     double t_end = kTEnd) {
  SimulationOptions o;
  o.t_end_s = t_end;
  o.dt_out_s = 1e-3;
  o.rtol = rtol;
  o.atol = atol;
  o.method = method;
  SimulationResult r = Simulate(FrictionModel::Paper(), MakePulseTrain({}), o);
  REQUIRE(r.summary.IsSolutionUsable());
  return r;
}

TEST_CASE("pulse train matches the tiny-step RK4 reference to 1e-7 at default tolerances",
          "[simulate][reference]") {
  const auto& ref = Reference();
  const SimulationOptions defaults;
  for (auto method : {IntegratorMethod::kAdams, IntegratorMethod::kBdf}) {
    const SimulationResult r = Run(defaults.rtol, defaults.atol, method);
    const Errors e = Compare(r.trajectory, ref.x, ref.v);
    INFO(ToString(method) << ": max|dv| = " << e.dv << ", max|dx| = " << e.dx);
    // The accuracy requirement; the reference itself is good to ~1e-10 (RK4, h = 1e-6).
    CHECK(e.dv <= 1e-7);
    CHECK(e.dx <= 1e-7);
  }
}

TEST_CASE("stop and release times agree with the reference", "[simulate][reference]") {
  const auto& ref = Reference();
  const SimulationResult r = Run(1e-10, 1e-12);
  std::vector<double> sim_t;
  for (const auto& ev : r.events)
    if (ev.kind != EventKind::kViscousSwitch) sim_t.push_back(ev.t_s);
  REQUIRE(sim_t.size() == ref.event_t.size());
  for (size_t k = 0; k < sim_t.size(); ++k)
    // Bisection in the reference is exact; 1e-9 s is 1e-8 m/s of v at |v'| ~ 10 m/s^2.
    CHECK(std::abs(sim_t[k] - ref.event_t[k]) < 1e-9);
}

TEST_CASE("the error falls as the tolerance falls", "[simulate][convergence]") {
  const auto& ref = Reference();
  std::vector<double> errors;
  for (double rtol : {1e-5, 1e-7, 1e-9, 1e-11}) {
    const Errors e = Compare(Run(rtol, rtol * 1e-2).trajectory, ref.x, ref.v);
    errors.push_back(e.dv);
  }
  INFO("max|dv| at rtol 1e-5, 1e-7, 1e-9, 1e-11: " << errors[0] << ", " << errors[1] << ", "
                                                   << errors[2] << ", " << errors[3]);
  // Two decades of tolerance buy at least one decade of error (measured: ~1.5-2 decades); the
  // reference's own error is below 5e-11 (it agrees with the shared peer reference to that).
  CHECK(errors[1] < errors[0] / 10);
  CHECK(errors[2] < errors[1] / 10);
  CHECK(errors[3] < errors[2] / 10);
  CHECK(errors[3] < 1e-10);
}

TEST_CASE("steady-state plateaus equal (a3|u| - a2)/a1", "[simulate]") {
  const FrictionModel m = FrictionModel::Paper();
  const SimulationResult r = Run(1e-10, 1e-12);
  const auto& tr = r.trajectory;
  // At the end of a 0.4 s pulse the transient e^{-a1 t} has decayed far below 1e-12.
  const Eigen::Index k_pos = 399, k_neg = 1399;  // t = 0.399 s and 1.399 s
  CHECK(tr.t_s[k_pos] == Approx(0.399));
  CHECK(tr.v_mps[k_pos] == Approx((m.a3 * 1.6 - m.a2p) / m.a1p).epsilon(1e-12));
  CHECK(tr.v_mps[k_neg] == Approx(-(m.a3 * 2.3 - m.a2n) / m.a1n).epsilon(1e-12));
}

TEST_CASE("the whole 10 s pulse train matches the shared peer reference", "[simulate][reference]") {
  ReadOptions ro;
  ro.required_columns = {"t", "u", "x", "v"};
  const Recording ref = ReadRecording(test::TestData("simulate/p1_reference_1ms.csv"), ro);
  SimulationOptions o;
  o.t_end_s = 10.0;
  const auto t = ref.column("t");
  o.output_times_s.assign(t.data(), t.data() + t.size());
  const SimulationResult r = Simulate(FrictionModel::Paper(), MakePulseTrain({}), o);
  REQUIRE(r.summary.IsSolutionUsable());
  const double dv = (r.trajectory.v_mps - ref.column("v")).cwiseAbs().maxCoeff();
  const double dx = (r.trajectory.x_m - ref.column("x")).cwiseAbs().maxCoeff();
  INFO("max|dv| = " << dv << ", max|dx| = " << dx << "; " << r.summary.BriefReport());
  CHECK(dv <= 1e-7);  // the requirement
  CHECK(dx <= 1e-7);
  CHECK((r.trajectory.u_v - ref.column("u")).cwiseAbs().maxCoeff() == 0.0);
}

TEST_CASE("the two references agree with each other", "[simulate][reference]") {
  ReadOptions ro;
  ro.required_columns = {"t", "u", "x", "v"};
  const Recording peer = ReadRecording(test::TestData("simulate/p1_reference_1ms.csv"), ro);
  const auto& ref = Reference();
  double dv = 0;
  for (size_t k = 0; k < ref.v.size(); ++k)
    dv = std::max(dv, std::abs(ref.v[k] - peer.column("v")[static_cast<Eigen::Index>(k)]));
  // Both RK4 with h = 1e-6 s (measured agreement < 5e-11); event handling differs in detail.
  CHECK(dv < 1e-9);
}

}  // namespace
}  // namespace sysid
