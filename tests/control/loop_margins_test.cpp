// Loop margins against closed forms (a delayed integrator; the continuous PI loop of the rough
// model, whose crossover solves a cubic), and the gain margin against a second method: the
// sampled closed loop simulated just inside and just outside it.
#include <catch2/catch.hpp>
#include <cmath>
#include <complex>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "support/test_support.hpp"
#include "sysid/control.hpp"
#include "sysid/error.hpp"
#include "sysid/model.hpp"

namespace {

constexpr double kPi = 3.14159265358979323846;

sysid::FrictionModel Model(double a1p, double a1n, double a3, double tau_s) {
  sysid::FrictionModel m;
  m.a1p = a1p;
  m.a1n = a1n;
  m.a3 = a3;
  m.tau_s = tau_s;
  return m;
}

// The peak |e| [m] over the last 200 samples of the sampled loop: x'' = -a1 x' + a3 u (RK4,
// 50 steps per sample, u held), u_k = gain (Kp e_k + Ki I_k), I_k = I_{k-1} + Ts e_k, from
// e = 1 um. Grows without bound outside the gain margin, decays inside.
double LateErrorPeak(double a1, double a3, const sysid::PiOptions& pi, double gain, int samples) {
  const double ts = pi.sample_time_s, h = ts / 50;
  double x = -1e-6, v = 0, integral = 0, peak = 0;
  for (int k = 0; k < samples; ++k) {
    const double e = -x;
    integral += ts * e;
    const double u = gain * (pi.kp_v_per_m * e + pi.ki_v_per_m_s * integral);
    auto f = [&](double vv) { return -a1 * vv + a3 * u; };
    for (int i = 0; i < 50; ++i) {
      const double k1v = f(v), k1x = v;
      const double k2v = f(v + h / 2 * k1v), k2x = v + h / 2 * k1v;
      const double k3v = f(v + h / 2 * k2v), k3x = v + h / 2 * k2v;
      const double k4v = f(v + h * k3v), k4x = v + h * k3v;
      x += h / 6 * (k1x + 2 * k2x + 2 * k3x + k4x);
      v += h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
    }
    if (k >= samples - 200) peak = std::max(peak, std::abs(e));
  }
  return peak;
}

// As LateErrorPeak with the rough model's delayed viscous term, x'' = -a1 x'(t - tau) + a3 u:
// tau a whole number of steps, x'(t - tau) between stored steps by linear interpolation
// (error h^2/8 max|x'''| per stage, far below the 3 % the test resolves).
double LateErrorPeakDelayed(double a1, double a3, double tau, const sysid::PiOptions& pi,
                            double gain, int samples) {
  const int steps = 50;
  const double ts = pi.sample_time_s, h = ts / steps;
  const auto d = static_cast<long>(std::lround(tau / h));
  std::vector<double> history(static_cast<size_t>(samples) * steps + 1, 0.0);  // v at t_j
  auto delayed = [&](long j, double frac) {  // v(t_j + frac h - tau), zero before the start
    const long i = j - d;
    if (i < 0) return 0.0;
    const double v0 = history[static_cast<size_t>(i)], v1 = history[static_cast<size_t>(i + 1)];
    return (1 - frac) * v0 + frac * v1;
  };
  double x = -1e-6, v = 0, integral = 0, peak = 0;
  long j = 0;
  for (int k = 0; k < samples; ++k) {
    const double e = -x;
    integral += ts * e;
    const double u = gain * (pi.kp_v_per_m * e + pi.ki_v_per_m_s * integral);
    for (int s = 0; s < steps; ++s, ++j) {
      history[static_cast<size_t>(j)] = v;
      // v' does not depend on v (the viscous term is delayed by at least one step): Simpson.
      const double g0 = -a1 * delayed(j, 0.0) + a3 * u, gm = -a1 * delayed(j, 0.5) + a3 * u,
                   g1 = -a1 * delayed(j, 1.0) + a3 * u;
      x += h * v + h * h / 6 * (g0 + 2 * gm);
      v += h / 6 * (g0 + 4 * gm + g1);
    }
    if (k >= samples - 200) peak = std::max(peak, std::abs(e));
  }
  return peak;
}

}  // namespace

TEST_CASE("loop margins of a delayed integrator: closed forms", "[control]") {
  // L = K e^(-j w d) / (j w): |L| = 1 at w = K, phase -90 - w d, -180 at w = pi / (2 d).
  const double k = 100, d = 1e-3;
  const auto m = sysid::ComputeLoopMargins(
      [&](double w) {
        return k * std::exp(std::complex<double>(0, -w * d)) / std::complex<double>(0, w);
      },
      1, 1e5);
  CHECK(m.crossover_rad_s == Approx(k).epsilon(1e-9));
  CHECK(m.phase_margin_deg == Approx(90 - k * d * 180 / kPi).epsilon(1e-9));
  CHECK(m.phase_crossover_rad_s == Approx(kPi / (2 * d)).epsilon(1e-9));
  CHECK(m.gain_margin == Approx(kPi / (2 * d * k)).epsilon(1e-9));
  CHECK(m.Stable());
  // No delay: the phase stays at -90 deg, so there is no phase crossover.
  const auto free =
      sysid::ComputeLoopMargins([&](double w) { return k / std::complex<double>(0, w); }, 1, 1e5);
  CHECK(free.phase_margin_deg == Approx(90).epsilon(1e-9));
  CHECK(std::isnan(free.gain_margin));
  CHECK(free.Stable());
}

TEST_CASE("the rough model's PI loop: the continuous limit's cubic", "[control]") {
  // With Ts -> 0 and tau = 0, L = (Kp + Ki/s) a3 / (s (s + a1)). |L| = 1 gives, in W = w^2,
  // W^3 + a1^2 W^2 - a3^2 Kp^2 W - a3^2 Ki^2 = 0 (one positive root), and
  // PM = atan(Kp w / Ki) - atan(w / a1).
  const sysid::FrictionModel m = Model(104.0154, 117.1441, 6, 0);
  sysid::PiOptions pi;  // the paper's gains
  pi.sample_time_s = 1e-7;
  for (int dir : {1, -1}) {
    const double a1 = dir > 0 ? m.a1p : m.a1n, a3 = m.a3, kp = pi.kp_v_per_m, ki = pi.ki_v_per_m_s;
    auto cubic = [&](double w2) {
      return w2 * w2 * w2 + a1 * a1 * w2 * w2 - a3 * a3 * kp * kp * w2 - a3 * a3 * ki * ki;
    };
    double lo = 1, hi = 1e8;  // cubic(lo) < 0 < cubic(hi)
    for (int i = 0; i < 200; ++i) (cubic(0.5 * (lo + hi)) < 0 ? lo : hi) = 0.5 * (lo + hi);
    const double wc = std::sqrt(lo);
    const auto r = sysid::RoughModelPiMargins(m, dir, pi);
    CHECK(r.crossover_rad_s == Approx(wc).epsilon(1e-6));
    CHECK(r.phase_margin_deg ==
          Approx((std::atan(kp * wc / ki) - std::atan(wc / a1)) * 180 / kPi).epsilon(1e-3));
  }
  // The hand calculation: 6 / (s (s + 104)) with the paper's gains crosses near 330 rad/s.
  CHECK(sysid::RoughModelPiMargins(m, 1, pi).crossover_rad_s == Approx(330).margin(5));
}

TEST_CASE("the rough model's gain margin: the sampled loop decays inside it, grows outside",
          "[control]") {
  const sysid::FrictionModel m = Model(104.0154, 117.1441, 6, 0);
  const sysid::PiOptions pi;  // the paper's gains at 1 kHz
  const auto r = sysid::RoughModelPiMargins(m, 1, pi);
  REQUIRE(r.gain_margin > 1);  // stable at the paper's gains, barely (about 1.2)
  INFO("gain margin " << r.gain_margin);
  // The ZOH as half a sample of delay is an approximation: 3 % either side is outside its error.
  CHECK(LateErrorPeak(m.a1p, m.a3, pi, 0.97 * r.gain_margin, 6000) < 1e-7);
  CHECK(LateErrorPeak(m.a1p, m.a3, pi, 1.03 * r.gain_margin, 6000) > 1e-5);
}

TEST_CASE("the rough model's gain margin with the delayed viscous term: the sampled loop",
          "[control]") {
  // tau = 3.5 ms (the paper's): the delay of the viscous term changes the loop, and the margin
  // must be that of x'' = -a1 x'(t - tau) + a3 u, simulated here with the delay.
  const sysid::FrictionModel m = Model(104.0154, 117.1441, 6, 0.0035);
  const sysid::PiOptions pi;
  const auto r = sysid::RoughModelPiMargins(m, 1, pi);
  REQUIRE(std::isfinite(r.gain_margin));
  INFO("gain margin " << r.gain_margin);
  // 3 % either side, as for tau = 0 (the ZOH's half-sample approximation).
  CHECK(LateErrorPeakDelayed(m.a1p, m.a3, m.tau_s, pi, 0.97 * r.gain_margin, 6000) < 1e-7);
  CHECK(LateErrorPeakDelayed(m.a1p, m.a3, m.tau_s, pi, 1.03 * r.gain_margin, 6000) > 1e-5);
}

TEST_CASE("loop margins: direction, delay and bad input", "[control]") {
  const sysid::PiOptions pi;
  // a1n is used backward: swapping a1p and a1n swaps the directions' margins exactly.
  const auto fwd = sysid::RoughModelPiMargins(Model(104, 117, 6, 0.0035), 1, pi);
  const auto back = sysid::RoughModelPiMargins(Model(117, 104, 6, 0.0035), -1, pi);
  CHECK(fwd.crossover_rad_s == back.crossover_rad_s);
  CHECK(fwd.phase_margin_deg == back.phase_margin_deg);
  // Every extra delay costs phase at the crossover: omega_c * delay.
  const auto no_tau = sysid::RoughModelPiMargins(Model(104, 117, 6, 0), 1, pi);
  const auto lag = sysid::RoughModelPiMargins(Model(104, 117, 6, 0), 1, pi, 3e-4);
  CHECK(lag.crossover_rad_s == Approx(no_tau.crossover_rad_s).epsilon(1e-9));
  CHECK(no_tau.phase_margin_deg - lag.phase_margin_deg ==
        Approx(no_tau.crossover_rad_s * 3e-4 * 180 / kPi).epsilon(1e-9));
  auto one = [](double) { return std::complex<double>(1, 0); };
  CHECK_THROWS_AS(sysid::ComputeLoopMargins(one, 0, 10), sysid::OptionsError);
  CHECK_THROWS_AS(sysid::ComputeLoopMargins(one, 10, 1), sysid::OptionsError);
  CHECK_THROWS_AS(sysid::ComputeLoopMargins(one, 1, 10, 8), sysid::OptionsError);
  CHECK_THROWS_AS(sysid::RoughModelPiMargins(Model(104, 117, 6, 0), 1, pi, -1e-3),
                  sysid::OptionsError);
  auto blows_up = [](double w) { return std::complex<double>(w > 5 ? NAN : 2.0, 0); };
  CHECK_THROWS_AS(sysid::ComputeLoopMargins(blows_up, 1, 10), sysid::NumericalError);
}

TEST_CASE("loop margins of a low-gain loop: the crossover below 0.1 rad/s, closed form",
          "[control]") {
  // P only, tau = 0: |L| = Kp a3 / (w |jw + a1|) (the hold's half sample is a pure delay), so
  // w_c^2 = (sqrt(a1^4 + 4 (Kp a3)^2) - a1^2) / 2 and the phase margin is
  // 90 - atan(w_c / a1) - w_c Ts / 2. Kp = 0.5 V/m puts w_c at 0.03 rad/s: a sweep from
  // 0.1 rad/s found no crossover and called this stable loop unstable.
  sysid::PiOptions pi;
  pi.kp_v_per_m = 0.5;
  pi.ki_v_per_m_s = 0;
  const double a1 = 100, a3 = 6, k = pi.kp_v_per_m * a3;
  const double wc = std::sqrt((std::sqrt(std::pow(a1, 4) + 4 * k * k) - a1 * a1) / 2);
  REQUIRE(wc < 0.1);
  const auto m = sysid::RoughModelPiMargins(Model(a1, a1, a3, 0), 1, pi);
  CHECK(m.crossover_rad_s == Approx(wc).epsilon(1e-9));
  CHECK(m.phase_margin_deg ==
        Approx(90 - (std::atan(wc / a1) + wc * pi.sample_time_s / 2) * 180 / kPi).epsilon(1e-9));
  CHECK(m.Stable());
  // No loop at all is an error, not a verdict.
  pi.kp_v_per_m = 0;
  CHECK_THROWS_WITH(sysid::RoughModelPiMargins(Model(a1, a1, a3, 0), 1, pi),
                    Catch::Contains("open loop"));
}

TEST_CASE("sysid margins: table, JSON and bad input", "[control][cli]") {
  sysid::test::TempDir dir;
  const std::string model = dir / "m.json";
  sysid::WriteModel(model, sysid::FrictionModel::Paper());  // tau = 3.5 ms
  const auto r = sysid::test::RunCli({"margins", "--model", model, "--json"});
  REQUIRE(r.exit_code == 0);
  const auto j = nlohmann::json::parse(r.out);
  const auto lib = sysid::AnalyzePiMargins(sysid::FrictionModel::Paper(), sysid::PiOptions{});
  REQUIRE(j["directions"].size() == 2);
  CHECK(j["directions"][0]["direction"] == "forward");
  CHECK(j["directions"][0]["phase_margin_deg"].get<double>() == lib.forward().phase_margin_deg);
  CHECK(j["directions"][1]["gain_margin"].get<double>() == lib.backward().gain_margin);
  CHECK(j["directions"][0]["stable"] == lib.forward().Stable());
  CHECK(j["kp_v_per_m"].get<double>() == 19000);
  // Lower gains at a slower rate: the flags reach the library.
  const auto slow = sysid::test::RunCli(
      {"margins", "--model", model, "--kp", "3000", "--ki", "104100", "--rate", "500", "--json"});
  REQUIRE(slow.exit_code == 0);
  CHECK(nlohmann::json::parse(slow.out)["sample_time_s"].get<double>() == Approx(2e-3));
  const auto table = sysid::test::RunCli({"margins", "--model", model});
  CHECK(table.exit_code == 0);
  CHECK_THAT(table.out, Catch::Contains("phase margin [deg]"));
  CHECK(sysid::test::RunCli({"margins", "--model", model, "--rate", "0"}).exit_code == 1);
  CHECK(sysid::test::RunCli({"margins", "--model", model, "--kp", "-5"}).exit_code == 1);
  // NaN compares false with both bounds: the flag's own range still refuses it, by name.
  for (const char* flag : {"--rate", "--extra-delay"}) {
    const auto nan = sysid::test::RunCli({"margins", "--model", model, flag, "nan"});
    CHECK(nan.exit_code == 1);
    CHECK(nan.out.empty());
    CHECK(nan.err.find(std::string(flag) + ": Value nan is not a finite number") !=
          std::string::npos);
  }
  sysid::test::WriteText(dir / "bad.json",
                         "{\"a1p\": 104, \"a1n\": 117, \"a2p\": 3.1, \"a2n\": 6.8,\n"
                         " \"a3\": \"six\", \"tau\": 0}");
  const auto bad = sysid::test::RunCli({"margins", "--model", dir / "bad.json"});
  CHECK(bad.exit_code == 2);
  CHECK_THAT(bad.err, Catch::Contains("bad.json:2:") && Catch::Contains("a3"));
}

TEST_CASE("margins JSON: the published keys in order, the derived ones from the margins",
          "[control][json]") {
  sysid::PiMarginsReport r =
      sysid::AnalyzePiMargins(sysid::FrictionModel::Paper(), sysid::PiOptions{});
  r.directions[1].margins = sysid::LoopMargins{};  // no crossing found
  const auto j = nlohmann::ordered_json::parse(sysid::ToJson(r));
  std::vector<std::string> keys;
  for (auto it = j.begin(); it != j.end(); ++it) keys.push_back(it.key());
  CHECK(keys == std::vector<std::string>{"kp_v_per_m", "ki_v_per_m_s", "sample_time_s",
                                         "extra_delay_s", "tau_s", "a3_mps2_per_v",
                                         "directions"});
  REQUIRE(j["directions"].size() == 2);
  const auto& f = j["directions"][0];
  keys.clear();
  for (auto it = f.begin(); it != f.end(); ++it) keys.push_back(it.key());
  CHECK(keys == std::vector<std::string>{"direction", "a1_per_s", "crossover_rad_s",
                                         "crossover_hz", "phase_margin_deg",
                                         "phase_crossover_rad_s", "gain_margin",
                                         "gain_margin_db", "stable"});
  // The derived keys by their definitions, to the last bits of the division and the log.
  const sysid::LoopMargins& m = r.forward();
  REQUIRE(std::isfinite(m.crossover_rad_s));
  CHECK(f["crossover_hz"].get<double>() ==
        Approx(m.crossover_rad_s / (2 * kPi)).epsilon(1e-15));
  CHECK(f["gain_margin_db"].get<double>() ==
        Approx(20 * std::log10(m.gain_margin)).epsilon(1e-15));
  CHECK(f["phase_margin_deg"].get<double>() == m.phase_margin_deg);
  CHECK(f["a1_per_s"].get<double>() == sysid::FrictionModel::Paper().a1p);
  const auto& b = j["directions"][1];
  for (const char* key : {"crossover_rad_s", "crossover_hz", "phase_margin_deg",
                          "phase_crossover_rad_s", "gain_margin", "gain_margin_db"})
    CHECK(b[key].is_null());
  CHECK(b["stable"] == false);
}
