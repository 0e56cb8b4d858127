// TunePi against independent methods: the margins it reports measured on the simulated loop
// (a frequency response of the stepped plant under the discrete PI law, no formula shared),
// no better gains on a brute-force grid of (Kp, Ki); its gains on the twin (no limit cycle, no
// saturation); the limit-cycle check on a loop known to limit-cycle; tracking on a model plant
// against the exact zero-order-hold plant.
#include <Eigen/Dense>
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <complex>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "support/test_support.hpp"
#include "sysid/control.hpp"
#include "sysid/control_tuning.hpp"
#include "sysid/error.hpp"
#include "sysid/simulate.hpp"
#include "sysid/stage.hpp"

namespace sysid {
namespace {

// Pure a3 / (s (s + a1 e^(-s tau))): no Coulomb friction, so the loop is linear.
FrictionModel Frictionless(double tau_s) {
  FrictionModel m;
  m.a1p = 60;
  m.a1n = 90;
  m.a2p = m.a2n = 0;
  m.a3 = 6;
  m.tau_s = tau_s;
  return m;
}

// The open loop e -> x at omega measured on the simulated loop: e_k = cos(omega t_k) into the
// PI law (no saturation), u held over each sample into the stepped plant (the simulator:
// the delay and the hold are the real ones), x_k fitted after the transients by
// c0 + c1 t + A cos + B sin (the plant's integrator turns the PI's mean output into a ramp).
// L = A - jB.
std::complex<double> SimulatedOpenLoop(const FrictionModel& model, int direction, PiOptions pi,
                                       double omega) {
  FrictionModel m = model;
  (direction > 0 ? m.a1n : m.a1p) = direction > 0 ? m.a1p : m.a1n;  // one branch only
  pi.u_max_v = 1e12;
  pi.anti_windup = AntiWindup::kNone;
  const double ts = pi.sample_time_s;
  const double settle = 12.0 / std::min(m.a1p, 60.0), span = 8 * 2 * M_PI / omega;
  const int n_settle = static_cast<int>(settle / ts), n = n_settle + static_cast<int>(span / ts);
  FrictionModelPlant plant(m, ts);
  PiController c(pi);
  Eigen::MatrixXd a(n - n_settle, 4);
  Eigen::VectorXd y(n - n_settle);
  double x = 0;
  for (int k = 0; k < n; ++k) {
    const double t = k * ts;
    if (k >= n_settle) {
      a.row(k - n_settle) << 1, t, std::cos(omega * t), std::sin(omega * t);
      y[k - n_settle] = x;
    }
    x = plant.Step(c.Update(std::cos(omega * t)));
  }
  const Eigen::Vector4d p = a.colPivHouseholderQr().solve(y);
  return {p[2], -p[3]};
}

TEST_CASE("tune-pi: its margins are those of the simulated loop", "[control][tuning]") {
  const FrictionModel model = Frictionless(2e-3);
  PiTuningOptions o;
  o.loop_rate_hz = 1000;
  const PiTuningResult r = TunePi(model, o);
  for (const auto& [name, a1, m] : r.margins.directions) {
    INFO(name << ": crossover " << m.crossover_rad_s << " rad/s, PM " << m.phase_margin_deg
              << " deg, GM " << 20 * std::log10(m.gain_margin) << " dB");
    CHECK(m.phase_margin_deg >= o.phase_margin_deg - 1e-6);
    CHECK(20 * std::log10(m.gain_margin) >= o.gain_margin_db - 1e-6);
    const int dir = std::string(name) == "forward" ? 1 : -1;
    const std::complex<double> at_crossover =
        SimulatedOpenLoop(model, dir, r.pi, m.crossover_rad_s);
    CHECK(std::abs(at_crossover) == Approx(1).epsilon(0.01));
    CHECK(180 + std::arg(at_crossover) * 180 / M_PI == Approx(m.phase_margin_deg).margin(0.5));
    const std::complex<double> at_phase_crossover =
        SimulatedOpenLoop(model, dir, r.pi, m.phase_crossover_rad_s);
    CHECK(1 / std::abs(at_phase_crossover) == Approx(m.gain_margin).epsilon(0.03));
  }
  // One direction is binding: the target is met with equality there (the highest crossover).
  const double pm = std::min(r.margins.forward().phase_margin_deg,
                             r.margins.backward().phase_margin_deg);
  const double gm = std::min(r.margins.forward().gain_margin, r.margins.backward().gain_margin);
  CHECK((std::abs(pm - o.phase_margin_deg) < 0.05 ||
         std::abs(20 * std::log10(gm) - o.gain_margin_db) < 0.05));
}

TEST_CASE("tune-pi JSON: four of the gains' fields, the targets it was given, the margins",
          "[control][tuning]") {
  PiTuningOptions o;
  o.phase_margin_deg = 50;
  o.gain_margin_db = 8;
  o.crossover_per_integral_corner = 4;
  const PiTuningResult r = TunePi(Frictionless(2e-3), o);
  const auto j = nlohmann::ordered_json::parse(ToJson(r));
  std::vector<std::string> keys;
  for (auto it = j.begin(); it != j.end(); ++it) keys.push_back(it.key());
  CHECK(keys == std::vector<std::string>{"kp_v_per_m", "ki_v_per_m_s", "sample_time_s",
                                         "u_max_v", "targets", "design_crossover_rad_s",
                                         "margins"});
  CHECK(j["kp_v_per_m"].get<double>() == r.pi.kp_v_per_m);
  CHECK(j["targets"] == nlohmann::ordered_json{{"phase_margin_deg", 50.0},
                                               {"gain_margin_db", 8.0},
                                               {"crossover_per_integral_corner", 4.0}});
  CHECK(j["margins"] == nlohmann::ordered_json::parse(ToJson(r.margins)));
}

TEST_CASE("tune-pi: no grid point of (Kp, Ki) meets the targets with a higher crossover",
          "[control][tuning]") {
  const FrictionModel model = Frictionless(3.5e-3);
  PiTuningOptions o;
  o.loop_rate_hz = 1000;
  const PiTuningResult r = TunePi(model, o);
  const double tuned = std::max(r.margins.forward().crossover_rad_s,
                                r.margins.backward().crossover_rad_s);
  CHECK(tuned == Approx(r.design_crossover_rad_s).epsilon(1e-6));
  double best = 0;
  for (int i = 0; i < 24; ++i) {
    for (int j = 0; j < 24; ++j) {
      PiOptions pi;
      pi.sample_time_s = 1 / o.loop_rate_hz;
      pi.kp_v_per_m = r.pi.kp_v_per_m * std::pow(10.0, -0.5 + 0.8 * i / 23.0);
      pi.ki_v_per_m_s = r.pi.ki_v_per_m_s * std::pow(10.0, -1 + 2.0 * j / 23.0);
      double fastest = 0;
      bool ok = true;
      for (int dir : {1, -1}) {
        const LoopMargins m = ComputeLoopMargins(
            [&](double w) { return RoughModelPiLoop(model, dir, pi, w); }, 1e-3,
            M_PI / pi.sample_time_s, 2000);
        ok = ok && m.Stable() && m.phase_margin_deg >= o.phase_margin_deg &&
             (std::isnan(m.gain_margin) || 20 * std::log10(m.gain_margin) >= o.gain_margin_db);
        fastest = std::max(fastest, m.crossover_rad_s);
      }
      // The tuner's rule: the integral corner at least crossover / N (integral action kept).
      ok = ok && pi.ki_v_per_m_s / pi.kp_v_per_m >= fastest / o.crossover_per_integral_corner;
      if (ok) best = std::max(best, fastest);
    }
  }
  INFO("tuned crossover " << tuned << " rad/s, best on the grid " << best << " rad/s");
  CHECK(best > 0.8 * tuned);         // the grid finds the same region
  CHECK(best <= tuned * (1 + 1e-3));  // and nothing faster
}

TEST_CASE("tune-pi: a target no gains meet is refused", "[control][tuning]") {
  PiTuningOptions o;
  o.phase_margin_deg = 89;  // the PI corner alone costs atan(1/5) = 11 deg
  CHECK_THROWS_AS(TunePi(Frictionless(3.5e-3), o), NumericalError);
  o.phase_margin_deg = 0;
  CHECK_THROWS_AS(TunePi(Frictionless(3.5e-3), o), OptionsError);
}

// The limit-cycle check's cases: the paper's gains on the actuator-delay stage hunt at +-10 V
// (PiOptions::ForActuatorDelayStage says why); that stage's own gains settle.
TEST_CASE("limit-cycle check: a hunting loop and a settled one", "[control][tuning]") {
  const StageParameters stage = StageParameters::ActuatorDelay();
  SmoothProfileOptions p;
  p.frequency_hz = 1;
  p.cycles = 1;
  const PositionReference ref = AppendHold(MakeStageProfile(stage, p), 1.0);
  const auto run = [&](const PiOptions& pi) {
    return TrackSchemes(stage, 1, ref, pi, {FeedforwardScheme::kNone}, {})[0].result;
  };
  const LimitCycleCheck hunting = CheckLimitCycle(run(PiOptions{}), 0.5, 5e-6);
  const LimitCycleCheck settled =
      CheckLimitCycle(run(PiOptions::ForActuatorDelayStage()), 0.5, 5e-6);
  INFO("paper gains: e p-p " << hunting.error_peak_to_peak_m << " m, u p-p "
                             << hunting.control_peak_to_peak_v << " V; own gains: e p-p "
                             << settled.error_peak_to_peak_m << " m");
  CHECK(hunting.limit_cycle);
  CHECK(hunting.control_peak_to_peak_v > 10);
  CHECK_FALSE(settled.limit_cycle);
}

// Gains tuned on the model identified from the twin's pulses (tests/data/control/
// twin_model.json: `sysid identify --a3 6 datasets/virtual/pulses.csv` then tune-delay) at
// the twin's 10 kHz loop, run on the twin: the acceptance of issue #40.
TEST_CASE("tune-pi on the twin's identified model: no limit cycle, no saturation on the twin",
          "[control][tuning]") {
  const FrictionModel model = ReadModel(test::TestData("control/twin_model.json"));
  const StageParameters twin = StageParameters::Default();
  PiTuningOptions o;
  o.loop_rate_hz = twin.rig.sample_rate_hz;
  const PiTuningResult r = TunePi(model, o);
  for (const double f : {0.5, 1.0}) {
    SmoothProfileOptions p;
    p.frequency_hz = f;
    p.cycles = 1;
    const PositionReference ref = AppendHold(MakeStageProfile(twin, p), 1.0);
    const TrackingResult t =
        TrackSchemes(twin, 1, ref, r.pi, {FeedforwardScheme::kNone}, {})[0].result;
    const LimitCycleCheck c = CheckLimitCycle(t, 0.5, 5e-6);
    INFO(f << " Hz: RMS e " << t.rms_error_m << " m, hold e p-p " << c.error_peak_to_peak_m
           << " m, u p-p " << c.control_peak_to_peak_v << " V");
    CHECK(t.saturated_samples == 0);
    CHECK_FALSE(c.limit_cycle);
    CHECK(t.rms_error_m < 1e-3);  // it tracks (a tenth of the 10 mm stroke)
    // The same gains on the identified model as the plant (track --plant M.json).
    const TrackingResult on_model = TrackModelSchemes(model, twin.sample_time_s(), ref, r.pi,
                                                      {FeedforwardScheme::kNone}, {})[0].result;
    const LimitCycleCheck cm = CheckLimitCycle(on_model, 0.5, 5e-6);
    CHECK(on_model.saturated_samples == 0);
    CHECK_FALSE(cm.limit_cycle);
  }
}

// Tracking on a model plant without friction or delay against the same loop on the exact
// zero-order-hold discretisation of a3 / (s (s + a1)).
TEST_CASE("track on a model plant: the exact ZOH plant's tracking errors", "[control][tuning]") {
  FrictionModel m = Frictionless(0);
  m.a1n = m.a1p;
  const double ts = 1e-3, a1 = m.a1p, e = std::exp(-a1 * ts);
  SmoothProfileOptions p;
  p.cycles = 1;
  const PositionReference ref = MakeSmoothProfile(p);
  PiOptions pi = PiOptions::ForActuatorDelayStage();
  const TrackingResult model_run =
      TrackModelSchemes(m, ts, ref, pi, {FeedforwardScheme::kNone}, {})[0].result;
  double x = 0, v = 0;
  const PlantStep exact = [&](double u) {
    const double v_inf = m.a3 * u / a1;
    x += v_inf * ts + (v - v_inf) * (1 - e) / a1;
    v = v_inf + (v - v_inf) * e;
    return x;
  };
  pi.sample_time_s = ts;
  const TrackingResult exact_run = RunClosedLoop(exact, 0.0, ref, pi);
  CHECK(model_run.rms_error_m == Approx(exact_run.rms_error_m).epsilon(1e-6));
  CHECK(model_run.max_error_m == Approx(exact_run.max_error_m).epsilon(1e-6));
  CHECK((model_run.x_m - exact_run.x_m).cwiseAbs().maxCoeff() < 1e-10);
}

}  // namespace
}  // namespace sysid
