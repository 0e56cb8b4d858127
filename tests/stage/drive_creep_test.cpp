// The drive's creep (stage.hpp, DriveCreep) against references written from its equations: the
// relaxation T_c z' = q - z and the envelope lag T_l u_d' = u_h - u_d solved in closed form
// piece by piece (an exponential input through a first-order lag), the play operators from the
// hysteresis module, a sinusoid's steady-state gain and phase, and the stage against the
// tiny-step RK4 reference with the relaxation integrated alongside.
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

using sysid::test::Commands;
using sysid::test::Reference;
using sysid::test::Stage1kHz;
using sysid::test::VelocitySourceReference;

// The hysteresis tests' ceramic, rate-independent.
sysid::DriveHysteresis Ceramic() { return sysid::test::Ceramic(0.3, 0.0, 0.0); }

sysid::DriveCreep Creep(double voltage_share, double loop_share, double time_constant_s) {
  sysid::DriveCreep c;
  c.voltage_share = voltage_share;
  c.loop_share = loop_share;
  c.time_constant_s = time_constant_s;
  return c;
}

// The lag's state u_d at the sample instants t_k = k Ts, k = 1..n, written from the equations:
// the DAC values (after the hysteresis: u_pi, and the command s) are held over
// [j Ts + T_d, (j + 1) Ts + T_d); on each such piece z(t) = q + (z_j - q) e^(-tau / T_c) with
// q = k_v u_pi + k_l (s - u_pi), u_h = (1 - k_v) u_pi + z, and the lag's exact solution for
// that input from u_d(piece start). Before T_d the input is 0.
struct ClosedForm {
  double ts, delay, tc, tl, kv, kl;
  std::vector<double> Lag(const std::vector<double>& s, const std::vector<double>& pi) const {
    // Pieces in time order: start, a = target of u_h, b = u_h - a at the start.
    struct Piece {
      double start, a, b;
    };
    std::vector<Piece> pieces{{0.0, 0.0, 0.0}};
    double z = 0;
    for (size_t j = 0; j < s.size(); ++j) {
      const double q = kv * pi[j] + kl * (s[j] - pi[j]);
      pieces.push_back({static_cast<double>(j) * ts + delay, (1 - kv) * pi[j] + q, z - q});
      z = q + (z - q) * std::exp(-ts / tc);
    }
    // u_d over a piece from u_d0 at its start: T_l u_d' = a + b e^(-tau/T_c) - u_d.
    auto advance = [&](const Piece& p, double ud0, double tau) {
      const double c = p.b * tc / (tc - tl);
      return p.a + c * std::exp(-tau / tc) + (ud0 - p.a - c) * std::exp(-tau / tl);
    };
    std::vector<double> out;
    double ud = 0;
    size_t i = 0;  // the piece ud belongs to, at its start
    for (size_t k = 1; k <= s.size(); ++k) {
      const double t = static_cast<double>(k) * ts;
      while (i + 1 < pieces.size() && pieces[i + 1].start <= t + 1e-12) {
        ud = advance(pieces[i], ud, pieces[i + 1].start - pieces[i].start);
        ++i;
      }
      out.push_back(advance(pieces[i], ud, t - pieces[i].start));
    }
    return out;
  }
};

sysid::StageParameters Stage(bool hysteresis, const sysid::DriveCreep& c) {
  sysid::StageParameters p = Stage1kHz();
  p.rig.position_noise_m = 0;
  if (hysteresis) p.SetDriveHysteresis(Ceramic());
  p.SetDriveCreep(c);
  return p;
}

// The stage's lag state after each sample, and the DAC values it was driven with.
std::vector<double> StageLag(const sysid::StageParameters& p, const std::vector<double>& u,
                             std::vector<double>* dac) {
  sysid::VirtualStage stage(p, 1);
  std::vector<double> out;
  for (double x : u) {
    dac->push_back(stage.DacOutput(x));
    stage.Step(x);
    out.push_back(stage.state().w_v);
  }
  return out;
}

double MaxDiff(const std::vector<double>& a, const std::vector<double>& b, size_t shift = 0) {
  double worst = 0;
  for (size_t k = shift; k < a.size(); ++k) worst = std::max(worst, std::abs(a[k] - b[k - shift]));
  return worst;
}

}  // namespace

TEST_CASE(
    "drive creep: the voltage share on held steps is the closed-form relaxation through "
    "the lag",
    "[stage][creep]") {
  const sysid::DriveCreep c = Creep(0.4, 0, 0.02);
  const sysid::StageParameters p = Stage(false, c);
  // Held steps: 1.5 V for 0.1 s (the stage moves), -1.0 V for 0.05 s, 0 V for 0.05 s.
  std::vector<double> u(100, 1.5);
  u.resize(150, -1.0);
  u.resize(200, 0.0);
  std::vector<double> dac;
  const std::vector<double> got = StageLag(p, u, &dac);
  const ClosedForm ref{
      p.sample_time_s(), 0, c.time_constant_s, p.driver.lag_time_constant_s, 0.4, 0};
  const std::vector<double> want = ref.Lag(dac, dac);
  INFO("max |u_d - closed form| " << MaxDiff(got, want) << " V");
  CHECK(MaxDiff(got, want) < 1e-5);  // the lag state's CVODE tolerance
  // The relaxation is there: 0.1 s after the step the voltage has (nearly) arrived, one sample
  // after it only (1 - k_v) of it.
  CHECK(got[99] == Approx(dac[0]).epsilon(0.4 * std::exp(-4.9)));
  CHECK(got[0] < 0.65 * dac[0]);
  // The first sample's value written out by hand: u_h = u - k u e^(-t/T_c).
  const double tl = p.driver.lag_time_constant_s, tc = c.time_constant_s, ts = p.sample_time_s();
  const double by_hand = dac[0] * (1 - std::exp(-ts / tl)) -
                         0.4 * dac[0] * tc / (tc - tl) * (std::exp(-ts / tc) - std::exp(-ts / tl));
  CHECK(got[0] == Approx(by_hand).epsilon(1e-5));
}

TEST_CASE(
    "drive creep: both shares after the play operators, against the module's operator and "
    "the closed form",
    "[stage][creep][hysteresis]") {
  const double kv = GENERATE(0.0, 0.3);
  const sysid::DriveCreep c = Creep(kv, 0.6, 0.015);
  const sysid::StageParameters p = Stage(true, c);
  const std::vector<double> u = Commands(2000);
  std::vector<double> dac;
  const std::vector<double> got = StageLag(p, u, &dac);
  const ClosedForm ref{
      p.sample_time_s(), 0, c.time_constant_s, p.driver.lag_time_constant_s, kv, 0.6};
  const std::vector<double> want = ref.Lag(dac, Reference(Ceramic(), dac, p.sample_time_s()));
  INFO("k_v " << kv << ": max |u_d - reference| " << MaxDiff(got, want) << " V");
  CHECK(MaxDiff(got, want) < 1e-5);
  // The creep changes the drive: without it the lag follows the play operators alone.
  const ClosedForm none{p.sample_time_s(), 0, 1.0, p.driver.lag_time_constant_s, 0, 0};
  CHECK(MaxDiff(none.Lag(dac, Reference(Ceramic(), dac, p.sample_time_s())), want) > 0.03);
}

TEST_CASE(
    "drive creep behind a fractional transport delay: the relaxation is delayed with its "
    "input",
    "[stage][creep]") {
  const sysid::DriveCreep c = Creep(0.3, 0.5, 0.01);
  sysid::StageParameters p = Stage(true, c);
  p.driver.transport_delay_s = 2.4 * p.sample_time_s();
  const std::vector<double> u = Commands(1500);
  std::vector<double> dac;
  const std::vector<double> got = StageLag(p, u, &dac);
  const ClosedForm ref{p.sample_time_s(),
                       p.driver.transport_delay_s,
                       c.time_constant_s,
                       p.driver.lag_time_constant_s,
                       0.3,
                       0.5};
  const std::vector<double> want = ref.Lag(dac, Reference(Ceramic(), dac, p.sample_time_s()));
  INFO("max |u_d - reference| " << MaxDiff(got, want) << " V");
  CHECK(MaxDiff(got, want) < 1e-5);
  CHECK(std::abs(got[1]) < 1e-12);  // nothing arrives before the delay
}

TEST_CASE("drive creep: a sinusoid's steady state has the closed-form gain and phase",
          "[stage][creep]") {
  // u_h / u = (1 + j w (1 - k) T_c) / (1 + j w T_c), then the lag 1 / (1 + j w T_l) and the
  // DAC's hold (gain sinc(w Ts / 2), delay Ts / 2). 1 V: inside the dead zone, no motion.
  const double k = 0.5, tc = 0.05, f = 2.0;
  sysid::StageParameters p = Stage(false, Creep(k, 0, tc));
  // 10 kHz: the hold's images near the sample rate, aliased back by sampling the lag state,
  // stay below 1e-5 of the fundamental.
  p.rig.sample_rate_hz = 10000;
  const double ts = p.sample_time_s(), w = 2 * M_PI * f;
  const int per_period = static_cast<int>(std::lround(1 / (f * ts)));
  std::vector<double> u;
  for (int i = 0; i < 6 * per_period; ++i) u.push_back(std::sin(w * i * ts));
  std::vector<double> dac;
  const std::vector<double> lag = StageLag(p, u, &dac);
  // Fundamental of the lag state over the last 2 periods (sample k holds the state at
  // (k + 1) Ts).
  double re = 0, im = 0;
  for (int i = 4 * per_period; i < 6 * per_period; ++i) {
    const double t = (i + 1) * ts;
    re += lag[static_cast<size_t>(i)] * std::sin(w * t);
    im += lag[static_cast<size_t>(i)] * std::cos(w * t);
  }
  const double gain = 2 * std::hypot(re, im) / (2 * per_period);
  const double phase = std::atan2(im, re);
  const double creep_gain = std::hypot(1, w * (1 - k) * tc) / std::hypot(1, w * tc);
  const double creep_phase = std::atan(w * (1 - k) * tc) - std::atan(w * tc);
  const double x = w * ts / 2;
  const double want_gain =
      creep_gain / std::hypot(1, w * p.driver.lag_time_constant_s) * std::sin(x) / x;
  const double want_phase = creep_phase - std::atan(w * p.driver.lag_time_constant_s) - x;
  INFO("gain " << gain << " (want " << want_gain << "), phase " << phase << " rad (want "
               << want_phase << ", of which the creep " << creep_phase << ")");
  CHECK(gain == Approx(want_gain).epsilon(1e-4));
  CHECK(phase == Approx(want_phase).margin(3e-4));
  CHECK(creep_phase < -0.2);  // the creep's lag dominates the phase
}

TEST_CASE("the stage with drive creep matches the tiny-step reference integrating the relaxation",
          "[stage][creep][plant]") {
  const sysid::DriveCreep c = Creep(0.2, 0.6, 0.02);
  const sysid::StageParameters p = Stage(true, c);
  const std::vector<double> u = Commands(1500);
  std::vector<double> dac;
  sysid::VirtualStage stage(p, 1);
  for (double x : u) dac.push_back(stage.DacOutput(x));
  const std::vector<double> pi = Reference(Ceramic(), dac, p.sample_time_s());
  VelocitySourceReference ref{p};
  double z = 0;
  const double h = 1e-6;
  // The bounds of the plant test without creep (the same integrators).
  sysid::test::CheckAgainstReference(stage, ref, u, [&](size_t k) {
    const double q = c.voltage_share * pi[k] + c.loop_share * (dac[k] - pi[k]);
    for (int i = 0; i < 1000; ++i) {
      // RK4 of T_c z' = q - z over the step; the plant's reference holds the step's mean u_h.
      const double k1 = (q - z) / c.time_constant_s,
                   k2 = (q - (z + h / 2 * k1)) / c.time_constant_s,
                   k3 = (q - (z + h / 2 * k2)) / c.time_constant_s,
                   k4 = (q - (z + h * k3)) / c.time_constant_s;
      const double z1 = z + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
      ref.Step((1 - c.voltage_share) * pi[k] + 0.5 * (z + z1), h);
      z = z1;
    }
  });
}

TEST_CASE(
    "drive creep keeps the pulse table: a held voltage has relaxed, the loop share's part "
    "of the lag too",
    "[stage][creep][hysteresis]") {
  const sysid::DriveCreep c = Creep(0.1, 0.6, 0.02);
  const sysid::StageParameters p = Stage(true, c);
  const sysid::DriveHysteresis h = Ceramic();
  CHECK(p.velocity_source().HeldDriveLag(true) == Approx(0.4 * h.HeldLag(true)));
  CHECK(p.velocity_source().HeldDriveLag(false) == Approx(0.4 * h.HeldLag(false)));
  // A slow rise starts the stage where the default's does (the dead zones moved by the held
  // lag that remains).
  const sysid::StageParameters def = Stage1kHz();
  CHECK(p.velocity_source().motor.dead_zone_forward_v + p.velocity_source().HeldDriveLag(true) ==
        Approx(def.velocity_source().motor.dead_zone_forward_v));
  CHECK(p.velocity_source().motor.dead_zone_backward_v + p.velocity_source().HeldDriveLag(false) ==
        Approx(def.velocity_source().motor.dead_zone_backward_v));
  for (const auto& [u, v] : sysid::StageParameters::PaperPulseTable()) {
    CHECK(p.SteadyVelocity(u) == Approx(v).epsilon(1e-10));
    // From the opposite direction, back to 0 V, then the pulse held 1.2 s: the plateau is the
    // stage's without hysteresis and creep (the same run), and the paper's (F1).
    const double got = sysid::test::HeldPulseVelocity(p, u, true);
    const double without = sysid::test::HeldPulseVelocity(def, u, false);
    INFO("u = " << u << " V");
    CHECK(got == Approx(without).epsilon(1e-6));
  }
  // Setting the creep first and the hysteresis after moves the dead zones alike.
  sysid::StageParameters other = Stage1kHz();
  sysid::DriveHysteresis tiny = h;
  tiny.weights = {0.0, 0.0, 0.01};
  other.SetDriveHysteresis(tiny);
  other.SetDriveCreep(c);
  other.SetDriveHysteresis(h);
  CHECK(other.velocity_source().motor.dead_zone_forward_v ==
        Approx(p.velocity_source().motor.dead_zone_forward_v));
  CHECK(other.velocity_source().motor.speed_map_in_v.back() ==
        Approx(p.velocity_source().motor.speed_map_in_v.back()));
}

TEST_CASE(
    "drive creep in the stage file: written only when set, read back, validated at its "
    "place",
    "[stage][creep][file]") {
  CHECK(sysid::StageParametersToJson(Stage(true, {})).find("creep") == std::string::npos);
  const sysid::StageParameters p = Stage(true, Creep(0.2, 0.5, 0.03));
  const std::string text = sysid::StageParametersToJson(p);
  const sysid::StageParameters back = sysid::ParseStageParameters(text, "c.json");
  CHECK(back.velocity_source().creep.voltage_share == 0.2);
  CHECK(back.velocity_source().creep.loop_share == 0.5);
  CHECK(back.velocity_source().creep.time_constant_s == 0.03);
  CHECK(sysid::StageParametersToJson(back) == text);
  // A preset file may add or change it (the preset's dead zones stay: the user moves them).
  const auto pre = sysid::ParseStageParameters(
      "{\"preset\": \"velocity-source\", \"drive\": {\"creep\": {\"voltage_share\": 0.1}}}",
      "p.json");
  CHECK(pre.velocity_source().creep.voltage_share == 0.1);
  CHECK(pre.velocity_source().creep.loop_share == 0);
  auto edited = [&](const std::string& from, const std::string& to) {
    std::string t = text;
    const size_t at = t.find(from);
    REQUIRE(at != std::string::npos);
    return t.replace(at, from.size(), to);
  };
  CHECK_THROWS_WITH(
      sysid::ParseStageParameters(edited("\"voltage_share\": 0.2", "\"voltage_share\": 1"),
                                  "c.json"),
      Catch::Matches(
          "c\\.json:[0-9]+:[0-9]+: drive\\.creep\\.voltage_share: expected 0 <= voltage_share "
          "< 1.*found 1.*"));
  CHECK_THROWS_WITH(
      sysid::ParseStageParameters(edited("\"loop_share\": 0.5", "\"loop_share\": -0.1"), "c.json"),
      Catch::Contains("creep.loop_share: expected 0 <= loop_share < 1"));
  CHECK_THROWS_WITH(sysid::ParseStageParameters(
                        edited("\"time_constant_s\": 0.03", "\"time_constant_s\": 0"), "c.json"),
                    Catch::Contains("creep.time_constant_s: expected 0 < time_constant_s <= 100"));
  CHECK_THROWS_WITH(
      sysid::ParseStageParameters(edited("\"time_constant_s\": 0.03", "\"_was\": 0"), "c.json"),
      Catch::Contains("missing required key 'time_constant_s'"));
  CHECK_THROWS_WITH(
      sysid::ParseStageParameters(edited("\"loop_share\": 0.5", "\"loopshare\": 0.5"), "c.json"),
      Catch::Contains("unknown key 'loopshare'"));
  // The loop share relaxes the play operators' lag: without them it is refused.
  CHECK_THROWS_WITH(
      sysid::ParseStageParameters(
          "{\"preset\": \"velocity-source\", \"drive\": {\"creep\": {\"loop_share\": 0.5}}}",
          "p.json"),
      Catch::Contains("p.json:") &&
          Catch::Contains("creep.loop_share: expected loop_share = 0 without drive.hysteresis"));
  // Not on the actuator-delay model.
  CHECK_THROWS_WITH(
      sysid::ParseStageParameters("{\"preset\": \"actuator-delay\", \"drive\": {\"creep\": "
                                  "{\"voltage_share\": 0.1}}}",
                                  "a.json"),
      Catch::Contains("belongs to the velocity-source model"));
}
