// TunePi: the PI gains with the highest crossover that meet the target phase and gain margins
// in both directions of an identified model (sysid/control_tuning.hpp says the design).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/option_rule.hpp"
#include "sysid/control_tuning.hpp"
#include "sysid/error.hpp"

namespace sysid {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kGridPoints = 160;     // log grid of candidate crossovers
constexpr int kBisections = 40;      // between the last good and the first bad grid point
constexpr double kLowestCrossoverRadS = 0.1;

void Require(bool ok, const char* field, double value, const char* rule) {
  if (!ok) internal::FailOption("PiTuningOptions", field, value, rule);
}

bool MeetsTargets(const LoopMargins& m, const PiTuningOptions& o) {
  if (!m.Stable() || !(m.phase_margin_deg >= o.phase_margin_deg)) return false;
  return std::isnan(m.gain_margin) || m.GainMarginDb() >= o.gain_margin_db;
}

}  // namespace

void PiTuningOptions::Validate() const {
  Require(std::isfinite(loop_rate_hz) && loop_rate_hz > 0 && loop_rate_hz <= 1e7,
          "loop_rate_hz", loop_rate_hz, "0 < loop_rate_hz <= 1e7");
  Require(phase_margin_deg > 0 && phase_margin_deg < 90, "phase_margin_deg", phase_margin_deg,
          "0 < phase_margin_deg < 90");
  Require(gain_margin_db >= 0 && gain_margin_db <= 40, "gain_margin_db", gain_margin_db,
          "0 <= gain_margin_db <= 40");
  Require(crossover_per_integral_corner >= 1 && crossover_per_integral_corner <= 1000,
          "crossover_per_integral_corner", crossover_per_integral_corner,
          "1 <= crossover_per_integral_corner <= 1000");
  Require(extra_delay_s >= 0 && extra_delay_s <= 10, "extra_delay_s", extra_delay_s,
          "0 <= extra_delay_s <= 10");
  Require(std::isfinite(u_max_v) && u_max_v > 0, "u_max_v", u_max_v, "u_max_v > 0, finite");
}

PiTuningResult TunePi(const FrictionModel& model, const PiTuningOptions& o) {
  model.Validate();
  o.Validate();
  PiOptions unit;  // Kp = 1 V/m, Ki / Kp = w / N: |L| scales with Kp
  unit.sample_time_s = 1 / o.loop_rate_hz;
  unit.u_max_v = o.u_max_v;
  auto gains = [&](double w) {
    PiOptions pi = unit;
    pi.kp_v_per_m = 1;
    pi.ki_v_per_m_s = w / o.crossover_per_integral_corner;
    const double gain = std::max(std::abs(RoughModelPiLoop(model, +1, pi, w, o.extra_delay_s)),
                                 std::abs(RoughModelPiLoop(model, -1, pi, w, o.extra_delay_s)));
    pi.kp_v_per_m = 1 / gain;
    pi.ki_v_per_m_s /= gain;
    return pi;
  };
  PiTuningResult r;
  auto feasible = [&](double w) {
    ++r.evaluations;
    const PiOptions pi = gains(w);
    return MeetsTargets(RoughModelPiMargins(model, +1, pi, o.extra_delay_s), o) &&
           MeetsTargets(RoughModelPiMargins(model, -1, pi, o.extra_delay_s), o);
  };
  const double w_max = kPi * o.loop_rate_hz;
  const double step = std::pow(w_max / kLowestCrossoverRadS, 1.0 / (kGridPoints - 1));
  double good = std::numeric_limits<double>::quiet_NaN(), bad = good;
  for (int i = kGridPoints - 1; i >= 0; --i) {  // from the top: the highest good point wins
    const double w = kLowestCrossoverRadS * std::pow(step, i);
    if (feasible(w)) {
      good = w;
      break;
    }
    bad = w;
  }
  if (std::isnan(good))
    throw NumericalError(fmt::format(
        "tune-pi: no crossover between {:g} and {:g} rad/s meets a phase margin of {:g} deg and "
        "a gain margin of {:g} dB in both directions (tau = {:g} s, loop rate {:g} Hz): lower "
        "the targets or raise the loop rate",
        kLowestCrossoverRadS, w_max, o.phase_margin_deg, o.gain_margin_db, model.tau_s,
        o.loop_rate_hz));
  if (!std::isnan(bad))
    for (int i = 0; i < kBisections; ++i) {
      const double mid = std::sqrt(good * bad);
      (feasible(mid) ? good : bad) = mid;
    }
  r.design_crossover_rad_s = good;
  r.pi = gains(good);
  r.margins = AnalyzePiMargins(model, r.pi, o.extra_delay_s);
  r.options = o;
  return r;
}

}  // namespace sysid
