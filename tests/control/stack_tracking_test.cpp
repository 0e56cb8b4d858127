// PI tracking on the virtual piezo stack: the loop without hysteresis against the closed form
// of the linear loop, the stack's references, its PI gains' margins, and a PI hysteresis model
// fitted to the stack's own recordings lowering the tracking error as feedforward.
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "sysid/control.hpp"
#include "sysid/error.hpp"
#include "sysid/hysteresis.hpp"
#include "sysid/stack.hpp"

using sysid::FeedforwardScheme;

namespace {

// The stack with its hysteresis switched off (a pure gain p0), no creep, an ideal rig.
sysid::StackParameters LinearStack() {
  sysid::StackParameters p = sysid::StackParameters::Default();
  for (auto& w : p.hysteresis.weights_m_per_v) w = 0;
  for (auto& q : p.hysteresis.rate_weights_m_s_per_v2) q = 0;
  p.creep = {};
  p.rig.dac_bits = 32;
  p.rig.voltage_min_v = -1e4;
  p.rig.voltage_max_v = 1e4;
  p.rig.sensor_noise_m = 0;
  p.rig.sensor_resolution_m = 1e-18;
  return p;
}

// x'' + 2 zeta wn x' + wn^2 x = wn^2 f over one sample with f held: the closed form
// x(t) = f + e^(-zeta wn t) (A cos wd t + B sin wd t), A = x0 - f, B = (v0 + zeta wn A) / wd.
void Propagate(double wn, double zeta, double f, double h, double& x, double& v) {
  const double wd = wn * std::sqrt(1 - zeta * zeta), a = x - f, b = (v + zeta * wn * a) / wd;
  const double e = std::exp(-zeta * wn * h), c = std::cos(wd * h), s = std::sin(wd * h);
  x = f + e * (a * c + b * s);
  v = e * (-zeta * wn * (a * c + b * s) + wd * (-a * s + b * c));
}

}  // namespace

TEST_CASE("stack loop without hysteresis: the closed form of the linear PI loop",
          "[control][stack]") {
  const sysid::StackParameters p = LinearStack();
  const sysid::PiOptions pi = sysid::StackPiOptions(sysid::StackParameters::Default());
  const double ts = p.sample_time_s(), step = 10e-6;
  const int n = 3000;  // 0.3 s: many closed-loop time constants
  sysid::PositionReference ref;
  ref.t_s = Eigen::VectorXd::LinSpaced(n, 0, (n - 1) * ts);
  ref.x_m = Eigen::VectorXd::Constant(n, step);
  ref.v_mps = Eigen::VectorXd::Zero(n);
  ref.a_mps2 = Eigen::VectorXd::Zero(n);
  const auto runs = sysid::TrackStackSchemes(p, 1, ref, pi, {FeedforwardScheme::kNone}, {});
  const sysid::TrackingResult& r = runs[0].result;
  // The same loop by hand: e_k = r - x_k, I_k = I_(k-1) + Ts e_k, u_k = Kp e_k + Ki I_k, and
  // the exact response of the mechanics to the held p0 u_k.
  const double wn = 2 * M_PI * p.mechanics.resonance_hz, zeta = p.mechanics.damping_ratio;
  double x = 0, v = 0, integral = 0, worst = 0;
  for (int k = 0; k < n; ++k) {
    const double e = step - x;
    worst = std::max(worst, std::abs(r.x_m[k] - x));
    integral += ts * e;
    const double u = pi.kp_v_per_m * e + pi.ki_v_per_m_s * integral;
    CHECK(std::abs(r.u_v[k] - u) <= 1e-6 * (1 + std::abs(u)));
    Propagate(wn, zeta, p.hysteresis.linear_gain_m_per_v * u, ts, x, v);
  }
  INFO("max |x_loop - x_closed_form| = " << worst << " m");
  CHECK(worst <= 1e-6 * step);
  // Integral action: no steady-state error.
  CHECK(std::abs(r.e_m[n - 1]) <= 1e-6 * step);
  CHECK(r.saturated_samples == 0);
}

TEST_CASE("stack PI gains: stable with the stated margins on the default stack",
          "[control][stack]") {
  const auto stack = sysid::StackParameters::Default();
  const sysid::PiOptions pi = sysid::StackPiOptions(stack);
  const sysid::LoopMargins m = sysid::StackPiMargins(stack, pi);
  INFO("gain margin " << m.gain_margin << ", phase margin " << m.phase_margin_deg
                      << " deg, crossover " << m.crossover_rad_s << " rad/s");
  CHECK(m.Stable());
  CHECK(m.gain_margin > 2);  // 2.23 (7 dB): the resonance peak, Kp adding to Ki / w there
  CHECK(m.phase_margin_deg > 60);
  // The integral path alone crosses over at Ki g = 2 zeta wn / 3.
  CHECK(m.crossover_rad_s == Approx(2 * 0.05 * 2 * M_PI * 1000 / 3).epsilon(0.15));
  // Ten times the integral gain puts the resonance peak above 1: the margins say unstable.
  sysid::PiOptions hot = pi;
  hot.ki_v_per_m_s *= 10;
  CHECK_FALSE(sysid::StackPiMargins(stack, hot).Stable());
}

TEST_CASE("stack references: sine and triangle from 0 to the stroke", "[control][stack]") {
  sysid::StackReferenceOptions o;
  o.frequency_hz = 5;
  o.stroke_m = 10e-6;
  o.cycles = 2;
  o.sample_rate_hz = 1000;
  for (auto w : {sysid::StackWaveform::kSine, sysid::StackWaveform::kTriangle}) {
    o.waveform = w;
    const auto r = sysid::MakeStackReference(o);
    REQUIRE(r.x_m.size() == 401);
    CHECK(r.x_m[0] == 0);
    CHECK(r.x_m[100] == Approx(10e-6));  // the top at half a period
    CHECK(std::abs(r.x_m[200]) < 1e-18);
    CHECK(r.x_m.maxCoeff() == Approx(10e-6));
  }
  CHECK(sysid::ParseStackWaveform("triangle") == sysid::StackWaveform::kTriangle);
  CHECK_THROWS_AS(sysid::ParseStackWaveform("square"), sysid::OptionsError);
  o.frequency_hz = 1e-6;
  CHECK_THROWS_WITH(sysid::MakeStackReference(o), Catch::Contains("samples"));
  // 20 samples a period at least (1 MHz at 1 kHz was a one-sample trace with 0 error).
  o.frequency_hz = 50;
  CHECK_NOTHROW(sysid::MakeStackReference(o));
  o.frequency_hz = 51;
  CHECK_THROWS_WITH(sysid::MakeStackReference(o), Catch::Contains("sample_rate_hz / 20 = 50 Hz"));
}

TEST_CASE("stack: the stage's schemes are refused, the hysteresis scheme needs its model",
          "[control][stack]") {
  const auto stack = sysid::StackParameters::Default();
  sysid::StackReferenceOptions o;
  o.cycles = 1;
  const auto ref = sysid::MakeStackReference(o);
  CHECK_THROWS_AS(sysid::TrackStackSchemes(stack, 1, ref, {}, {FeedforwardScheme::kAnalytic}, {}),
                  sysid::OptionsError);
  CHECK_THROWS_AS(sysid::TrackStackSchemes(stack, 1, ref, {}, {FeedforwardScheme::kHysteresis}, {}),
                  sysid::OptionsError);
}

TEST_CASE("stack: a PI model fitted to the stack's own recordings beats PI alone as feedforward",
          "[control][stack]") {
  const auto stack = sysid::StackParameters::Default();
  const sysid::PiOptions pi = sysid::StackPiOptions(stack);
  // Training: PI alone tracking sines at three rates, a little beyond the test's stroke.
  std::vector<sysid::Recording> training;
  for (double f : {2.0, 10.0, 40.0}) {
    sysid::StackReferenceOptions o;
    o.frequency_hz = f;
    o.stroke_m = 22e-6;
    o.cycles = 2;
    o.sample_rate_hz = stack.rig.control_rate_hz;
    const auto runs = sysid::TrackStackSchemes(stack, 2, sysid::MakeStackReference(o), pi,
                                               {FeedforwardScheme::kNone}, {});
    training.push_back(sysid::TrackingRecording(runs[0].result, "none"));
  }
  sysid::PiFitOptions fit;
  fit.operators = 10;
  const auto model = sysid::FitPrandtlIshlinskii(training, fit);
  // Test: a triangle at another rate.
  sysid::StackReferenceOptions o;
  o.waveform = sysid::StackWaveform::kTriangle;
  o.frequency_hz = 5;
  o.stroke_m = 20e-6;
  o.cycles = 2;
  o.sample_rate_hz = stack.rig.control_rate_hz;
  const auto runs = sysid::TrackStackSchemes(
      stack, 3, sysid::MakeStackReference(o), pi,
      {FeedforwardScheme::kNone, FeedforwardScheme::kHysteresis}, {nullptr, nullptr, model.get()});
  const double none = runs[0].result.rms_error_m, ff = runs[1].result.rms_error_m;
  INFO("RMS error: PI alone " << none << " m, PI + hysteresis inverse " << ff << " m");
  CHECK(ff < 0.5 * none);
}
