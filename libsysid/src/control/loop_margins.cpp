// Gain and phase margins of a linear open loop, and the rough model's loop under the PI law:
// the check behind "are these gains stable on my stage" (the paper's gains sit at the edge of
// the paper's own model, docs/control.md).
#include <cmath>
#include <complex>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>

#include "control/control_json.hpp"
#include "core/json_fields.hpp"
#include "sysid/control.hpp"
#include "sysid/error.hpp"
#include "sysid/model.hpp"

namespace sysid {
namespace {

constexpr double kPi = 3.14159265358979323846;
// [rad/s] where the sweep's start stops moving down (a period of 200 years).
constexpr double kLowestSweepStartRadS = 1e-9;

// The root of f between lo and hi (f(lo), f(hi) of opposite signs), by bisection in log omega.
double Bisect(const std::function<double(double)>& f, double lo, double hi) {
  double f_lo = f(lo);
  while (hi / lo - 1 > 1e-12) {
    const double mid = std::sqrt(lo * hi), f_mid = f(mid);
    if ((f_mid < 0) == (f_lo < 0)) {
      lo = mid;
      f_lo = f_mid;
    } else {
      hi = mid;
    }
  }
  return std::sqrt(lo * hi);
}

// The angle in (-180, 180] degrees.
double WrapDeg(double deg) {
  deg = std::fmod(deg, 360.0);
  if (deg <= -180) deg += 360;
  if (deg > 180) deg -= 360;
  return deg;
}

}  // namespace

bool LoopMargins::Stable() const {
  return phase_margin_deg > 0 && (std::isnan(gain_margin) || gain_margin > 1);
}

LoopMargins ComputeLoopMargins(const std::function<std::complex<double>(double)>& open_loop,
                               double w_min_rad_s, double w_max_rad_s, int points) {
  if (!(w_min_rad_s > 0) || !(w_max_rad_s > w_min_rad_s) || !std::isfinite(w_max_rad_s))
    throw OptionsError("ComputeLoopMargins: expected 0 < w_min < w_max < inf, found w_min = " +
                       std::to_string(w_min_rad_s) + ", w_max = " + std::to_string(w_max_rad_s));
  if (points < 16 || points > 10'000'000)
    throw OptionsError("ComputeLoopMargins: expected 16 <= points <= 10^7, found " +
                       std::to_string(points));
  LoopMargins m;  // NaN until a crossing is found
  const double step = std::pow(w_max_rad_s / w_min_rad_s, 1.0 / (points - 1));
  // arg L unwrapped along the sweep: phase(w) for w near a sample continues that sample's.
  auto phase_near = [&](double w, std::complex<double> ref, double ref_phase) {
    return ref_phase + std::arg(open_loop(w) / ref);
  };
  double w0 = w_min_rad_s;
  std::complex<double> l0 = open_loop(w0);
  double phase0 = std::arg(l0);
  for (int i = 1; i < points; ++i) {
    const double w1 = i + 1 == points ? w_max_rad_s : w0 * step;
    const std::complex<double> l1 = open_loop(w1);
    const double phase1 = phase0 + std::arg(l1 / l0);
    if (!std::isfinite(std::abs(l1)) || !std::isfinite(phase1))
      throw NumericalError("ComputeLoopMargins: L(j omega) is not finite at omega = " +
                           std::to_string(w1) + " rad/s");
    if (std::abs(l0) >= 1 && std::abs(l1) < 1) {  // the last such crossing wins
      m.crossover_rad_s =
          Bisect([&](double w) { return std::log(std::abs(open_loop(w))); }, w0, w1);
      m.phase_margin_deg = WrapDeg(180 + phase_near(m.crossover_rad_s, l0, phase0) * 180 / kPi);
    }
    // -180 deg (mod 360) crossed going down: the turn count of pi + phase drops.
    if (std::isnan(m.phase_crossover_rad_s) &&
        std::floor((phase1 + kPi) / (2 * kPi)) < std::floor((phase0 + kPi) / (2 * kPi))) {
      const double target = 2 * kPi * std::floor((phase0 + kPi) / (2 * kPi)) - kPi;
      m.phase_crossover_rad_s =
          Bisect([&](double w) { return phase_near(w, l0, phase0) - target; }, w0, w1);
      m.gain_margin = 1 / std::abs(open_loop(m.phase_crossover_rad_s));
    }
    w0 = w1;
    l0 = l1;
    phase0 = phase1;
  }
  return m;
}

std::complex<double> RoughModelPiLoop(const FrictionModel& model, int direction,
                                      const PiOptions& pi, double omega_rad_s,
                                      double extra_delay_s) {
  using namespace std::complex_literals;
  const double a1 = direction >= 0 ? model.a1p : model.a1n, ts = pi.sample_time_s;
  const std::complex<double> s = 1i * omega_rad_s;
  const std::complex<double> pi_law =
      pi.kp_v_per_m + pi.ki_v_per_m_s * ts / (1.0 - std::exp(-s * ts));
  const std::complex<double> plant = model.a3 * std::exp(-s * (ts / 2 + extra_delay_s)) /
                                     (s * (s + a1 * std::exp(-s * model.tau_s)));
  return pi_law * plant;
}

LoopMargins RoughModelPiMargins(const FrictionModel& model, int direction, const PiOptions& pi,
                                double extra_delay_s) {
  model.Validate();
  pi.Validate();
  if (!(extra_delay_s >= 0) || !std::isfinite(extra_delay_s))
    throw OptionsError("RoughModelPiMargins: expected extra_delay_s >= 0, found " +
                       std::to_string(extra_delay_s));
  if (pi.kp_v_per_m == 0 && pi.ki_v_per_m_s == 0)
    throw OptionsError("RoughModelPiMargins: Kp = Ki = 0 is an open loop: it has no margins");
  auto loop = [&](double w) { return RoughModelPiLoop(model, direction, pi, w, extra_delay_s); };
  // The sweep starts at 0.1 rad/s, or lower until |L| > 1 there: the loop has an integrator
  // (|L| grows without bound as omega -> 0), so a low-gain loop's crossover lies below 0.1 rad/s
  // and a sweep started above it would find none and call a stable loop unstable.
  double w_min = 0.1;
  while (std::abs(loop(w_min)) <= 1 && w_min > kLowestSweepStartRadS) w_min /= 10;
  return ComputeLoopMargins(loop, w_min, kPi / pi.sample_time_s);
}

PiMarginsReport AnalyzePiMargins(const FrictionModel& model, const PiOptions& pi,
                                 double extra_delay_s) {
  return {pi,
          extra_delay_s,
          model.tau_s,
          model.a3,
          {{"forward", model.a1p, RoughModelPiMargins(model, +1, pi, extra_delay_s)},
           {"backward", model.a1n, RoughModelPiMargins(model, -1, pi, extra_delay_s)}}};
}

std::string ToJson(const PiMarginsReport& r, int indent) {
  return internal::FieldsToJson(r, indent);
}

}  // namespace sysid
