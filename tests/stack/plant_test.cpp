// The virtual piezo stack against independent references: its CVODE integration against a
// fixed-step RK4 at a tiny step of the same ODE driven by the hysteresis module's own rdpi
// model (the same operator sequence, computed by other code), its creep elements against their
// closed-form step response, and its DAC and sensor.
#include <catch2/catch.hpp>
#include <cmath>
#include <iomanip>
#include <vector>

#include "sysid/error.hpp"
#include "sysid/hysteresis.hpp"
#include "sysid/stack.hpp"

namespace {

// The stack without its rig's quantisation and noise, so that only the integration differs.
sysid::StackParameters Clean() {
  sysid::StackParameters p = sysid::StackParameters::Default();
  p.rig.dac_bits = 32;
  p.rig.sensor_noise_m = 0;
  p.rig.sensor_resolution_m = 1e-18;
  return p;
}

// One RK4 step of the stack's ODE (x, x', c_1..c_m) with the hysteresis output y held.
std::vector<double> Derivative(const sysid::StackParameters& p, double y,
                               const std::vector<double>& s) {
  const double wn = 2 * M_PI * p.mechanics.resonance_hz;
  std::vector<double> d(s.size());
  double drive = y;
  for (size_t j = 0; j < p.creep.fractions.size(); ++j) {
    drive += s[2 + j];
    d[2 + j] = (p.creep.fractions[j] * y - s[2 + j]) / p.creep.time_constants_s[j];
  }
  d[0] = s[1];
  d[1] = wn * wn * (drive - s[0]) - 2 * p.mechanics.damping_ratio * wn * s[1];
  return d;
}

void Rk4(const sysid::StackParameters& p, double y, double h, std::vector<double>& s) {
  auto add = [](const std::vector<double>& a, const std::vector<double>& b, double f) {
    std::vector<double> r(a.size());
    for (size_t i = 0; i < a.size(); ++i) r[i] = a[i] + f * b[i];
    return r;
  };
  const auto k1 = Derivative(p, y, s);
  const auto k2 = Derivative(p, y, add(s, k1, h / 2));
  const auto k3 = Derivative(p, y, add(s, k2, h / 2));
  const auto k4 = Derivative(p, y, add(s, k3, h));
  for (size_t i = 0; i < s.size(); ++i) s[i] += h / 6 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
}

}  // namespace

TEST_CASE(
    "CVODE and the exact discretisation match a tiny-step RK4 of the same ODE "
    "and operator sequence",
    "[stack]") {
  sysid::StackParameters p = Clean();
  const auto method = GENERATE(sysid::StackMethod::kCvode, sysid::StackMethod::kExact);
  p.integrator.method = method;
  INFO("integrator.method " << sysid::ToString(method));
  const double ts = p.sample_time_s();
  const int n = 600;  // 60 ms: reversals at two rates, the resonance rung, creep under way
  Eigen::VectorXd u(n);
  for (int k = 0; k < n; ++k) {
    const double t = k * ts;
    u[k] = 45 + 40 * std::sin(2 * M_PI * 40 * t) + 8 * std::sin(2 * M_PI * 430 * t);
  }
  sysid::PiezoStack stack(p);
  Eigen::VectorXd dac(n), x(n);
  for (int k = 0; k < n; ++k) {
    dac[k] = stack.DacOutput(u[k]);
    stack.Step(u[k]);
    x[k] = stack.state().x_m;  // at t_{k+1}
  }
  // The hysteresis module's rdpi model, simulated on the DAC samples: the same operator sequence.
  const Eigen::VectorXd y = sysid::PrandtlIshlinskiiModel(p.HysteresisPi()).Simulate(dac, ts);
  std::vector<double> s(2 + p.creep.fractions.size(), 0.0);
  const int sub = 2000;
  double worst = 0, scale = 0;
  for (int k = 0; k < n; ++k) {
    for (int i = 0; i < sub; ++i) Rk4(p, y[k], ts / sub, s);
    worst = std::max(worst, std::abs(x[k] - s[0]));
    scale = std::max(scale, std::abs(s[0]));
  }
  INFO("max |x_cvode - x_rk4| = " << worst << " m of max |x| = " << scale << " m");
  CHECK(scale > 20e-6);  // the drive spans most of the travel
  CHECK(worst <= 1e-6 * scale);
}

TEST_CASE("each creep element follows kappa y (1 - exp(-t / tau)) after a step", "[stack]") {
  const auto method = GENERATE(sysid::StackMethod::kCvode, sysid::StackMethod::kExact);
  INFO("integrator.method " << sysid::ToString(method));
  // CVODE's local error (~rtol per sample) adds up over the 30000 restarts: ~7e-8 relative at
  // the default rtol 1e-10, so the comparison runs at 1e-12.
  sysid::StackParameters p = Clean();
  p.integrator.relative_tolerance = 1e-12;
  p.integrator.method = method;
  sysid::PiezoStack stack(p);
  const double u = stack.DacOutput(50);  // 50 V to 3e-8 V, the 32-bit DAC's step
  const double ts = p.sample_time_s();
  // The loading curve from rest, worked by hand: y = p0 u + sum w_i (u - r_i) for r_i < u.
  double y = p.hysteresis.linear_gain_m_per_v * u;
  for (size_t i = 0; i < p.hysteresis.thresholds_v.size(); ++i)
    y += p.hysteresis.weights_m_per_v[i] * std::max(0.0, u - p.hysteresis.thresholds_v[i]);
  const int n = 30000;  // 3 s: the 0.1 s and 1 s elements nearly settle, the 10 s one rises
  for (int k = 1; k <= n; ++k) {
    stack.Step(u);
    if (k % 5000 != 0) continue;
    const double t = k * ts;
    const sysid::StackState st = stack.state();
    INFO("y = " << std::setprecision(17) << st.hysteresis_m << ", by hand " << y);
    CHECK(st.hysteresis_m == Approx(y).epsilon(1e-12));
    double creep_total = 0;
    for (size_t j = 0; j < p.creep.fractions.size(); ++j) {
      const double expected =
          p.creep.fractions[j] * y * (1 - std::exp(-t / p.creep.time_constants_s[j]));
      INFO("element " << j << " at t = " << t << " s");
      INFO("c = " << st.creep_m[j] << ", closed form " << expected << ", relative error "
                  << (st.creep_m[j] - expected) / (p.creep.fractions[j] * y));
      CHECK(std::abs(st.creep_m[j] - expected) <= 1e-8 * p.creep.fractions[j] * y);
      creep_total += expected;
    }
    // The resonance rang out long ago; x lags the slow creep by ~2 zeta / w_n only.
    CHECK(std::abs(st.x_m - (y + creep_total)) <= 1e-6 * y);
  }
}

TEST_CASE("the stack's DAC clips to the amplifier's range and the sensor quantises", "[stack]") {
  sysid::StackParameters p = sysid::StackParameters::Default();
  p.rig.sensor_noise_m = 0;
  p.rig.sensor_resolution_m = 1e-9;
  sysid::PiezoStack stack(p);
  const double step = (p.rig.voltage_max_v - p.rig.voltage_min_v) / 65535.0;
  CHECK(stack.DacOutput(500) == p.rig.voltage_max_v);
  CHECK(stack.DacOutput(-500) == p.rig.voltage_min_v);
  CHECK(std::abs(stack.DacOutput(33.3) - 33.3) <= step / 2 + 1e-12);
  CHECK(stack.DescribeLimits() == "none");
  stack.Step(200);
  stack.Step(200);
  CHECK(stack.clipped_samples() == 2);
  CHECK_THAT(stack.DescribeLimits(), Catch::Contains("clipped 2 samples (first at t = 0 s)"));
  const double r = stack.measured_position_m();
  CHECK(std::abs(r / 1e-9 - std::round(r / 1e-9)) < 1e-6);
  CHECK_THROWS_AS(stack.Step(std::nan("")), sysid::OptionsError);
}

TEST_CASE("the stack's readings: the same seed gives the same readings, another seed other noise",
          "[stack]") {
  const sysid::StackParameters p = sysid::StackParameters::Default();
  Eigen::VectorXd u = Eigen::VectorXd::LinSpaced(200, 0, 80);
  const auto a = sysid::RunStackOpenLoop(p, u, 7), b = sysid::RunStackOpenLoop(p, u, 7),
             c = sysid::RunStackOpenLoop(p, u, 8);
  CHECK(a.x_m == b.x_m);
  CHECK(a.x_m != c.x_m);
  CHECK(a.x_true_m == c.x_true_m);
  // The readings' noise is the rig's: 1 nm standard deviation.
  const Eigen::VectorXd d = a.x_m - a.x_true_m;
  const double sd = std::sqrt(d.squaredNorm() / static_cast<double>(d.size()));
  CHECK(sd > 0.7e-9);
  CHECK(sd < 1.3e-9);
}
