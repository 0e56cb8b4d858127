// Output-error refinement where the steady-state method cannot work: pulses too short to settle.
#include <catch2/catch.hpp>
#include <cmath>

#include "identify/simulated_recording.hpp"
#include "sysid/error.hpp"
#include "sysid/delay.hpp"

using sysid::test::MakeModel;

TEST_CASE("output-error refinement recovers a stage whose pulses never settle",
          "[identify][refine][sim]") {
  // Time constant 1/a1 = 40-50 ms and 0.1 s pulses: the plateau window still rises.
  const auto truth = MakeModel(20.0, 25.0, 1.0, 1.5, 4.0, 0.002);
  sysid::PulseTrainSpec spec;
  spec.amplitudes_v = {0.8, -0.9, 1.2, -1.3, 1.6, -1.7};
  spec.on_s = 0.1;
  spec.off_s = 0.25;
  spec.repeats = 1;
  spec.start_s = 0.05;
  sysid::test::RigSampling s;
  s.seed = 77;
  const auto rec =
      sysid::test::RigRecording(truth, sysid::MakePulseTrain(spec), spec.duration_s() + 0.05, s);
  // The paper's method refuses these pulses...
  sysid::PulseIdentificationOptions po;
  po.fit.a3 = truth.a3;
  po.detection.min_duration_s = 0.05;
  CHECK_THROWS_WITH(sysid::IdentifyFromPulses({rec}, po), Catch::Contains("never settles"));
  // ...and, forced to accept them, is biased (the plateau is below the steady state).
  po.plateau.settle_tolerance = 10;
  const auto steady = sysid::IdentifyFromPulses({rec}, po);
  const double steady_error = std::abs(steady.model.a1p / truth.a1p - 1);
  CHECK(steady_error > 0.03);
  sysid::RefineOptions ro;
  ro.detection.min_duration_s = 0.05;
  const auto r = sysid::RefineOutputError(steady.model, {rec}, ro);
  INFO(r.BriefReport());
  CHECK(r.final_cost < 0.1 * r.initial_cost);
  // 1 % / 3 % as the pulse acceptance; a3 and tau are refined too (0.1 ms on tau).
  CHECK(r.model.a1p == Approx(truth.a1p).epsilon(0.01));
  CHECK(r.model.a1n == Approx(truth.a1n).epsilon(0.01));
  CHECK(r.model.a2p == Approx(truth.a2p).epsilon(0.03));
  CHECK(r.model.a2n == Approx(truth.a2n).epsilon(0.03));
  CHECK(r.model.a3 == Approx(truth.a3).epsilon(0.01));
  CHECK(r.model.tau_s == Approx(truth.tau_s).margin(1e-4));
  REQUIRE(r.std_error.size() == 6);
  for (Eigen::Index i = 0; i < 6; ++i) CHECK(std::isfinite(r.std_error[i]));
  // A budget of 2: two iterations reported, as Ceres' own message counts them (the start,
  // iteration 0, was counted as a third).
  ro.max_iterations = 2;
  const auto short_run = sysid::RefineOutputError(steady.model, {rec}, ro);
  CHECK(short_run.termination == sysid::Termination::kBudgetExhausted);
  CHECK(short_run.iterations == 2);
  CHECK_THAT(short_run.message, Catch::Contains("Number of iterations: 2."));
}
