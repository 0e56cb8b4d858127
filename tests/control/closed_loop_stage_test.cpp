// PI tracking on the virtual stage: paper's gains, with and without a feedforward.
#include <catch2/catch.hpp>
#include <cmath>

#include "sysid/control.hpp"
#include "sysid/stage.hpp"

namespace {

// The stage's own steady-state inverse, by bisection on SteadyVelocity: the voltage [V] whose
// steady velocity is the reference's.
auto SteadyStateInverse(const sysid::StageParameters& p) {
  return [&p](const sysid::ReferenceSample& r) {
    const double v = r.v_mps;
    if (v == 0) return 0.0;
    double lo = 0, hi = 10;
    for (int i = 0; i < 60; ++i) {
      const double mid = 0.5 * (lo + hi);
      (std::abs(p.SteadyVelocity(v > 0 ? mid : -mid)) < std::abs(v) ? lo : hi) = mid;
    }
    return v > 0 ? hi : -hi;
  };
}

}  // namespace

TEST_CASE("PI with the actuator-delay gains tracks the 0.5 Hz profile, feedforward helps",
          "[control][stage]") {
  const sysid::StageParameters p = sysid::StageParameters::ActuatorDelay();
  sysid::SmoothProfileOptions o;
  o.frequency_hz = 0.5;
  o.cycles = 1;
  const auto ref = sysid::MakeSmoothProfile(o);
  sysid::VirtualStage plain(p, 7);
  const auto pi_only = sysid::RunClosedLoop(plain, ref, sysid::PiOptions::ForActuatorDelayStage());
  INFO("PI alone: " << pi_only.BriefReport());
  // Stable and tracking. Regression bound, not a reference: the run is seeded and deterministic
  // (measured 0.227 mm); 0.25 mm leaves 10 % for rounding differences between platforms, so a
  // loop that tracks 10 % worse fails (a limit cycle or a wrong gain gives millimetres).
  CHECK(pi_only.max_error_m < 0.25e-3);
  CHECK(pi_only.saturated_samples == 0);
  // The stage's own steady-state inverse (bisection on SteadyVelocity) as a feedforward.
  const auto inverse = SteadyStateInverse(p);
  sysid::VirtualStage ff_stage(p, 7);
  const auto with_ff =
      sysid::RunClosedLoop(ff_stage, ref, sysid::PiOptions::ForActuatorDelayStage(), inverse);
  INFO("PI + inverse feedforward: " << with_ff.BriefReport());
  CHECK(with_ff.rms_error_m < pi_only.rms_error_m);
}

TEST_CASE("the paper's gains track the 0.5 Hz profile on the default stage, feedforward helps",
          "[control][stage]") {
  const sysid::StageParameters p = sysid::StageParameters::Default();
  sysid::SmoothProfileOptions o;
  o.frequency_hz = 0.5;
  o.cycles = 1;
  const auto ref = sysid::MakeStageProfile(p, o);  // at the stage's 10 kHz control rate
  sysid::VirtualStage plain(p, 7);
  const auto pi_only = sysid::RunClosedLoop(plain, ref);  // Kp 19000 V/m, Ki 660000 V/(m s)
  INFO("PI alone: " << pi_only.BriefReport());
  // Stable: no clipping, and no worse than the paper's own PI-alone error at 0.5 Hz, 0.10651 mm
  // (its tracking table, PaperFacts::TrackingMaxErrorM; the stage is the paper's stage's twin;
  // measured 0.0897 mm at the 10 kHz loop, 0.091 mm at 1 kHz).
  CHECK(pi_only.max_error_m < 0.10651e-3);
  CHECK(pi_only.saturated_samples == 0);
  CHECK(pi_only.max_abs_u_v < 5.0);
  // The stage's own steady-state inverse as a feedforward.
  const auto inverse = SteadyStateInverse(p);
  sysid::VirtualStage ff_stage(p, 7);
  const auto with_ff = sysid::RunClosedLoop(ff_stage, ref, sysid::PiOptions{}, inverse);
  INFO("PI + inverse feedforward: " << with_ff.BriefReport());
  CHECK(with_ff.max_error_m < pi_only.max_error_m);
}
