// The closed-loop runner and its metrics.
#include <cmath>
#include <sstream>

#include "sysid/control.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"
#include "sysid/stage.hpp"

namespace sysid {

std::string TrackingResult::BriefReport() const {
  std::ostringstream s;
  s.precision(4);
  s << "max |e| " << max_error_m * 1e3 << " mm, rms e " << rms_error_m * 1e3 << " mm, rms u "
    << rms_u_v << " V, max |u| " << max_abs_u_v << " V, " << saturated_samples
    << " saturated samples";
  return s.str();
}

std::string TrackingResult::FullReport() const {
  std::ostringstream s;
  s.precision(6);
  s << BriefReport() << "\n  samples " << t_s.size() << ", max |e| " << max_error_m
    << " m, rms e " << rms_error_m << " m, rms u " << rms_u_v << " V, max |u| " << max_abs_u_v
    << " V, total variation of u " << total_variation_v << " V, saturated samples "
    << saturated_samples << "\n";
  return s.str();
}

TrackingResult RunClosedLoop(const PlantStep& plant, double x0_measured_m,
                             const PositionReference& ref, const PiOptions& pi,
                             const Feedforward& feedforward) {
  pi.Validate();
  const Eigen::Index n = ref.x_m.size();
  if (n == 0 || ref.t_s.size() != n || ref.v_mps.size() != n || ref.a_mps2.size() != n)
    throw OptionsError(
        "RunClosedLoop: the reference's t_s, x_m, v_mps, a_mps2 must be equally "
        "long and non-empty (" +
        std::to_string(ref.t_s.size()) + ", " + std::to_string(n) + ", " +
        std::to_string(ref.v_mps.size()) + ", " + std::to_string(ref.a_mps2.size()) + ")");
  if (n >= 2) {
    const double dt = ref.t_s[1] - ref.t_s[0];
    if (std::abs(dt - pi.sample_time_s) > 1e-6 * pi.sample_time_s)
      throw OptionsError("RunClosedLoop: the reference is sampled every " + std::to_string(dt) +
                         " s but PiOptions::sample_time_s = " + std::to_string(pi.sample_time_s));
  }
  PiController controller(pi);
  TrackingResult r;
  r.t_s = ref.t_s;
  r.x_ref_m = ref.x_m;
  r.x_m.resize(n);
  r.e_m.resize(n);
  r.u_v.resize(n);
  r.u_ff_v.resize(n);
  double x = x0_measured_m;
  for (Eigen::Index k = 0; k < n; ++k) {
    const double u_ff = feedforward ? feedforward({ref.x_m[k], ref.v_mps[k], ref.a_mps2[k]}) : 0.0;
    if (!std::isfinite(u_ff))
      throw NumericalError("RunClosedLoop: the feedforward returned " + std::to_string(u_ff) +
                           " at t = " + std::to_string(ref.t_s[k]) +
                           " s (x_ref = " + std::to_string(ref.x_m[k]) +
                           " m, v_ref = " + std::to_string(ref.v_mps[k]) + " m/s)");
    r.x_m[k] = x;
    r.e_m[k] = ref.x_m[k] - x;
    r.u_ff_v[k] = u_ff;
    r.u_v[k] = controller.Update(r.e_m[k], u_ff);
    if (controller.saturated()) ++r.saturated_samples;
    x = plant(r.u_v[k]);
  }
  r.max_error_m = r.e_m.cwiseAbs().maxCoeff();
  r.rms_error_m = std::sqrt(r.e_m.squaredNorm() / static_cast<double>(n));
  r.rms_u_v = std::sqrt(r.u_v.squaredNorm() / static_cast<double>(n));
  r.max_abs_u_v = r.u_v.cwiseAbs().maxCoeff();
  for (Eigen::Index k = 1; k < n; ++k) r.total_variation_v += std::abs(r.u_v[k] - r.u_v[k - 1]);
  return r;
}

TrackingResult RunClosedLoop(VirtualStage& stage, const PositionReference& reference, PiOptions pi,
                             const Feedforward& feedforward) {
  pi.sample_time_s = stage.parameters().sample_time_s();
  return RunClosedLoop([&stage](double u) { return stage.Step(u); }, stage.measured_position_m(),
                       reference, pi, feedforward);
}

Recording TrackingRecording(const TrackingResult& r, const std::string& scheme) {
  Recording rec;
  rec.metadata = {{"ff", scheme}, {"units", "t [s], x_ref [m], x [m], e [m], u [V], u_ff [V]"}};
  rec.SetColumn("t", r.t_s);
  rec.SetColumn("x_ref", r.x_ref_m);
  rec.SetColumn("x", r.x_m);
  rec.SetColumn("e", r.e_m);
  rec.SetColumn("u", r.u_v);
  rec.SetColumn("u_ff", r.u_ff_v);
  return rec;
}

}  // namespace sysid
