// The drive's rate-dependent, asymmetric hysteresis (stage.hpp, DriveHysteresis) against the
// hysteresis module's own operators driven by the same command sequence, and the stage with it
// against the tiny-step RK4 reference replaying the effective voltage.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <string>
#include <vector>

#include "sysid/error.hpp"
#include "sysid/hysteresis.hpp"
#include "sysid/stage.hpp"
#include "drive_reference.hpp"
#include "velocity_source_reference.hpp"

namespace {

using sysid::test::Ceramic;
using sysid::test::Commands;
using sysid::test::Reference;
using sysid::test::Stage1kHz;
using sysid::test::VelocitySourceReference;

// The stage's effective voltage in each sample, recovered from its lag state: over a held
// sample, u_d(t1) = u_h + (u_d(t0) - u_h) e^(-Ts/T_l).
std::vector<double> StageEffective(const sysid::StageParameters& p, const std::vector<double>& u) {
  sysid::VirtualStage stage(p, 1);
  const double e = std::exp(-p.sample_time_s() / p.driver.lag_time_constant_s);
  std::vector<double> out;
  double w0 = stage.state().w_v;
  for (double x : u) {
    stage.Step(x);
    const double w1 = stage.state().w_v;
    out.push_back((w1 - e * w0) / (1 - e));
    w0 = w1;
  }
  return out;
}

sysid::StageParameters Stage(const sysid::DriveHysteresis& h) {
  sysid::StageParameters p = Stage1kHz();
  p.rig.position_noise_m = 0;
  p.SetDriveHysteresis(h);
  return p;
}

double MaxDiff(const std::vector<double>& a, const std::vector<double>& b) {
  double worst = 0;
  for (size_t k = 0; k < a.size(); ++k) worst = std::max(worst, std::abs(a[k] - b[k]));
  return worst;
}

}  // namespace

TEST_CASE("drive hysteresis: symmetric and rate-free, it is the module's classical PI model",
          "[stage][hysteresis]") {
  const sysid::DriveHysteresis h = Ceramic(0.0, 0.0, 0.0);
  const sysid::StageParameters p = Stage(h);
  const std::vector<double> u = Commands(2000);
  // y = (1 - sum w) u + sum w_i F_ri[u]: a PI model with p0 = 1 - sum w, no offset.
  sysid::PiParameters pi;
  pi.thresholds = h.thresholds_v;
  pi.weights = h.weights;
  pi.polynomial = {1 - 0.45};
  pi.input_min_v = -3;
  pi.input_max_v = 3;
  const sysid::PrandtlIshlinskiiModel model(pi);
  std::vector<double> dac;
  sysid::VirtualStage probe(p, 1);
  for (double x : u) dac.push_back(probe.DacOutput(x));
  const Eigen::VectorXd y = model.Simulate(
      Eigen::Map<const Eigen::VectorXd>(dac.data(), static_cast<long>(dac.size())),
      p.sample_time_s());
  const std::vector<double> got = StageEffective(p, u);
  double worst = 0;
  for (size_t k = 0; k < u.size(); ++k) worst = std::max(worst, std::abs(got[k] - y[static_cast<long>(k)]));
  INFO("max |u_h - PI| " << worst << " V");
  CHECK(worst < 1e-5);  // the lag state's CVODE tolerance, divided by 1 - e^(-Ts/T_l)
  // It is a hysteresis: the same command gives different effective voltages on the way up and
  // down (the loop of the slow sinusoid at 1.0 V is 2 sum w_i r_i = 0.165 V wide).
  CHECK(h.HeldLag(true) == Approx(0.15 * 0.05 + 0.1 * 0.12 + 0.2 * 0.25));
}

TEST_CASE("drive hysteresis: asymmetric and rate-dependent, against the play operator and the "
          "rate filter written out",
          "[stage][hysteresis]") {
  const double tau = GENERATE(0.0, 0.005);
  const sysid::DriveHysteresis h = Ceramic(0.4, 0.004, tau);
  sysid::StageParameters p = Stage(h);
  const std::vector<double> u = Commands(2000);
  std::vector<double> dac;
  sysid::VirtualStage probe(p, 1);
  for (double x : u) dac.push_back(probe.DacOutput(x));
  const std::vector<double> want = Reference(h, dac, p.sample_time_s());
  const std::vector<double> got = StageEffective(p, u);
  INFO("tau " << tau << " s: max |u_h - reference| " << MaxDiff(got, want) << " V");
  CHECK(MaxDiff(got, want) < 1e-5);
  // The rate widens the loop: without the rate weights the effective voltage differs.
  sysid::DriveHysteresis slow = h;
  slow.rate_weights_s_per_v = {0, 0, 0};
  CHECK(MaxDiff(Reference(slow, dac, p.sample_time_s()), want) > 0.05);
  // Asymmetric: a rise holds back (1 + alpha) sum w r, a fall (1 - alpha) sum w r.
  CHECK(h.HeldLag(true) / h.HeldLag(false) == Approx(1.4 / 0.6));
}

TEST_CASE("drive hysteresis behind a transport delay: its output is delayed, not its state",
          "[stage][hysteresis]") {
  // The operators are causal per sample, so delaying their input by n samples delays their
  // output by n samples (the stage's history holds the driven values).
  const sysid::DriveHysteresis h = Ceramic(0.3, 0.004, 0.005);
  sysid::StageParameters p = Stage(h);
  p.driver.transport_delay_s = 2 * p.sample_time_s();
  const std::vector<double> u = Commands(1500);
  std::vector<double> dac;
  sysid::VirtualStage probe(p, 1);
  for (double x : u) dac.push_back(probe.DacOutput(x));
  const std::vector<double> want = Reference(h, dac, p.sample_time_s());
  const std::vector<double> got = StageEffective(p, u);
  double worst = 0;
  for (size_t k = 2; k < u.size(); ++k) worst = std::max(worst, std::abs(got[k] - want[k - 2]));
  INFO("max |u_h(k) - reference(k - 2)| " << worst << " V");
  CHECK(worst < 1e-5);
  CHECK(std::abs(got[0]) < 1e-12);
  CHECK(std::abs(got[1]) < 1e-12);
}

TEST_CASE("the stage with drive hysteresis matches the tiny-step reference replaying u_h",
          "[stage][hysteresis][plant]") {
  const sysid::DriveHysteresis h = Ceramic(0.3, 0.003, 0.01);
  const sysid::StageParameters p = Stage(h);
  const std::vector<double> u = Commands(1500);
  std::vector<double> dac;
  sysid::VirtualStage stage(p, 1);
  for (double x : u) dac.push_back(stage.DacOutput(x));
  const std::vector<double> uh = Reference(h, dac, p.sample_time_s());
  VelocitySourceReference ref{p};
  // The bounds of the plant test without hysteresis (the same integrators).
  sysid::test::CheckAgainstReference(stage, ref, u, [&](size_t k) {
    for (int i = 0; i < 1000; ++i) ref.Step(uh[k], 1e-6);
  });
}

TEST_CASE("drive hysteresis keeps the pulse table: held pulses from 0 V settle on the paper's "
          "plateaus",
          "[stage][hysteresis]") {
  const sysid::DriveHysteresis h = Ceramic(0.3, 0.003, 0.01);
  const sysid::StageParameters p = Stage(h);
  for (const auto& [u, v] : sysid::StageParameters::PaperPulseTable()) {
    CHECK(p.SteadyVelocity(u) == Approx(v).epsilon(1e-10));
    // From rest, first the opposite direction then back to 0 V, then the pulse held 1.2 s:
    // the plateau is the stage's without hysteresis (the same run), and the paper's (F1).
    const double got = sysid::test::HeldPulseVelocity(p, u, true);
    const double without = sysid::test::HeldPulseVelocity(Stage1kHz(), u, false);
    INFO("u = " << u << " V");
    CHECK(got == Approx(without).epsilon(1e-6));
    CHECK(got == Approx(v).epsilon(1e-3));
  }
  // Moving the knots by the held lag: without it the held pulses would be slower.
  sysid::StageParameters raw = Stage1kHz();
  raw.velocity_source().hysteresis = h;
  raw.velocity_source().motor.dead_zone_forward_v -= h.HeldLag(true);
  raw.velocity_source().motor.dead_zone_backward_v -= h.HeldLag(false);
  CHECK(std::abs(raw.SteadyVelocity(1.5)) < 0.0574 - 0.003);
}

TEST_CASE("drive hysteresis in the stage file: written only when set, read back, validated at "
          "its place",
          "[stage][hysteresis][file]") {
  const sysid::StageParameters def = Stage1kHz();
  const std::string plain = sysid::StageParametersToJson(def);
  CHECK(plain.find("hysteresis") == std::string::npos);  // old files: byte for byte
  const sysid::StageParameters p = Stage(Ceramic(0.3, 0.003, 0.01));
  const std::string text = sysid::StageParametersToJson(p);
  const sysid::StageParameters back = sysid::ParseStageParameters(text, "h.json");
  CHECK(back.velocity_source().hysteresis.thresholds_v ==
        p.velocity_source().hysteresis.thresholds_v);
  CHECK(back.velocity_source().hysteresis.rate_weights_s_per_v ==
        p.velocity_source().hysteresis.rate_weights_s_per_v);
  CHECK(back.velocity_source().hysteresis.asymmetry == 0.3);
  CHECK(sysid::StageParametersToJson(back) == text);
  // A preset file adds the block (the preset's dead zones and map stay: the user moves them).
  const auto pre = sysid::ParseStageParameters(
      "{\"preset\": \"virtual\", \"drive\": {\"hysteresis\": {\"thresholds_v\": [0.1], "
      "\"weights\": [0.2], \"rate_weights_s_per_v\": [0], \"rate_time_constant_s\": 0, "
      "\"asymmetry\": 0}}}",
      "p.json");
  CHECK(pre.velocity_source().hysteresis.enabled());
  // Errors name the key, the rule and the value at the key's place.
  auto edited = [&](const std::string& from, const std::string& to) {
    std::string t = text;
    const size_t at = t.find(from);
    REQUIRE(at != std::string::npos);
    return t.replace(at, from.size(), to);
  };
  CHECK_THROWS_WITH(sysid::ParseStageParameters(edited("\"asymmetry\": 0.3", "\"asymmetry\": 1"),
                                                "h.json"),
                    Catch::Contains("h.json:") &&
                        Catch::Contains("hysteresis.asymmetry: expected -1 < asymmetry < 1, "
                                        "found 1"));
  CHECK_THROWS_WITH(
      sysid::ParseStageParameters(edited("\"weights\": [\n        0.15", "\"weights\": [\n  0.75"),
                                  "h.json"),
      Catch::Contains("hysteresis.weights: expected sum of weights < 1"));
  CHECK_THROWS_WITH(
      sysid::ParseStageParameters(edited("\"thresholds_v\": [\n        0.05",
                                         "\"thresholds_v\": [\n        0.5"),
                                  "h.json"),
      Catch::Contains("hysteresis.thresholds_v[1]: expected thresholds strictly increasing"));
  CHECK_THROWS_WITH(
      sysid::ParseStageParameters(edited("\"rate_weights_s_per_v\": [\n        0.003,",
                                         "\"rate_weights_s_per_v\": ["),
                                  "h.json"),
      Catch::Contains("hysteresis.rate_weights_s_per_v: expected one rate weight per threshold "
                      "(3), found 2"));
  CHECK_THROWS_WITH(sysid::ParseStageParameters(edited("\"asymmetry\": 0.3", "\"_was\": 0"), "h.json"),
                    Catch::Contains("missing required key 'asymmetry'"));
  CHECK_THROWS_WITH(sysid::ParseStageParameters(edited("\"asymmetry\": 0.3", "\"asymetry\": 0.3"),
                                                "h.json"),
                    Catch::Contains("unknown key 'asymetry'"));
  // Not on the actuator-delay model.
  CHECK_THROWS_WITH(
      sysid::ParseStageParameters("{\"preset\": \"actuator-delay\", \"drive\": {\"hysteresis\": "
                                  "{\"thresholds_v\": [0.1]}}}",
                                  "a.json"),
      Catch::Contains("belongs to the velocity-source model"));
  // Too large a lag for the dead zones: SetDriveHysteresis refuses it.
  sysid::DriveHysteresis wide = Ceramic(0.0, 0.0, 0.0);
  wide.weights = {0.3, 0.3, 0.39};
  wide.thresholds_v = {0.5, 1.0, 2.0};
  sysid::StageParameters q = Stage1kHz();
  CHECK_THROWS_AS(q.SetDriveHysteresis(wide), sysid::OptionsError);
}

TEST_CASE("the drive-hysteresis presets: candidate C's loop with the ceramic's loop, the pulse "
          "table kept",
          "[stage][hysteresis][file]") {
  const std::string name = GENERATE(std::string("drive-hysteresis"),
                                    std::string("drive-hysteresis-static"));
  INFO(name);
  REQUIRE(sysid::StageParameters::IsPresetName(name));
  const sysid::StageParameters p = sysid::LoadStage(name);
  CHECK(p.velocity_source().hysteresis.enabled());
  // The static one (H2) has no creep; the default one's play lag partly relaxes.
  CHECK(p.velocity_source().creep.enabled() == (name == "drive-hysteresis"));
  CHECK(p.rig.sample_rate_hz == 10000);
  CHECK(p.RecordRateHz() == 1000);
  for (const auto& [u, v] : sysid::StageParameters::PaperPulseTable())
    CHECK(p.SteadyVelocity(u) == Approx(v).epsilon(1e-10));
  // On a slow rise the stage starts where the default does (the dead zone moved by the lag a
  // held voltage keeps).
  const sysid::StageParameters def = Stage1kHz();
  CHECK(p.velocity_source().motor.dead_zone_forward_v + p.velocity_source().HeldDriveLag(true) ==
        Approx(def.velocity_source().motor.dead_zone_forward_v));
  CHECK(p.velocity_source().motor.dead_zone_backward_v + p.velocity_source().HeldDriveLag(false) ==
        Approx(def.velocity_source().motor.dead_zone_backward_v));
  const std::string text = sysid::StageParametersToJson(p);
  CHECK(sysid::StageParametersToJson(sysid::ParseStageParameters(text, "p.json")) == text);
  // It is candidate C with the hysteresis block whichever stage is the default: built here
  // from the 1 kHz preset with C's rates and lag written out.
  sysid::StageParameters c = sysid::LoadStage("virtual-1khz");
  c.name = p.name;
  c.rig.sample_rate_hz = 10000;
  c.rig.record_rate_hz = 1000;
  c.driver.lag_time_constant_s = 0.0001;
  c.SetDriveHysteresis(p.velocity_source().hysteresis);
  if (p.velocity_source().creep.enabled()) c.SetDriveCreep(p.velocity_source().creep);
  CHECK(sysid::StageParametersToJson(c) == text);
  // A file may name it as its preset and change one value.
  CHECK(sysid::ParseStageParameters(
            "{\"preset\": \"" + name + "\", \"drive\": {\"hysteresis\": {\"asymmetry\": 0}}}",
            "p.json")
            .velocity_source()
            .hysteresis.asymmetry == 0);
}
