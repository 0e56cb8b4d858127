// The stack's parameters: the bundled defaults (docs/piezo_stack.md, "Where the numbers come
// from") and their rules.
#include <cmath>
#include <sstream>

#include "core/option_rule.hpp"
#include "sysid/error.hpp"
#include "sysid/stack.hpp"

namespace sysid {
namespace {

[[noreturn]] void Violated(const std::string& field, double value, const std::string& rule) {
  internal::FailOption("StackParameters", field, value, rule);
}

std::string G(double v) {
  std::ostringstream s;
  s.precision(12);
  s << v;
  return s.str();
}

std::string At(const char* array, size_t i) {
  return std::string(array) + "[" + std::to_string(i) + "]";
}

}  // namespace

StackParameters StackParameters::Default() {
  StackParameters p;
  // 10 play operators over half the nominal 0-100 V drive (the PI fit's uniform thresholds).
  constexpr int kOperators = 10;
  constexpr double kHalfRangeV = 50.0;
  p.hysteresis.linear_gain_m_per_v = 0.18e-6;
  p.hysteresis.rate_weights_m_s_per_v2.push_back(0.0);
  for (int i = 1; i <= kOperators; ++i) {
    const double w = 0.033e-6 * std::pow(0.8, i - 1);
    p.hysteresis.thresholds_v.push_back(i * kHalfRangeV / (kOperators + 1));
    p.hysteresis.weights_m_per_v.push_back(w);
    // Slopes 1e-5 s/V steeper per V/s of input rate: +3 % at a 10 Hz full-stroke sine.
    p.hysteresis.rate_weights_m_s_per_v2.push_back(1e-5 * w);
  }
  // Three decades of creep, 1 % of a step per decade (Jung & Gweon 2000).
  p.creep.time_constants_s = {0.1, 1.0, 10.0};
  p.creep.fractions = {0.01, 0.01, 0.01};
  return p;
}

std::string ToString(StackMethod method) {
  return method == StackMethod::kCvode ? "cvode" : "exact";
}

StackMethod ParseStackMethod(const std::string& name) {
  if (name == "cvode") return StackMethod::kCvode;
  if (name == "exact") return StackMethod::kExact;
  throw OptionsError("'" + name + "' is not one of cvode, exact", "integrator.method");
}

bool IsStackPresetName(const std::string& name) { return name == "piezo-stack" || name == "stack"; }

void StackParameters::Validate() const {
  const StackHysteresis& h = hysteresis;
  if (!std::isfinite(h.linear_gain_m_per_v) || !(h.linear_gain_m_per_v > 0))
    Violated("hysteresis.linear_gain_m_per_v", h.linear_gain_m_per_v,
             "linear_gain_m_per_v > 0 and finite (the stack stays monotone and invertible)");
  if (h.thresholds_v.size() > static_cast<size_t>(kMaxPlayOperators))
    Violated("hysteresis.thresholds_v", static_cast<double>(h.thresholds_v.size()),
             "at most " + std::to_string(kMaxPlayOperators) + " thresholds");
  for (size_t i = 0; i < h.thresholds_v.size(); ++i) {
    const double r = h.thresholds_v[i];
    if (!std::isfinite(r) || !(r > 0))
      Violated(At("hysteresis.thresholds_v", i), r, "r_i > 0 and finite");
    if (i > 0 && !(r > h.thresholds_v[i - 1]))
      Violated(At("hysteresis.thresholds_v", i), r,
               "thresholds increasing (r_i > r_(i-1) = " + G(h.thresholds_v[i - 1]) + ")");
  }
  if (h.weights_m_per_v.size() != h.thresholds_v.size())
    Violated("hysteresis.weights_m_per_v", static_cast<double>(h.weights_m_per_v.size()),
             "one weight per threshold (" + std::to_string(h.thresholds_v.size()) + ")");
  for (size_t i = 0; i < h.weights_m_per_v.size(); ++i)
    if (!std::isfinite(h.weights_m_per_v[i]) || h.weights_m_per_v[i] < 0)
      Violated(At("hysteresis.weights_m_per_v", i), h.weights_m_per_v[i], "w_i >= 0 and finite");
  if (h.rate_weights_m_s_per_v2.size() != h.thresholds_v.size() + 1)
    Violated("hysteresis.rate_weights_m_s_per_v2",
             static_cast<double>(h.rate_weights_m_s_per_v2.size()),
             "q_0 .. q_n: one more than the thresholds (" +
                 std::to_string(h.thresholds_v.size() + 1) + ")");
  for (size_t i = 0; i < h.rate_weights_m_s_per_v2.size(); ++i)
    if (!std::isfinite(h.rate_weights_m_s_per_v2[i]) || h.rate_weights_m_s_per_v2[i] < 0)
      Violated(At("hysteresis.rate_weights_m_s_per_v2", i), h.rate_weights_m_s_per_v2[i],
               "q_i >= 0 and finite");

  if (creep.time_constants_s.size() > static_cast<size_t>(kMaxCreepElements))
    Violated("creep.time_constants_s", static_cast<double>(creep.time_constants_s.size()),
             "at most " + std::to_string(kMaxCreepElements) + " creep elements");
  if (creep.fractions.size() != creep.time_constants_s.size())
    Violated(
        "creep.fractions", static_cast<double>(creep.fractions.size()),
        "one fraction per time constant (" + std::to_string(creep.time_constants_s.size()) + ")");
  for (size_t j = 0; j < creep.time_constants_s.size(); ++j) {
    const double tau = creep.time_constants_s[j];
    if (!std::isfinite(tau) || !(tau > 0))
      Violated(At("creep.time_constants_s", j), tau, "tau_j > 0 and finite");
    const double kappa = creep.fractions[j];
    if (!std::isfinite(kappa) || kappa < 0 || kappa > 10)
      Violated(At("creep.fractions", j), kappa, "kappa_j in [0, 10]");
  }

  if (!std::isfinite(rig.control_rate_hz) || !(rig.control_rate_hz > 0) ||
      rig.control_rate_hz > 1e6)
    Violated("rig.control_rate_hz", rig.control_rate_hz, "control_rate_hz in (0, 1e6]");
  const double nyquist = 0.5 * rig.control_rate_hz;
  if (!std::isfinite(mechanics.resonance_hz) || !(mechanics.resonance_hz > 0) ||
      !(mechanics.resonance_hz < nyquist))
    Violated("mechanics.resonance_hz", mechanics.resonance_hz,
             "0 < resonance_hz < control_rate_hz / 2 = " + G(nyquist));
  // Below 1e-4 the resonance peak 1/(2 zeta) passes 5000 and the loop's margins are not
  // finite numbers (1e-300 printed "gain nan").
  if (!std::isfinite(mechanics.damping_ratio) || !(mechanics.damping_ratio >= 1e-4) ||
      mechanics.damping_ratio > 2)
    Violated("mechanics.damping_ratio", mechanics.damping_ratio, "damping_ratio in [1e-4, 2]");
  if (!std::isfinite(rig.voltage_min_v)) Violated("rig.voltage_min_v", rig.voltage_min_v, "finite");
  if (!std::isfinite(rig.voltage_max_v) || !(rig.voltage_max_v > rig.voltage_min_v))
    Violated("rig.voltage_max_v", rig.voltage_max_v,
             "voltage_max_v > voltage_min_v = " + G(rig.voltage_min_v));
  if (rig.dac_bits < 1 || rig.dac_bits > 32)
    Violated("rig.dac_bits", rig.dac_bits, "dac_bits in 1..32");
  // The reading is round((x + n) / q) q: a q near 1e-320 made the count overflow into inf
  // (1e-20, far below any sensor, reads effectively unquantised);
  // noise past 1 mm (a stack moves tens of um) makes the readings meaningless and, near
  // 1e300, inf.
  if (!std::isfinite(rig.sensor_resolution_m) || !(rig.sensor_resolution_m >= 1e-20) ||
      rig.sensor_resolution_m > 1e-3)
    Violated("rig.sensor_resolution_m", rig.sensor_resolution_m,
             "1e-20 <= sensor_resolution_m <= 1e-3");
  if (!std::isfinite(rig.sensor_noise_m) || rig.sensor_noise_m < 0 || rig.sensor_noise_m > 1e-3)
    Violated("rig.sensor_noise_m", rig.sensor_noise_m, "0 <= sensor_noise_m <= 1e-3");
  if (!std::isfinite(integrator.relative_tolerance) || integrator.relative_tolerance < 1e-14 ||
      integrator.relative_tolerance > 1e-2)
    Violated("integrator.relative_tolerance", integrator.relative_tolerance,
             "relative_tolerance in [1e-14, 1e-2]");
  if (!std::isfinite(integrator.position_tolerance_m) || !(integrator.position_tolerance_m > 0))
    Violated("integrator.position_tolerance_m", integrator.position_tolerance_m,
             "position_tolerance_m > 0");
}

PiParameters StackParameters::HysteresisPi() const {
  PiParameters p;
  p.form = PiForm::kRateDependent;
  p.thresholds = hysteresis.thresholds_v;
  p.weights = hysteresis.weights_m_per_v;
  p.polynomial = {hysteresis.linear_gain_m_per_v};
  p.rate_weights = hysteresis.rate_weights_m_s_per_v2;
  p.offset_m = 0;
  p.initial_input_v = 0;
  p.input_min_v = rig.voltage_min_v;
  p.input_max_v = rig.voltage_max_v;
  return p;
}

StackParameters StackWithHysteresis(const StackParameters& base, const PiParameters& model,
                                    const std::string& model_name) {
  if (model.form == PiForm::kPolynomial)
    throw OptionsError(model_name + ": a gpi model's input polynomial has no form in the stack's "
                       "hysteresis (rate-dependent PI: p0 u + sum w_i F_ri[u]); fit pi or rdpi");
  StackParameters s = base;
  s.name = "piezo stack with the hysteresis of " + model_name;
  s.hysteresis.linear_gain_m_per_v = model.polynomial.empty() ? 0.0 : model.polynomial[0];
  s.hysteresis.thresholds_v = model.thresholds;
  s.hysteresis.weights_m_per_v = model.weights;
  s.hysteresis.rate_weights_m_s_per_v2 = model.form == PiForm::kRateDependent
                                             ? model.rate_weights
                                             : std::vector<double>(model.thresholds.size() + 1, 0.0);
  try {
    s.Validate();
  } catch (const OptionsError& e) {
    throw OptionsError(model_name + " is not a stack's hysteresis: " + e.what());
  }
  return s;
}

double StackParameters::MaxStaticGain() const {
  double g = hysteresis.linear_gain_m_per_v;
  for (double w : hysteresis.weights_m_per_v) g += w;
  double creep_gain = 1;
  for (double kappa : creep.fractions) creep_gain += kappa;
  return g * creep_gain;
}

}  // namespace sysid
