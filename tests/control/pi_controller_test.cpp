// The discrete PI law against hand-computed sequences, and the reference profile against its
// own numerical derivatives.
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "sysid/control.hpp"
#include "sysid/error.hpp"

namespace {

// x_{k+1} = x_k + b Ts u_k: a pure integrator (velocity-controlled stage), b = 1 m/(s V).
struct Integrator {
  double x = 0, ts = 0.1;
  double operator()(double u) { return x += ts * u; }
};

sysid::PiOptions SmallGains() {
  sysid::PiOptions o;
  o.kp_v_per_m = 2;
  o.ki_v_per_m_s = 10;
  o.sample_time_s = 0.1;
  o.u_max_v = 100;
  return o;
}

sysid::PositionReference Step(int n, double ts, double r) {
  sysid::PositionReference ref;
  ref.t_s = Eigen::VectorXd::LinSpaced(n, 0, (n - 1) * ts);
  ref.x_m = Eigen::VectorXd::Constant(n, r);
  ref.v_mps = ref.a_mps2 = Eigen::VectorXd::Zero(n);
  return ref;
}

}  // namespace

TEST_CASE("PI step response on an integrator matches the hand-computed sequence", "[control][pi]") {
  // By hand (Kp = 2, Ki = 10, Ts = 0.1, r = 1): e0 = 1, I0 = 0.1, u0 = 3, x1 = 0.3;
  // e1 = 0.7, I1 = 0.17, u1 = 3.1, x2 = 0.61; e2 = 0.39, I2 = 0.209, u2 = 2.87, x3 = 0.897;
  // e3 = 0.103, I3 = 0.2193, u3 = 2.399, x4 = 1.1369.
  Integrator plant;
  const auto res = sysid::RunClosedLoop(std::ref(plant), 0.0, Step(200, 0.1, 1.0), SmallGains());
  const std::vector<double> u = {3.0, 3.1, 2.87, 2.399};
  const std::vector<double> x = {0.0, 0.3, 0.61, 0.897, 1.1369};
  for (size_t k = 0; k < u.size(); ++k) CHECK(res.u_v[k] == Approx(u[k]).epsilon(1e-12));
  for (size_t k = 0; k < x.size(); ++k) CHECK(res.x_m[k] == Approx(x[k]).epsilon(1e-12));
  // Closed loop: x_{k+1} = x_k + Ts (Kp e_k + Ki I_k); poles |z| < 1 here, so x -> r.
  CHECK(res.x_m[199] == Approx(1.0).epsilon(1e-9));  // 20 s = many time constants
  CHECK(res.max_error_m == Approx(1.0));
}

TEST_CASE("anti-windup holds the integral while the output is clipped", "[control][pi]") {
  sysid::PiOptions o = SmallGains();
  o.u_max_v = 1;
  // By hand with conditional integration: while I = 0 the free output is
  // 2e + 10 (0 + 0.1 e) = 3e > 1, so the integral stays frozen; u = clip(2e) = 1 for
  // e >= 0.5 (x = 0, 0.1, ..., 0.5), then x6 = 0.6: e = 0.4, 3e = 1.2 > 1 -> I = 0, u = 0.8;
  // x7 = 0.68: e = 0.32, 3e = 0.96 <= 1 -> I = 0.032, u = 0.64 + 0.32 = 0.96.
  Integrator plant;
  const auto res = sysid::RunClosedLoop(std::ref(plant), 0.0, Step(300, 0.1, 1.0), o);
  for (int k = 0; k < 6; ++k) {
    CHECK(res.u_v[k] == Approx(1.0).epsilon(1e-12));
    CHECK(res.x_m[k] == Approx(0.1 * k).margin(1e-12));
  }
  CHECK(res.u_v[6] == Approx(0.8).epsilon(1e-12));
  CHECK(res.x_m[7] == Approx(0.68).epsilon(1e-12));
  CHECK(res.u_v[7] == Approx(0.96).epsilon(1e-12));
  CHECK(res.saturated_samples >= 5);  // k = 0..4 clipped; k = 5 sits exactly at the limit
  // Without anti-windup the integral winds up during saturation and the response overshoots
  // far more.
  sysid::PiOptions none = o;
  none.anti_windup = sysid::AntiWindup::kNone;
  Integrator plant2;
  const auto wound = sysid::RunClosedLoop(std::ref(plant2), 0.0, Step(300, 0.1, 1.0), none);
  const double overshoot_aw = res.x_m.maxCoeff() - 1.0;
  const double overshoot_none = wound.x_m.maxCoeff() - 1.0;
  CHECK(overshoot_none > 2 * overshoot_aw);
  CHECK(res.x_m[299] == Approx(1.0).epsilon(1e-6));  // both settle eventually
}

TEST_CASE("feedforward adds to the PI output and options are checked", "[control][pi]") {
  sysid::PiController pi(SmallGains());
  // e = 0: only the feedforward remains.
  CHECK(pi.Update(0.0, 1.25) == 1.25);
  sysid::PiOptions bad;
  bad.sample_time_s = 0;
  CHECK_THROWS_WITH(sysid::PiController(bad), Catch::Contains("sample_time_s > 0"));
  Integrator plant;
  CHECK_THROWS_AS(sysid::RunClosedLoop(std::ref(plant), 0.0, Step(10, 0.01, 1.0), SmallGains()),
                  sysid::OptionsError);  // reference sampled at 0.01 s vs Ts = 0.1 s
  const auto ref = Step(20, 0.1, 0.0);
  const auto res = sysid::RunClosedLoop(std::ref(plant), 0.0, ref, SmallGains(),
                                        [](const sysid::ReferenceSample&) { return 0.5; });
  CHECK(res.u_ff_v.minCoeff() == 0.5);
}

TEST_CASE("the smooth profile has continuous derivatives and rests at the ends",
          "[control][reference]") {
  sysid::SmoothProfileOptions o;
  o.frequency_hz = 1.0;
  o.amplitude_m = 0.01;
  o.dwell_fraction = 0.1;
  o.cycles = 2;
  o.sample_rate_hz = 10000;
  const auto r = sysid::MakeSmoothProfile(o);
  const double dt = 1e-4;
  REQUIRE(r.x_m.size() == 20001);
  CHECK(r.x_m.maxCoeff() == Approx(0.01).epsilon(1e-9));
  CHECK(r.x_m.minCoeff() == Approx(0.0).margin(1e-15));
  // Minimum-jerk peak speed 1.875 A / Tm with Tm = (1 - 2 d) / (2 f) = 0.4 s.
  CHECK(r.v_mps.maxCoeff() == Approx(1.875 * 0.01 / 0.4).epsilon(1e-6));
  // v and a agree with central differences of x and v (O(dt^2) = 1e-8 relative here).
  double worst_v = 0, worst_a = 0;
  for (Eigen::Index k = 1; k + 1 < r.x_m.size(); ++k) {
    worst_v = std::max(worst_v, std::abs((r.x_m[k + 1] - r.x_m[k - 1]) / (2 * dt) - r.v_mps[k]));
    worst_a =
        std::max(worst_a, std::abs((r.v_mps[k + 1] - r.v_mps[k - 1]) / (2 * dt) - r.a_mps2[k]));
  }
  CHECK(worst_v < 1e-6);  // [m/s] vs peak 0.047: truncation error of the difference
  CHECK(worst_a < 1e-3);  // [m/s^2] vs peak 0.36; includes the jerk jumps at move ends
  CHECK(r.v_mps[0] == 0);
  CHECK(r.v_mps[500] == 0);  // inside the first dwell (0.1 s)
  CHECK_THROWS_WITH(sysid::MakeSmoothProfile({0.5, 0.01, 0.5, 1, 1000}),
                    Catch::Contains("0 <= dwell_fraction < 0.5"));
}
