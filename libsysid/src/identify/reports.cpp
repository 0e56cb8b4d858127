// FullReport of the identifications: BriefReport plus every diagnostic (Ceres' pattern).
#include <fmt/format.h>

#include <string>

#include "sysid/identify.hpp"

namespace sysid {
namespace {

std::string FitDiagnostics(const LinearFit& fit) {
  std::string s = fmt::format(
      "  fit: {} rows, rank {}, dof {}, condition {:.4g}, rms residual {:.4g}, relative error "
      "{:.4g}\n  R diagonal (identifiability, largest first):",
      fit.rows, fit.rank, fit.dof, fit.condition_number, fit.rms_residual, fit.relative_error);
  for (const auto& [name, r] : fit.r_diagonal) s += fmt::format(" {} {:.4g}", name, r);
  return s + "\n";
}

}  // namespace

std::string PulseIdentificationResult::FullReport() const {
  std::string s = BriefReport() + FitDiagnostics(fit);
  s += fmt::format("  equations: {} (u [V], v [m/s], residual [m/s^2])\n", points.size());
  for (size_t i = 0; i < points.size(); ++i)
    s += fmt::format("    {} u {:.6g} v {:.6g} r {:.4g}\n", points[i].label, points[i].u_v,
                     points[i].v_mps,
                     static_cast<Eigen::Index>(i) < fit.residuals.size()
                         ? fit.residuals[static_cast<Eigen::Index>(i)]
                         : 0.0);
  s += fmt::format("  pulses: {}\n", pulses.size());
  for (const auto& e : pulses)
    s += fmt::format("    {} t {:.6g} s, {:.6g} s, u {:.6g} V: v {:.6g} +- {:.2g} m/s, drift "
                     "{:.3g} m/s, {} samples, {}{}\n",
                     e.pulse.source, e.pulse.t_start_s, e.pulse.duration_s, e.pulse.amplitude_v,
                     e.v_mps, e.v_stderr_mps, e.drift_mps, e.window_samples, ToString(e.status),
                     e.reason.empty() ? "" : ": " + e.reason);
  return s;
}

std::string TrajectoryIdentificationResult::FullReport() const {
  std::string s = BriefReport() + FitDiagnostics(fit);
  s += fmt::format("  velocity filter: {}; offset c0 {:.6g} m/s^2\n", ToString(derivative),
                   offset_mps2);
  s += fmt::format("  delay curve: {} points (tau [s], residual sum of squares [V^2])\n",
                   tau_curve.size());
  for (const auto& [tau, rss] : tau_curve) s += fmt::format("    {:.6g} {:.6g}\n", tau, rss);
  return s;
}

}  // namespace sysid
