// The velocity-source plant's equations written out again, independently of the CVODE stage:
// the tiny-step RK4 reference of tests/stage (plant_test.cpp, loop_rate_test.cpp).
#ifndef SYSID_TESTS_STAGE_VELOCITY_SOURCE_REFERENCE_HPP_
#define SYSID_TESTS_STAGE_VELOCITY_SOURCE_REFERENCE_HPP_

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "sysid/stage.hpp"

namespace sysid::test {

// The velocity-source stage on a 1 kHz loop with a 0.3 ms driver lag (preset "virtual-1khz",
// the default before the loop-rate candidate C): the mechanism tests that replay 1 ms samples
// (1000 reference steps of 1 us each, 2000-sample command sequences) were written for it.
inline sysid::StageParameters Stage1kHz() {
  return sysid::StageParameters::Preset("virtual-1khz");
}

// The velocity-source equations of stage.hpp written out again: RK4 with h = 1 us while
// sliding; the Karnopp switches are checked after every step (a sign change of v ends the
// slide: stick when |p v_f| <= Fs, else reverse; stuck, it breaks away once |p v_f| > Fs).
// With frictional memory (T_m > 0) the friction is g(s), T_m s' = |v| - s (s fades at rest).
// With a thrust limit L > 0 the droop y = p (v_f - v) pushes with L tanh(y / L).
struct VelocitySourceReference {
  sysid::StageParameters p;
  double x = 0, v = 0, w = 0, s = 0;
  bool stuck = true;
  double d = 1;  // sliding direction
  const sysid::VelocitySourcePlant& vs() const { return p.velocity_source(); }
  double Thrust(double y) const {
    const double l = vs().motor.thrust_limit_mps2;
    return l > 0 ? l * std::tanh(y / l) : y;
  }
  double Accel(double vv, double ww, double ss) const {
    const double slip = vs().rail.memory_time_s > 0 ? ss : std::abs(vv);
    return Thrust(vs().motor.pole_per_s * (vs().NoLoadSpeed(ww) - vv)) -
           d * vs().rail.Sliding(slip);
  }
  double Memory(double vv, double ss) const {
    return vs().rail.memory_time_s > 0 ? (std::abs(vv) - ss) / vs().rail.memory_time_s : 0.0;
  }
  void Step(double u_drive, double h) {
    const double t = p.driver.lag_time_constant_s;
    auto dw = [&](double ww) { return (u_drive - ww) / t; };
    if (stuck) {
      const double k1 = dw(w), k2 = dw(w + h / 2 * k1), k3 = dw(w + h / 2 * k2),
                   k4 = dw(w + h * k3);
      w += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
      const double m1 = Memory(0, s), m2 = Memory(0, s + h / 2 * m1),
                   m3 = Memory(0, s + h / 2 * m2), m4 = Memory(0, s + h * m3);
      s += h / 6 * (m1 + 2 * m2 + 2 * m3 + m4);
      const double vf = vs().NoLoadSpeed(w);
      if (std::abs(Thrust(vs().motor.pole_per_s * vf)) > vs().rail.static_mps2) {
        stuck = false;
        d = vf > 0 ? 1 : -1;
      }
      return;
    }
    const double x1 = v, v1 = Accel(v, w, s), w1 = dw(w), s1 = Memory(v, s);
    const double x2 = v + h / 2 * v1, v2 = Accel(v + h / 2 * v1, w + h / 2 * w1, s + h / 2 * s1),
                 w2 = dw(w + h / 2 * w1), s2 = Memory(v + h / 2 * v1, s + h / 2 * s1);
    const double x3 = v + h / 2 * v2, v3 = Accel(v + h / 2 * v2, w + h / 2 * w2, s + h / 2 * s2),
                 w3 = dw(w + h / 2 * w2), s3 = Memory(v + h / 2 * v2, s + h / 2 * s2);
    const double x4 = v + h * v3, v4 = Accel(v + h * v3, w + h * w3, s + h * s3),
                 w4 = dw(w + h * w3), s4 = Memory(v + h * v3, s + h * s3);
    x += h / 6 * (x1 + 2 * x2 + 2 * x3 + x4);
    v += h / 6 * (v1 + 2 * v2 + 2 * v3 + v4);
    w += h / 6 * (w1 + 2 * w2 + 2 * w3 + w4);
    s += h / 6 * (s1 + 2 * s2 + 2 * s3 + s4);
    if (v * d < 0) {  // came to rest within the step
      v = 0;
      const double vf = vs().NoLoadSpeed(w);
      if (std::abs(Thrust(vs().motor.pole_per_s * vf)) <= vs().rail.static_mps2)
        stuck = true;
      else
        d = vf > 0 ? 1 : -1;
    }
  }
};

// Drives `stage` with the commands u and, after each sample, `advance_reference(k)` (which steps
// `ref` over sample k); checks that both stick and slide alike after the first 20 samples, that
// the run slides enough to test something, and the plant test's bounds (6e-8 m, 5e-5 m/s).
template <class AdvanceReference>
void CheckAgainstReference(sysid::VirtualStage& stage, const VelocitySourceReference& ref,
                           const std::vector<double>& u, AdvanceReference advance_reference) {
  double worst_x = 0, worst_v = 0;
  int slides = 0;
  for (size_t k = 0; k < u.size(); ++k) {
    stage.Step(u[k]);
    advance_reference(k);
    const sysid::StageState s = stage.state();
    worst_x = std::max(worst_x, std::abs(s.x_m - ref.x));
    worst_v = std::max(worst_v, std::abs(s.v_mps - ref.v));
    if (k > 20) CHECK(s.stuck == ref.stuck);
    slides += s.stuck ? 0 : 1;
  }
  INFO("max |dx| " << worst_x << " m, max |dv| " << worst_v << " m/s, sliding samples " << slides);
  CHECK(slides > 300);
  CHECK(std::abs(ref.x) + worst_x > 1e-3);
  CHECK(worst_x < 6e-8);
  CHECK(worst_v < 5e-5);
}

}  // namespace sysid::test

#endif  // SYSID_TESTS_STAGE_VELOCITY_SOURCE_REFERENCE_HPP_
