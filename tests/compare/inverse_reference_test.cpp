// The analytic inverse u = (a + a1 v(t - tau) + a2 sgn v) / a3 against references it did not
// produce: (1) a hand-worked table, (2) the forward model x'' = -a1 v(t - tau) - a2 sgn v + a3 u
// integrated by the simulator tests' own tiny-step RK4 method of steps
// (tests/simulate/reference_integrator, no libsysid code) under a known piecewise-constant u,
// with u recovered from the simulated (a, v(t - tau), v) and required back.
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "identify/simulated_recording.hpp"
#include "simulate/reference_integrator.hpp"
#include "sysid/compare.hpp"
#include "sysid/input.hpp"
#include "sysid/model.hpp"

TEST_CASE("analytic inverse: hand-worked table", "[compare][inverse][reference]") {
  // Round coefficients so every row can be checked on paper; a1 follows the sign of v(t - tau),
  // a2 the sign of v (the rows with opposite signs are the reversals).
  const auto m = sysid::test::MakeModel(100, 120, 3, 7, 5, 0.002);
  struct Row {
    double a, vd, v, u;  // [m/s^2], [m/s], [m/s], expected [V]
  };
  const Row rows[] = {
      {10, 0.05, 0.04, 3.6},       // (10 + 100*0.05 + 3) / 5
      {-20, 0.05, -0.01, -4.4},    // (-20 + 100*0.05 - 7) / 5: reversal, a1p and a2n
      {4, -0.02, 0.01, 0.92},      // (4 + 120*(-0.02) + 3) / 5: reversal, a1n and a2p
      {-6, -0.03, -0.03, -3.32},   // (-6 + 120*(-0.03) - 7) / 5
      {2.5, 0.0, 0.01, 1.1},       // (2.5 + 0 + 3) / 5
      {-2.5, 0.0, 0.0, -0.5},      // at rest: no friction term, a / a3
  };
  for (const auto& r : rows) {
    INFO("a = " << r.a << ", v(t-tau) = " << r.vd << ", v = " << r.v);
    // Decimal inputs: the only error is the rounding of a few operations (1e-14 relative).
    CHECK(m.InverseVoltage(r.a, r.vd, r.v) == Approx(r.u).epsilon(1e-14).margin(1e-15));
  }
}

TEST_CASE("analytic inverse recovers the input of the forward model simulated by a tiny-step "
          "reference integrator",
          "[compare][inverse][reference]") {
  // Direction-dependent coefficients (the paper's), so p/n swaps show; tau = 350 h exactly.
  const auto m = sysid::test::MakeModel(104.0154, 117.1441, 3.1023, 6.8216, 6.0, 0.0035);
  const double h = 1e-5;  // [s] the reference's step; tau = 350 h
  // Forward, reverse while v(t - tau) is still positive, stick, forward, slow and fast backward,
  // reverse while v(t - tau) is still negative. Edges on the grid.
  const std::vector<double> edges{0.0, 0.04, 0.08, 0.12, 0.17, 0.23, 0.27};
  const std::vector<double> levels{2.0, -3.0, 0.3, 3.5, -1.6, -4.0, 1.0};
  const sysid::PiecewiseConstantInput input(edges, levels);
  const double t_end = 0.32;
  const auto ref = sysid::test::ReferenceRk4(m, input, t_end, h, 1);
  const auto n = static_cast<Eigen::Index>(ref.t.size());
  const auto D = static_cast<Eigen::Index>(std::lround(m.tau_s / h));
  // Acceleration by a central difference of the reference velocity: its error is
  // h^2/6 max|v'''| with v''' = a1^2 a(t - 2 tau) between events, so <= h^2/6 a1max^2 amax.
  Eigen::VectorXd v(n), a = Eigen::VectorXd::Zero(n);
  for (Eigen::Index k = 0; k < n; ++k) v[k] = ref.v[static_cast<size_t>(k)];
  for (Eigen::Index k = 1; k + 1 < n; ++k) a[k] = (v[k + 1] - v[k - 1]) / (2 * h);
  // a jumps at input edges and at events (stop / release / reversal) and has a kink tau later
  // (v(t - tau) has one there): the difference quotient is not the derivative on the two
  // samples next to them. Those samples are excluded, as are samples at rest (a stuck stage has
  // no inverse: any u in the dead zone holds it).
  std::vector<double> breaks;
  for (double e : edges) breaks.insert(breaks.end(), {e, e + m.tau_s});
  for (double e : ref.event_t) breaks.insert(breaks.end(), {e, e + m.tau_s});
  auto near_break = [&](double t) {
    for (double b : breaks)
      if (std::abs(t - b) <= 2.01 * h) return true;
    return false;
  };
  const double a1max = std::max(m.a1p, m.a1n);
  const double amax = a.cwiseAbs().maxCoeff();
  // The difference quotient's bound in volts, doubled for the RK4 and Hermite errors of v
  // (O(h^4), far smaller) and rounding (eps |v| / h ~ 1e-12 m/s^2).
  const double tol_v = 2 * h * h / 6 * a1max * a1max * amax / m.a3;
  REQUIRE(tol_v < 1e-4);  // a tolerance far below any term of the inverse

  const Eigen::VectorXd u_analytic = sysid::AnalyticInverse(m, h, v, a);
  int forward = 0, backward = 0, reversal = 0, accelerating = 0;
  double worst = 0;
  for (Eigen::Index k = D + 1; k + 1 < n; ++k) {
    const double t = ref.t[static_cast<size_t>(k)];
    if (v[k - 1] == 0 || v[k] == 0 || v[k + 1] == 0 || near_break(t)) continue;
    const double u_true = input.Value(t + 0.5 * h);  // edges on the grid: the step's value
    const double vd = v[k - D];                      // v(t - tau) on the grid, exactly
    const double u = m.InverseVoltage(a[k], vd, v[k]);
    INFO("t = " << t << " s, a = " << a[k] << ", v(t-tau) = " << vd << ", v = " << v[k]);
    REQUIRE(std::abs(u - u_true) <= tol_v);
    // The sampled-signal inverse of the comparisons (DelaySignal at tau = 350 h): same answer.
    REQUIRE(std::abs(u_analytic[k] - u_true) <= tol_v);
    worst = std::max(worst, std::abs(u - u_true));
    forward += vd > 0 && v[k] > 0;
    backward += vd < 0 && v[k] < 0;
    reversal += (vd > 0) != (v[k] > 0) && vd != 0;
    accelerating += std::abs(a[k]) > 1.0;
  }
  INFO("worst |u - u_true| = " << worst << " V, tolerance " << tol_v << " V");
  // Every regime is exercised: both directions, both kinds of reversal (v(t - tau) and v of
  // opposite signs) and a nonzero acceleration (the sign of a and the delay matter there).
  CHECK(forward > 5000);
  CHECK(backward > 5000);
  CHECK(reversal > 300);  // a few ms per reversal at 1e-5 s steps
  CHECK(accelerating > 3000);
}
