// The discrete PI law with conditional-integration anti-windup (see control.hpp).
#include <algorithm>
#include <cmath>

#include "core/option_rule.hpp"
#include "sysid/control.hpp"
#include "sysid/error.hpp"

namespace sysid {
namespace {
[[noreturn]] void Violated(const char* field, double value, const char* rule) {
  internal::FailOption("PiOptions", field, value, rule);
}
}  // namespace

void PiOptions::Validate() const {
  if (!std::isfinite(kp_v_per_m) || kp_v_per_m < 0)
    Violated("kp_v_per_m", kp_v_per_m, "kp_v_per_m >= 0 and finite");
  if (!std::isfinite(ki_v_per_m_s) || ki_v_per_m_s < 0)
    Violated("ki_v_per_m_s", ki_v_per_m_s, "ki_v_per_m_s >= 0 and finite");
  if (!std::isfinite(sample_time_s) || !(sample_time_s > 0))
    Violated("sample_time_s", sample_time_s, "sample_time_s > 0");
  if (!std::isfinite(u_max_v) || !(u_max_v > 0)) Violated("u_max_v", u_max_v, "u_max_v > 0");
}

PiOptions PiOptions::ForActuatorDelayStage() {
  PiOptions o;
  o.kp_v_per_m = 3000;
  o.ki_v_per_m_s = 104100;
  return o;
}

PiController::PiController(const PiOptions& options) : options_(options) { options_.Validate(); }

void PiController::Reset() {
  integral_m_s_ = 0;
  saturated_ = false;
}

double PiController::Update(double e, double u_ff) {
  const PiOptions& o = options_;
  const double candidate_integral = integral_m_s_ + o.sample_time_s * e;
  const double u_free = o.kp_v_per_m * e + o.ki_v_per_m_s * candidate_integral + u_ff;
  bool integrate = true;
  if (o.anti_windup == AntiWindup::kConditionalIntegration) {
    // Skip the integral step only when it would drive an already clipped output further out.
    if ((u_free > o.u_max_v && e > 0) || (u_free < -o.u_max_v && e < 0)) integrate = false;
  }
  if (integrate) integral_m_s_ = candidate_integral;
  const double u = o.kp_v_per_m * e + o.ki_v_per_m_s * integral_m_s_ + u_ff;
  const double clipped = std::clamp(u, -o.u_max_v, o.u_max_v);
  saturated_ = clipped != u;
  return clipped;
}

}  // namespace sysid
