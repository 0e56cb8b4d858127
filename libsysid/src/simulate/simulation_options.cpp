// Option checks and names of the simulator's public types.
#include <cmath>
#include <sstream>
#include <string>

#include "core/option_rule.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"
#include "sysid/simulate.hpp"

namespace sysid {
namespace {

void Require(bool ok, const std::string& field, double value, const std::string& rule) {
  if (!ok) internal::FailOption("SimulationOptions", field, value, rule);
}

}  // namespace

void SimulationOptions::Validate() const {
  Require(std::isfinite(t0_s), "t0_s", t0_s, "finite");
  Require(std::isfinite(t_end_s) && t_end_s > t0_s, "t_end_s", t_end_s, "finite, t_end_s > t0_s");
  if (output_times_s.empty()) {
    Require(std::isfinite(dt_out_s) && dt_out_s > 0, "dt_out_s", dt_out_s, "dt_out_s > 0");
    Require((t_end_s - t0_s) / dt_out_s <= kMaxSignalSamples, "dt_out_s", dt_out_s,
            "(t_end_s - t0_s) / dt_out_s <= 2e7 output samples (sysid::kMaxSignalSamples; "
            "asked for " + std::to_string((t_end_s - t0_s) / dt_out_s) + ")");
  }
  for (size_t k = 0; k < output_times_s.size(); ++k) {
    const double t = output_times_s[k];
    const std::string field = "output_times_s[" + std::to_string(k) + "]";
    Require(std::isfinite(t) && t >= t0_s && t <= t_end_s, field, t, "t0_s <= t <= t_end_s");
    if (k > 0) Require(t > output_times_s[k - 1], field, t, "strictly ascending");
  }
  Require(std::isfinite(x0_m), "x0_m", x0_m, "finite");
  Require(std::isfinite(v0_mps), "v0_mps", v0_mps, "finite");
  Require(std::isfinite(history_v_mps), "history_v_mps", history_v_mps, "finite");
  Require(std::isfinite(rtol) && rtol > 0 && rtol < 1, "rtol", rtol, "0 < rtol < 1");
  Require(std::isfinite(atol) && atol > 0, "atol", atol, "atol > 0");
  Require(max_steps >= 1, "max_steps", static_cast<double>(max_steps), "max_steps >= 1");
  Require(std::isfinite(max_step_s) && max_step_s >= 0, "max_step_s", max_step_s,
          "max_step_s >= 0 (0 = automatic)");
  Require(breakpoint_order >= 1 && breakpoint_order <= 8, "breakpoint_order", breakpoint_order,
          "1 <= breakpoint_order <= 8");
  const int order_limit = method == IntegratorMethod::kBdf ? 5 : 12;
  Require(max_order >= 0 && max_order <= order_limit, "max_order", max_order,
          "0 <= max_order <= " + std::to_string(order_limit) + " for " +
              (method == IntegratorMethod::kBdf ? "BDF" : "Adams"));
}

std::string ToString(IntegratorMethod method) {
  return method == IntegratorMethod::kBdf ? "bdf" : "adams";
}

IntegratorMethod ParseIntegratorMethod(const std::string& name) {
  if (name == "adams") return IntegratorMethod::kAdams;
  if (name == "bdf") return IntegratorMethod::kBdf;
  internal::FailOption("", "method", "'" + name + "'", "one of adams, bdf");
}

std::string ToString(EventKind kind) {
  switch (kind) {
    case EventKind::kStick:
      return "stick";
    case EventKind::kSlipForward:
      return "slip+";
    case EventKind::kSlipBackward:
      return "slip-";
    case EventKind::kReverse:
      return "reverse";
    case EventKind::kViscousSwitch:
      return "a1-switch";
  }
  return "unknown";
}

std::string SimulationSummary::BriefReport() const {
  std::ostringstream os;
  os << ToString(termination) << (IsSolutionUsable() ? "" : " (" + cvode_flag + ")") << ": " << steps << " steps, "
     << rhs_evaluations << " rhs evaluations, " << root_evaluations << " root evaluations, "
     << events << " events, " << reinitialisations << " reinitialisations, " << wall_time_s << " s";
  if (!IsSolutionUsable()) os << "; " << message;
  return os.str();
}

}  // namespace sysid
