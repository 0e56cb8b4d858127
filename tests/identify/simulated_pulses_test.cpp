// Recover-the-truth tests on simulated pulse recordings (needs sysid::Simulate).
#include <catch2/catch.hpp>
#include <cmath>

#include "identify/simulated_recording.hpp"
#include "sysid/delay.hpp"
#include "sysid/error.hpp"
#include "sysid/identify.hpp"

using sysid::test::MakeModel;
using sysid::test::RigRecording;
using sysid::test::RigSampling;

namespace {

struct StageCase {
  sysid::FrictionModel truth;
  std::vector<double> amplitudes_v;
};

const StageCase kStages[] = {
    {sysid::FrictionModel::Paper(), {1.3, -1.8, 1.5, -2.0, 1.6, -2.1, 1.7, -2.3, 2.0, -2.5}},
    {MakeModel(60.0, 80.0, 2.0, 4.0, 5.0, 0.002), {1.0, -1.2, 1.4, -1.6, 1.8, -2.0}},
    {MakeModel(150.0, 130.0, 5.0, 3.0, 8.0, 0.001), {1.0, -0.8, 1.5, -1.2, 2.0, -1.6}},
};

sysid::Recording PulseRecording(const StageCase& c, unsigned seed, double on_s = 0.4) {
  sysid::PulseTrainSpec spec;
  spec.amplitudes_v = c.amplitudes_v;
  spec.on_s = on_s;
  spec.off_s = 0.3;
  spec.repeats = 1;
  spec.start_s = 0.1;
  const auto input = sysid::MakePulseTrain(spec);
  RigSampling s;
  s.seed = seed;
  return RigRecording(c.truth, input, spec.duration_s() + 0.1, s);
}

}  // namespace

TEST_CASE("pulse least squares recovers several simulated stages", "[identify][pulse][sim]") {
  unsigned seed = 100;
  for (const auto& c : kStages) {
    const auto rec = PulseRecording(c, seed++);
    sysid::PulseIdentificationOptions o;
    o.fit.a3 = c.truth.a3;
    const auto r = sysid::IdentifyFromPulses({rec}, o);
    INFO(r.BriefReport());
    REQUIRE(r.pulses.size() == c.amplitudes_v.size());
    for (const auto& p : r.pulses) {
      INFO(p.reason);
      CHECK(p.usable());
      CHECK(p.pulse.duration_s == Approx(0.4).margin(1.5e-3));  // one sample of 1 ms
    }
    // The acceptance bounds: a1 within 1 %, a2 within 3 %.
    CHECK(r.model.a1p == Approx(c.truth.a1p).epsilon(0.01));
    CHECK(r.model.a1n == Approx(c.truth.a1n).epsilon(0.01));
    CHECK(r.model.a2p == Approx(c.truth.a2p).epsilon(0.03));
    CHECK(r.model.a2n == Approx(c.truth.a2n).epsilon(0.03));
  }
}

TEST_CASE("unsettled, stuck and one-sided pulse records give the specified errors",
          "[identify][pulse][sim][errors]") {
  // A slow stage (time constant 1/a1 = 0.2 s) never settles within 0.4 s pulses.
  const StageCase slow{MakeModel(5.0, 5.0, 0.1, 0.1, 1.0, 0.0), {0.3, -0.3, 0.5, -0.5}};
  const auto rec = PulseRecording(slow, 7);
  const auto pulses = sysid::DetectPulses(rec.column("t"), rec.column("u"));
  const auto est = sysid::EstimatePlateaus(sysid::ExtractMotion(rec), pulses);
  REQUIRE(est.size() == 4);
  for (const auto& e : est) {
    CHECK(e.status == sysid::PulseStatus::kUnsettled);
    CHECK_THAT(e.reason, Catch::Contains("never settles"));
  }
  CHECK_THROWS_AS(sysid::IdentifyFromPulses({rec}), sysid::NumericalError);
  // Below breakaway (a3 u < a2) the stage never moves.
  const StageCase stuck{MakeModel(100.0, 100.0, 5.0, 5.0, 6.0, 0.0), {0.5, -0.5, 1.5, -1.5}};
  const auto est2 =
      sysid::EstimatePlateaus(sysid::ExtractMotion(PulseRecording(stuck, 8)),
                              sysid::DetectPulses(PulseRecording(stuck, 8).column("t"),
                                                  PulseRecording(stuck, 8).column("u")));
  REQUIRE(est2.size() == 4);
  CHECK(est2[0].status == sysid::PulseStatus::kStuck);
  CHECK(est2[1].status == sysid::PulseStatus::kStuck);
  CHECK(est2[2].usable());
  // Positive pulses only: exit-3 error naming a1n, a2n.
  const StageCase pos{sysid::FrictionModel::Paper(), {1.3, 1.6, 2.0}};
  CHECK_THROWS_WITH(sysid::IdentifyFromPulses({PulseRecording(pos, 9)}),
                    Catch::Contains("a1n, a2n: no negative pulses"));
}

TEST_CASE("delay tuning recovers tau within 0.1 ms from rig-like recordings",
          "[identify][delay][sim]") {
  unsigned seed = 200;
  for (const auto& c : {kStages[0], kStages[1]}) {
    const auto rec = PulseRecording(c, seed++);
    sysid::FrictionModel start = c.truth;
    start.tau_s = 0;
    sysid::DelayTuningOptions o;
    o.tau_max_s = 0.01;
    const auto r = sysid::TuneDelay(start, {rec}, o);
    INFO(r.BriefReport());
    CHECK(r.tau_s == Approx(c.truth.tau_s).margin(1e-4));  // the 0.1 ms
    CHECK(r.model.tau_s == r.tau_s);
    CHECK(r.evaluations <= o.max_evaluations);
    CHECK(r.curve.size() == static_cast<size_t>(r.evaluations));
    // One piece per pulse (cut at its start, at rest) plus the rest before the first pulse.
    CHECK(r.segments == static_cast<int>(c.amplitudes_v.size()) + 1);
  }
}

TEST_CASE("delay tuning accepts a measured velocity column", "[identify][delay][sim]") {
  const auto& c = kStages[0];
  const auto rec = PulseRecording(c, 300);
  // Velocity measured by the rig: the central difference of x, stored as column v_meas.
  sysid::Recording vrec;
  vrec.source = "v-only";
  vrec.names = {"t", "u", "v_meas"};
  vrec.data.resize(rec.rows(), 3);
  vrec.data.col(0) = rec.column("t");
  vrec.data.col(1) = rec.column("u");
  vrec.data.col(2) = sysid::CentralDifference(rec.column("x"), 1e-3);
  sysid::DelayTuningOptions o;
  o.motion.velocity_column = "v_meas";
  o.tau_max_s = 0.01;
  const auto r = sysid::TuneDelay(c.truth, {vrec}, o);
  CHECK(r.tau_s == Approx(c.truth.tau_s).margin(1e-4));  // the 0.1 ms
}

TEST_CASE("delay tuning says when the recordings do not determine tau", "[identify][delay][sim]") {
  // u = 0 throughout: the stage and the model rest at every tau, the cost is 0 everywhere, and
  // the search used to report its stopping point as "converged".
  const auto& c = kStages[0];
  sysid::Recording rest = PulseRecording(c, 301);
  rest.data.col(1).setZero();  // u [V]
  rest.data.col(2).setZero();  // x [m]
  sysid::DelayTuningOptions o;
  o.tau_max_s = 0.01;
  CHECK_THROWS_AS(sysid::TuneDelay(c.truth, {rest}, o), sysid::NumericalError);
  CHECK_THROWS_WITH(sysid::TuneDelay(c.truth, {rest}, o),
                    Catch::Contains("do not determine tau"));
  // The moving recording next to it is determined (the reference above).
  CHECK_NOTHROW(sysid::TuneDelay(c.truth, {PulseRecording(c, 301)}, o));
}
