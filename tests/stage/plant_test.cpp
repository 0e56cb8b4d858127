// The virtual stage's plant against an independent tiny-step RK4 integrator of the documented
// equations, and its rig effects (DAC, encoder, limits, noise).
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "core/portable_random.hpp"
#include "sysid/error.hpp"
#include "sysid/stage.hpp"
#include "velocity_source_reference.hpp"

namespace {

using sysid::test::Stage1kHz;
using sysid::test::VelocitySourceReference;

// The plant equations of stage.hpp, written out again and integrated by classic RK4 with
// h = 1 us (1000 steps per sample, the delay's half-sample edge on a step boundary).
struct Rk4Reference {
  sysid::StageParameters p;
  double drive = 0;
  std::vector<double> Rhs(const std::vector<double>& y) const {
    const double v = y[1];
    const sysid::FrictionBranch& b =
        v < 0 ? p.actuator_delay().backward : p.actuator_delay().forward;
    const double r = v / b.stribeck_velocity_mps;
    const double g = b.coulomb_mps2 + (b.static_mps2 - b.coulomb_mps2) * std::exp(-r * r);
    const double dz = v - p.actuator_delay().bristle_stiffness_per_s2 * std::abs(v) * y[2] / g;
    const double f = p.actuator_delay().bristle_stiffness_per_s2 * y[2] +
                     p.actuator_delay().bristle_damping_per_s * dz + b.viscous_per_s * v;
    return {v, p.actuator_delay().gain_mps2_per_v * y[3] - f, dz,
            (drive - y[3]) / p.driver.lag_time_constant_s};
  }
  void Step(std::vector<double>& y, double h) const {
    auto add = [](const std::vector<double>& a, const std::vector<double>& b, double s) {
      std::vector<double> c(a);
      for (size_t i = 0; i < c.size(); ++i) c[i] += s * b[i];
      return c;
    };
    const auto k1 = Rhs(y);
    const auto k2 = Rhs(add(y, k1, h / 2));
    const auto k3 = Rhs(add(y, k2, h / 2));
    const auto k4 = Rhs(add(y, k3, h));
    for (size_t i = 0; i < y.size(); ++i) y[i] += h / 6 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
  }
  double Driver(double u_dac) const {
    const double s = std::clamp(u_dac, -p.driver.saturation_v, p.driver.saturation_v);
    if (std::abs(s) <= p.actuator_delay().dead_zone_v) return 0;
    return p.actuator_delay().DriveMap(s > 0 ? s - p.actuator_delay().dead_zone_v
                                             : s + p.actuator_delay().dead_zone_v);
  }
};

// Runs the plant and the reference through pulses, reversals, the low-speed segment and stick
// phases; returns the largest position and velocity differences [m], [m/s].
std::pair<double, double> CompareWithReference(const sysid::StageParameters& p) {
  const int n = 420;
  std::vector<double> u(n, 0.0);
  for (int k = 10; k < 110; ++k) u[k] = 2.0;     // forward pulse, decays to rest in the dead zone
  for (int k = 110; k < 210; ++k) u[k] = -2.3;   // direct reversal
  for (int k = 230; k < 330; ++k) u[k] = 1.25;   // the steep low-speed segment
  for (int k = 330; k < 400; ++k) u[k] = -1.75;  // just past the backward dead zone
  sysid::VirtualStage stage(p, 1);
  VelocitySourceReference ref{p};
  double worst_x = 0, worst_v = 0;
  bool saw_stuck = false, saw_slide_after = false;
  for (int k = 0; k < n; ++k) {
    stage.Step(u[k]);
    const double drive =
        std::clamp(stage.DacOutput(u[k]), -p.driver.saturation_v, p.driver.saturation_v);
    for (int i = 0; i < 1000; ++i) ref.Step(drive, 1e-6);
    const sysid::StageState s = stage.state();
    worst_x = std::max(worst_x, std::abs(s.x_m - ref.x));
    worst_v = std::max(worst_v, std::abs(s.v_mps - ref.v));
    if (p.velocity_source().rail.memory_time_s > 0)
      CHECK(s.slip_memory_mps == Approx(ref.s).margin(5e-5));
    if (k > 20) {
      CHECK(s.stuck == ref.stuck);
      saw_stuck = saw_stuck || s.stuck;
      saw_slide_after = saw_slide_after || (saw_stuck && !s.stuck);
    }
  }
  INFO("final x " << ref.x << " m");
  CHECK(std::abs(ref.x) > 1e-3);  // it really moved
  CHECK(saw_stuck);
  CHECK(saw_slide_after);
  return {worst_x, worst_v};
}

}  // namespace

TEST_CASE("the velocity-source plant matches a tiny-step reference through stick, slip and "
          "reversals",
          "[stage][plant]") {
  sysid::StageParameters p = Stage1kHz();
  REQUIRE(p.model() == sysid::StageModel::kVelocitySource);
  p.rig.position_noise_m = 0;
  SECTION("memoryless rail (Karnopp with g(|v|))") {
    p.velocity_source().rail.memory_time_s = 0;
    const auto [worst_x, worst_v] = CompareWithReference(p);
    INFO("max |dx| " << worst_x << " m, max |dv| " << worst_v << " m/s");
    // CVODE rtol 1e-7 over ~2.5 cm of path (measured 3.9e-8 m); the reference locates each
    // switch to within its 1 us step, where the velocity moves by up to |v'| h ~ 3e-5 m/s.
    CHECK(worst_x < 6e-8);  // [m]
    CHECK(worst_v < 5e-5);  // [m/s]
  }
  SECTION("rail with frictional memory and a strong Stribeck dip") {
    p.velocity_source().rail = {0.6, 4.0, 0.01, 0.02};
    const auto [worst_x, worst_v] = CompareWithReference(p);
    INFO("max |dx| " << worst_x << " m, max |dv| " << worst_v << " m/s");
    CHECK(worst_x < 6e-8);  // [m]
    CHECK(worst_v < 5e-5);  // [m/s]
  }
  SECTION("a stiff droop behind a thrust limit") {
    p.velocity_source().motor.pole_per_s = 2000;
    p.velocity_source().motor.thrust_limit_mps2 = 8;
    p.velocity_source().rail = {0.6, 1.0, 0.005, 0.0};
    const auto [worst_x, worst_v] = CompareWithReference(p);
    INFO("max |dx| " << worst_x << " m, max |dv| " << worst_v << " m/s");
    CHECK(worst_x < 6e-8);  // [m]
    CHECK(worst_v < 5e-5);  // [m/s]
  }
}

TEST_CASE("thrust limit: steady velocities, breakaway and the limit on acceleration",
          "[stage][plant]") {
  sysid::StageParameters p = Stage1kHz();
  p.velocity_source().motor.pole_per_s = 2000;
  p.velocity_source().motor.thrust_limit_mps2 = 8;
  p.velocity_source().rail = {0.6, 1.0, 0.005, 0.0};
  p.rig.position_noise_m = 0;
  p.velocity_source().SetSpeedMapThrough(sysid::StageParameters::PaperPulseTable());
  REQUIRE_NOTHROW(p.Validate());
  // The speed map puts each held pulse on the paper's plateau: L tanh(p (v_f - v) / L) = g(v).
  for (const auto& [u, v] : sysid::StageParameters::PaperPulseTable())
    CHECK(p.SteadyVelocity(u) == Approx(v).epsilon(1e-10));
  // Breakaway where L tanh(p v_f / L) = Fs: v_f = (L / p) atanh(Fs / L).
  const double vf_break = 8.0 / 2000 * std::atanh(1.0 / 8);
  double lo = p.velocity_source().motor.dead_zone_forward_v,
         hi = 1.3;  // v_f rises from 0 to the first knot
  for (int i = 0; i < 100; ++i)
    (p.velocity_source().NoLoadSpeed(0.5 * (lo + hi)) < vf_break ? lo : hi) = 0.5 * (lo + hi);
  CHECK(p.SteadyVelocity(lo - 1e-9) == 0.0);
  CHECK(p.SteadyVelocity(hi + 1e-9) > 0.0);
  // A 2 V step from rest: the stage accelerates at no more than L - Fc (the lag and the
  // tanh only lower it), and the droop is saturated at the start (p v_f = 170 m/s^2 >> L).
  sysid::VirtualStage stage(p, 1);
  double v_prev = 0, max_accel = 0;
  for (int k = 0; k < 30; ++k) {
    stage.Step(2.0);
    const double v = stage.state().v_mps;
    max_accel = std::max(max_accel, (v - v_prev) / p.sample_time_s());
    v_prev = v;
  }
  CHECK(max_accel <= 8 - 0.6 + 1e-9);
  CHECK(max_accel > 0.9 * (8 - 0.6));
  // Validate: a limit at or below the static friction could never break the stage away.
  p.velocity_source().motor.thrust_limit_mps2 = 1.0;
  CHECK_THROWS_WITH(p.Validate(), Catch::Contains("thrust_limit_mps2"));
  // Near its limit the thrust barely grows with the droop: the Stribeck dip could then give two
  // steady speeds. p = 100 beats max |g'| = 68.6 1/s alone, not with L = 1.2 (100 x 0.31).
  p.velocity_source().motor.pole_per_s = 100;
  p.velocity_source().motor.thrust_limit_mps2 = 0;
  CHECK_NOTHROW(p.Validate());
  p.velocity_source().motor.thrust_limit_mps2 = 1.2;
  CHECK_THROWS_WITH(p.Validate(), Catch::Contains("single steady speed"));
}

TEST_CASE("frictional memory: the lagged slip speed against its closed forms", "[stage][plant]") {
  sysid::StageParameters p = Stage1kHz();
  p.rig.position_noise_m = 0;
  p.velocity_source().rail = {0.6, 4.0, 0.01, 0.02};
  const double tm = p.velocity_source().rail.memory_time_s;
  // A long held pulse: steady sliding has s = |v|, so the steady law (and the pulse table) does
  // not depend on T_m.
  sysid::VirtualStage stage(p, 1);
  for (int k = 0; k < 400; ++k) stage.Step(2.0);
  const double v_end = stage.state().v_mps;
  CHECK(stage.state().slip_memory_mps == Approx(v_end).epsilon(1e-6));
  CHECK(v_end == Approx(p.SteadyVelocity(2.0)).epsilon(2e-3));
  // At rest (0 V holds the stage) the memory fades as s(t) = s0 exp(-t / T_m).
  int k_rest = -1;
  double s0 = 0;
  for (int k = 0; k < 300; ++k) {
    stage.Step(0.0);
    if (k_rest < 0 && stage.state().stuck) {
      k_rest = k;
      s0 = stage.state().slip_memory_mps;
    }
    if (k_rest >= 0 && k == k_rest + 40) {
      INFO("s0 " << s0 << " m/s");
      REQUIRE(s0 > 1e-4);
      // CVODE's absolute tolerance on s is position_tolerance_m / Ts = 1e-7 m/s.
      CHECK(stage.state().slip_memory_mps == Approx(s0 * std::exp(-40e-3 / tm)).margin(2e-6));
    }
  }
  REQUIRE(k_rest >= 0);
}

TEST_CASE("the triangle's voltage-velocity loop widens with the rate and with the memory",
          "[stage][plant]") {
  // Open-loop triangle 0 -> +1.5 -> 0 -> -2.1 -> 0 V over a period T: the width of the loop at
  // +1.25 V (falling minus rising branch velocity) [m/s]. docs/virtual_stage.md, "Rate
  // dependence" (measured: 3.1 / 16.1 / 24.2 mm/s at 6 / 1.5 / 0.75 s; 9.9 mm/s at 1.5 s without
  // memory).
  auto width = [](double memory_time_s, double period_s) {
    sysid::StageParameters p = Stage1kHz();
    p.velocity_source().rail.memory_time_s = memory_time_s;
    p.rig.position_noise_m = 0;
    const int n = static_cast<int>(period_s * 1000);
    const double q = period_s / 4;
    Eigen::VectorXd u(n);
    for (int k = 0; k < n; ++k) {
      const double t = k / 1000.0;
      u[k] = t < q ? 1.5 * t / q
                   : t < 2 * q ? 1.5 * (2 * q - t) / q
                               : t < 3 * q ? -2.1 * (t - 2 * q) / q : -2.1 * (4 * q - t) / q;
    }
    const sysid::StageRun r = sysid::RunOpenLoop(p, u, 1);
    double v[2] = {0, 0};
    int found = 0;
    for (int k = 1; k < n && found < 2; ++k)
      if ((u[k - 1] - 1.25) * (u[k] - 1.25) <= 0 && u[k - 1] != 1.25) v[found++] = r.v_true_mps[k];
    REQUIRE(found == 2);
    return v[1] - v[0];
  };
  const double slow = width(0.02, 6.0), mid = width(0.02, 1.5), fast = width(0.02, 0.75);
  const double none = width(0.0, 1.5), half = width(0.01, 1.5);
  INFO("loop width at +1.25 V: " << slow << " / " << mid << " / " << fast << " m/s; at 1.5 s "
                                 << none << " (no memory), " << half << " (T_m = 10 ms)");
  CHECK(slow > 0);
  // A first-order lag (the memory T_m, the drive's lag) shifts the two branches by
  // +-T_m |dv/dt|: the width is proportional to the sweep rate at slow rates, so 4x the rate
  // gives at least 4x the width (measured 5.2x: the Stribeck slope steepens it further).
  CHECK(mid > 4 * slow);
  CHECK(fast > mid);
  // The width grows with the memory time at a fixed rate (the lag T_m |dv/dt| grows with T_m):
  // measured 9.9 / 14.8 / 16.1 mm/s at T_m = 0, 10, 20 ms.
  CHECK(half > none);
  CHECK(mid > half);
}

TEST_CASE("velocity source: speed map, steady velocities and breakaway against closed forms",
          "[stage][plant]") {
  const sysid::StageParameters p = Stage1kHz();
  const double pp = p.velocity_source().motor.pole_per_s;
  // The map passes its knots, is 0 in the dead zone and extends its end segments linearly.
  for (size_t i = 0; i < p.velocity_source().motor.speed_map_in_v.size(); ++i)
    CHECK(p.velocity_source().NoLoadSpeed(p.velocity_source().motor.speed_map_in_v[i]) ==
          Approx(p.velocity_source().motor.speed_map_out_mps[i]));
  CHECK(p.velocity_source().NoLoadSpeed(0.0) == 0.0);
  CHECK(p.velocity_source().NoLoadSpeed(p.velocity_source().motor.dead_zone_forward_v) == 0.0);
  CHECK(p.velocity_source().NoLoadSpeed(-p.velocity_source().motor.dead_zone_backward_v) == 0.0);
  const double f13 = p.velocity_source().NoLoadSpeed(1.3),
               f17 = p.velocity_source().NoLoadSpeed(1.7),
               f20 = p.velocity_source().NoLoadSpeed(2.0);
  const double dz = p.velocity_source().motor.dead_zone_forward_v;
  CHECK(p.velocity_source().NoLoadSpeed(0.5 * (dz + 1.3)) == Approx(0.5 * f13));
  CHECK(p.velocity_source().NoLoadSpeed(3.0) == Approx(f20 + (f20 - f17) / 0.3 * 1.0));
  // Steady sliding p (v_f - v) = g(v): the paper's ten pulse points come out exactly.
  const double table[10][2] = {{1.3, 0.04465},   {1.5, 0.05742},   {1.6, 0.06222},
                               {1.7, 0.06863},   {2.0, 0.08519},   {-1.8, -0.03393},
                               {-2.0, -0.04622}, {-2.1, -0.04991}, {-2.3, -0.05562},
                               {-2.5, -0.07120}};
  for (const auto& row : table) {
    const double v = p.SteadyVelocity(row[0]);
    CHECK(v == Approx(row[1]).epsilon(1e-10));
    CHECK(pp * (p.velocity_source().NoLoadSpeed(row[0]) - v) ==
          Approx((v > 0 ? 1 : -1) * p.velocity_source().rail.Sliding(std::abs(v))));
  }
  // Breakaway from rest where p v_f(u) = Fs: on the first segment v_f = f13 (u - dz)/(1.3 - dz).
  const double u_start = dz + p.velocity_source().rail.static_mps2 / pp * (1.3 - dz) / f13;
  CHECK(p.SteadyVelocity(u_start - 1e-6) == 0.0);
  CHECK(p.SteadyVelocity(u_start + 1e-3) > 0.0);
  // Held inside the threshold the stage does not move at all (the preload holds it).
  sysid::StageParameters quiet = p;
  quiet.rig.position_noise_m = 0;
  const sysid::StageRun held =
      sysid::RunOpenLoop(quiet, Eigen::VectorXd::Constant(200, u_start - 0.002), 3);
  CHECK(held.x_true_m.cwiseAbs().maxCoeff() == 0.0);
  const sysid::StageRun back = sysid::RunOpenLoop(
      quiet, Eigen::VectorXd::Constant(200, -p.velocity_source().motor.dead_zone_backward_v + 0.01),
      3);
  CHECK(back.x_true_m.cwiseAbs().maxCoeff() == 0.0);
  // A held voltage settles at the steady velocity (time constant 1/p = 3.3 ms << 0.3 s).
  for (double u : {1.25, 1.6, 3.0, -1.9, -4.0}) {
    const sysid::StageRun run = sysid::RunOpenLoop(quiet, Eigen::VectorXd::Constant(300, u), 3);
    // The DAC moves u by <= 1.5e-4 V; on the steepest segment that is ~1e-4 of v.
    CHECK(run.v_true_mps[299] == Approx(p.SteadyVelocity(u)).epsilon(2e-3));
  }
}

TEST_CASE("the actuator-delay plant matches a tiny-step RK4 reference through pulses and reversals",
          "[stage][plant]") {
  sysid::StageParameters p = sysid::StageParameters::ActuatorDelay();
  p.driver.transport_delay_s = 0.0025;  // 2.5 samples: exercises the edge inside the sample
  p.rig.position_noise_m = 0;
  const int n = 260;
  std::vector<double> u(n, 0.0);
  for (int k = 10; k < 110; ++k) u[k] = 2.0;
  for (int k = 110; k < 210; ++k) u[k] = -2.3;  // reversal through stick and the Stribeck dip
  sysid::VirtualStage stage(p, 1);
  Rk4Reference ref{p};
  std::vector<double> y = {p.rig.initial_position_m, 0, 0, 0};
  std::vector<double> dac;
  double worst_x = 0, worst_v = 0;
  for (int k = 0; k < n; ++k) {
    stage.Step(u[k]);
    dac.push_back(stage.DacOutput(u[k]));
    // Delayed DAC value: 2.5 samples -> u[k-3] for the first half of sample k, u[k-2] after.
    const double before = k >= 3 ? dac[k - 3] : 0.0, after = k >= 2 ? dac[k - 2] : 0.0;
    for (int i = 0; i < 1000; ++i) {
      ref.drive = ref.Driver(i < 500 ? before : after);
      ref.Step(y, 1e-6);
    }
    const sysid::StageState s = stage.state();
    worst_x = std::max(worst_x, std::abs(s.x_m - y[0]));
    worst_v = std::max(worst_v, std::abs(s.v_mps - y[1]));
  }
  INFO("final x " << y[0] << " m, max |dx| " << worst_x << " m, max |dv| " << worst_v);
  REQUIRE(std::abs(y[0]) > 1e-3);  // it really moved
  CHECK(worst_x < 2e-8);           // [m] CVODE rtol 1e-7 on ~1 cm of travel, RK4 error ~1e-12
  CHECK(worst_v < 2e-5);           // [m/s] same tolerances on velocities of ~0.1 m/s
}

TEST_CASE("actuator delay: a held voltage settles at the steady velocity found by bisection",
          "[stage][plant]") {
  const sysid::StageParameters p = sysid::StageParameters::ActuatorDelay();
  for (double u : {0.9, 3.0, -1.6, -4.0}) {
    const Eigen::VectorXd cmd = Eigen::VectorXd::Constant(300, u);
    const sysid::StageRun run = sysid::RunOpenLoop(p, cmd, 3);
    // 0.3 s >> the ~10 ms mechanical time constant; the DAC moves u by < 1.6e-4 V.
    CHECK(run.v_true_mps[299] == Approx(p.SteadyVelocity(u)).epsilon(2e-3));
  }
  // Below breakaway (dz + Fs/a3 = 0.633 V forward) the stage only creeps in pre-sliding.
  const sysid::StageRun stuck = sysid::RunOpenLoop(p, Eigen::VectorXd::Constant(300, 0.5), 3);
  CHECK(std::abs(stuck.x_true_m[299]) < 5e-6);  // [m] bristle deflection <= Fs/s0 = 2.9 um
  CHECK(p.SteadyVelocity(0.5) == 0.0);
}

TEST_CASE("the transport delay holds the drive back by whole and half samples", "[stage][plant]") {
  sysid::StageParameters p = sysid::StageParameters::ActuatorDelay();
  p.driver.transport_delay_s = 0.003;
  sysid::VirtualStage stage(p, 1);
  for (int k = 0; k < 3; ++k) {
    stage.Step(5.0);
    CHECK(stage.state().w_v == 0.0);  // the driver has not seen the step yet
  }
  stage.Step(5.0);
  CHECK(stage.state().w_v > 0.0);
}

TEST_CASE("DAC, encoder and noise are what the rig specifies", "[stage][rig]") {
  const sysid::StageParameters p = Stage1kHz();
  sysid::VirtualStage stage(p, 11);
  const double q = 20.0 / 65536;
  for (double u : {1.3, -2.5, 0.0, 0.1234567})
    CHECK(std::abs(stage.DacOutput(u) - u) <= q / 2 + 1e-15);
  CHECK(stage.DacOutput(25.0) == Approx(10.0 - q).epsilon(1e-15));
  CHECK(stage.DacOutput(-25.0) == -10.0);
  CHECK_THROWS_AS(stage.Step(std::nan("")), sysid::OptionsError);
  const sysid::StageRun run = sysid::RunOpenLoop(p, Eigen::VectorXd::Constant(500, 1.5), 5);
  double worst = 0, worst_error = 0;
  for (Eigen::Index k = 0; k < run.x_m.size(); ++k) {
    const double counts = run.x_m[k] / p.rig.encoder_resolution_m;
    worst = std::max(worst, std::abs(counts - std::round(counts)));
    worst_error = std::max(worst_error, std::abs(run.x_m[k] - run.x_true_m[k]));
  }
  // reading = round((x + n)/q) q with |n| <= 6 sigma (Irwin-Hall bound) and q/2 rounding
  CHECK(worst_error <= 6 * p.rig.position_noise_m + 0.5e-7 + 1e-15);
  CHECK(worst < 1e-6);  // readings are whole encoder counts (up to the double's rounding)  //
                        // readings are whole encoder counts (up to the double's rounding)
}

TEST_CASE("the noise is seeded, standard-specified and close to N(0,1)", "[stage][noise]") {
  // The C++ standard fixes mt19937_64's 10000th output ([rand.predef]).
  std::mt19937_64 e;
  e.discard(9999);
  CHECK(e() == 9981545732273789042ULL);
  sysid::internal::PortableRandom a(5), b(5), c(6);
  double s1 = 0, s2 = 0, s4 = 0;
  bool differ = false, same_seed_same = true;
  const int n = 100000;
  for (int i = 0; i < n; ++i) {
    const double x = a.IrwinHallGaussian();
    same_seed_same = same_seed_same && x == b.IrwinHallGaussian();
    differ = differ || x != c.IrwinHallGaussian();
    s1 += x;
    s2 += x * x;
    s4 += x * x * x * x;
  }
  CHECK(same_seed_same);
  CHECK(differ);
  // Irwin-Hall(12) - 6: mean 0, variance 1, kurtosis 3 - 1.2/12 = 2.9. Sampling errors at
  // n = 1e5: sd(mean) = 0.0032, sd(var) ~ 0.0044, sd(kurtosis) ~ 0.02; bounds are ~5 sd.
  CHECK(std::abs(s1 / n) < 0.016);
  CHECK(s2 / n == Approx(1.0).margin(0.022));
  CHECK(s4 / n == Approx(2.9).margin(0.1));
}

TEST_CASE("end stops hold the stage and are reported, overspeed is reported", "[stage][limits]") {
  for (const auto& preset : {Stage1kHz(),
                             sysid::StageParameters::ActuatorDelay()}) {
    INFO(preset.name);
    sysid::StageParameters p = preset;
    p.rig.initial_position_m = 0.055;
    Eigen::VectorXd u(600);
    u.head(300).setConstant(3.0);
    u.tail(300).setConstant(-3.0);
    const sysid::StageRun run = sysid::RunOpenLoop(p, u, 1);
    CHECK(run.status.travel_limit_hit);
    CHECK(run.status.first_travel_hit_s > 0.0);
    CHECK(run.x_true_m.maxCoeff() <= p.rig.travel_max_m);
    CHECK(run.x_true_m[299] == p.rig.travel_max_m);
    CHECK(run.x_true_m[599] < p.rig.travel_max_m - 0.01);  // reversed away from the stop
    CHECK_THAT(run.status.Describe(), Catch::Contains("travel limit hit at t = "));
    CHECK_FALSE(run.status.velocity_limit_exceeded);
    const sysid::StageRun fast = sysid::RunOpenLoop(preset, Eigen::VectorXd::Constant(100, 9.0));
    CHECK(fast.status.velocity_limit_exceeded);  // steady speed ~0.5 m/s > 0.23 m/s
  }
}

TEST_CASE("an integrator failure is the CVODE wrapper's sentence with the stage's hint",
          "[stage][plant]") {
  sysid::StageParameters p = Stage1kHz();
  p.integrator.relative_tolerance = 1e-300;  // valid (> 0) but below what a double can deliver
  p.integrator.position_tolerance_m = 1e-300;
  sysid::VirtualStage stage(p, 1);
  CHECK_THROWS_AS(stage.Step(2.0), sysid::NumericalError);
  sysid::VirtualStage again(p, 1);
  CHECK_THROWS_WITH(again.Step(2.0),
                    Catch::StartsWith("virtual stage: CVODE failed at t = ") &&
                        Catch::Contains("(CV_TOO_MUCH_ACC) in CVode") &&
                        Catch::EndsWith("; try a larger integrator.relative_tolerance or a smaller "
                                        "friction.bristle_stiffness_per_s2"));
}
