// Reference profiles for the tracking experiment.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/option_rule.hpp"
#include "sysid/control.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"
#include "sysid/stage.hpp"

namespace sysid {

void SmoothProfileOptions::Validate() const {
  auto fail = [](const char* field, double v, const char* rule) {
    internal::FailOption("SmoothProfileOptions", field, v, rule);
  };
  if (!std::isfinite(frequency_hz) || !(frequency_hz > 0))
    fail("frequency_hz", frequency_hz, "frequency_hz > 0");
  if (!std::isfinite(amplitude_m) || amplitude_m == 0)
    fail("amplitude_m", amplitude_m, "amplitude_m != 0 and finite");
  if (!(dwell_fraction >= 0 && dwell_fraction < 0.5))
    fail("dwell_fraction", dwell_fraction, "0 <= dwell_fraction < 0.5");
  if (cycles < 1) fail("cycles", cycles, "cycles >= 1");
  if (!std::isfinite(sample_rate_hz) || !(sample_rate_hz > 0))
    fail("sample_rate_hz", sample_rate_hz, "sample_rate_hz > 0");
  // Each move of the profile needs samples to be a profile at all; and the run is bounded
  // before its vectors are allocated.
  if (!(frequency_hz <= sample_rate_hz / 20))
    fail("frequency_hz", frequency_hz, "frequency_hz <= sample_rate_hz / 20 (20 samples a period)");
  if (!(cycles / frequency_hz * sample_rate_hz <= kMaxSignalSamples))
    fail("cycles", cycles, "cycles / frequency_hz * sample_rate_hz <= 2e7 samples (kMaxSignalSamples)");
}

PositionReference MakeStageProfile(const StageParameters& stage, SmoothProfileOptions options) {
  options.sample_rate_hz = stage.rig.sample_rate_hz;
  // The stroke must fit the stage's travel from where it starts.
  const double end = stage.rig.initial_position_m + options.amplitude_m;
  if (!(end >= stage.rig.travel_min_m && end <= stage.rig.travel_max_m))
    internal::FailOption(
        "SmoothProfileOptions", "amplitude_m", fmt::format("{} m", options.amplitude_m),
        fmt::format("the stroke from the start position {} m stays within the "
                    "stage's travel [{}, {}] m",
                    stage.rig.initial_position_m, stage.rig.travel_min_m, stage.rig.travel_max_m));
  return MakeSmoothProfile(options);
}

PositionReference MakeSmoothProfile(const SmoothProfileOptions& o) {
  o.Validate();
  const double period = 1.0 / o.frequency_hz;
  const double dwell = o.dwell_fraction * period;
  const double tm = 0.5 * period - dwell;
  const auto n = static_cast<Eigen::Index>(std::llround(o.cycles * period * o.sample_rate_hz)) + 1;
  PositionReference r;
  r.t_s.resize(n);
  r.x_m.resize(n);
  r.v_mps.resize(n);
  r.a_mps2.resize(n);
  const double A = o.amplitude_m;
  for (Eigen::Index k = 0; k < n; ++k) {
    const double t = static_cast<double>(k) / o.sample_rate_hz;
    double ph = std::fmod(t, period);
    // Phase within the period: [0, dwell) rest at 0, move up, rest at A, move down.
    double x = 0, v = 0, a = 0;
    auto move = [&](double t_in, double from, double to) {
      const double tau = t_in / tm, d = to - from;
      const double t2 = tau * tau, t3 = t2 * tau;
      x = from + d * (10 * t3 - 15 * t3 * tau + 6 * t3 * t2);
      v = d * (30 * t2 - 60 * t3 + 30 * t3 * tau) / tm;
      a = d * (60 * tau - 180 * t2 + 120 * t3) / (tm * tm);
    };
    if (ph < dwell) {
      x = 0;
    } else if (ph < dwell + tm) {
      move(ph - dwell, 0, A);
    } else if (ph < 2 * dwell + tm) {
      x = A;
    } else {
      move(ph - 2 * dwell - tm, A, 0);
    }
    r.t_s[k] = t;
    r.x_m[k] = x;
    r.v_mps[k] = v;
    r.a_mps2[k] = a;
  }
  std::ostringstream d;
  d << "smooth back-and-forth, " << o.frequency_hz << " Hz, stroke " << A * 1e3 << " mm, dwell "
    << o.dwell_fraction << " of the period, " << o.cycles << " cycles";
  r.description = d.str();
  return r;
}

PositionReference ReferenceFromPositions(const Eigen::VectorXd& t_s, const Eigen::VectorXd& x_m) {
  const Eigen::Index n = x_m.size();
  if (t_s.size() != n || n < 3)
    throw InputError("reference: need equally long t and x columns with at least 3 samples (" +
                     std::to_string(t_s.size()) + ", " + std::to_string(n) + ")");
  PositionReference r;
  r.t_s = t_s;
  r.x_m = x_m;
  r.v_mps.resize(n);
  r.a_mps2.resize(n);
  // Central differences on the (possibly non-uniform) grid; one-sided at the ends.
  auto deriv = [&](const Eigen::VectorXd& y, Eigen::VectorXd& out) {
    for (Eigen::Index k = 0; k < n; ++k) {
      const Eigen::Index lo = k == 0 ? 0 : k - 1, hi = k == n - 1 ? n - 1 : k + 1;
      out[k] = (y[hi] - y[lo]) / (t_s[hi] - t_s[lo]);
    }
  };
  deriv(x_m, r.v_mps);
  deriv(r.v_mps, r.a_mps2);
  r.description = "sampled positions";
  return r;
}

PositionReference ReadPositionReference(const std::string& path, const SourceMapping& mapping) {
  ReadOptions ro;
  ro.mapping = mapping;
  ro.required_columns = {"t"};
  ro.any_of_columns = {"x_ref", "x"};
  const Recording r = ReadRecording(path, ro);
  PositionReference ref =
      ReferenceFromPositions(r.column("t"), r.column(r.has("x_ref") ? "x_ref" : "x"));
  ref.description = path;
  return ref;
}

PositionReference ReferenceAtControlRate(const PositionReference& ref, double control_rate_hz) {
  const Eigen::Index n = ref.t_s.size();
  if (n < 2 || !(control_rate_hz > 0)) return ref;
  const double span = ref.t_s[n - 1] - ref.t_s[0];
  const double dt = span / static_cast<double>(n - 1);  // [s] the reference's step
  for (Eigen::Index k = 1; k < n; ++k)
    if (std::abs(ref.t_s[k] - ref.t_s[k - 1] - dt) > 1e-6 * dt) return ref;  // not uniform
  const double ratio = dt * control_rate_hz;
  const double r = std::round(ratio);
  if (r < 2 || std::abs(ratio - r) > 1e-6 * r) return ref;  // at the rate, faster, or no divisor
  if (static_cast<double>(n - 1) * r + 1 > kMaxReferenceSamples)
    throw InputError(fmt::format(
        "{}: {} samples at {:g} Hz make {:.4g} at the control rate {:g} Hz, more than the {:g} a "
        "reference may hold",
        ref.description, n, 1 / dt, static_cast<double>(n - 1) * r + 1, control_rate_hz,
        kMaxReferenceSamples));
  const auto steps = static_cast<Eigen::Index>(r);
  const Eigen::Index m = (n - 1) * steps + 1;
  PositionReference out;
  out.description = ref.description;
  out.t_s.resize(m);
  out.x_m.resize(m);
  out.v_mps.resize(m);
  out.a_mps2.resize(m);
  for (Eigen::Index i = 0; i < m; ++i) {
    const Eigen::Index k = std::min(i / steps, n - 2);  // the interval [t_k, t_k+1]
    const double w = static_cast<double>(i - k * steps) / r;  // 0 at t_k, 1 at t_k+1
    const auto lerp = [&](const Eigen::VectorXd& y) { return (1 - w) * y[k] + w * y[k + 1]; };
    out.t_s[i] = lerp(ref.t_s);
    out.x_m[i] = lerp(ref.x_m);
    out.v_mps[i] = lerp(ref.v_mps);
    out.a_mps2[i] = lerp(ref.a_mps2);
  }
  return out;
}

void CheckReferenceForPlant(const PositionReference& ref, double control_rate_hz, double x_min_m,
                            double x_max_m) {
  const Eigen::Index n = ref.t_s.size();
  const double dt = 1.0 / control_rate_hz;
  for (Eigen::Index k = 1; k < n; ++k) {
    const double step = ref.t_s[k] - ref.t_s[k - 1];
    if (std::abs(step - dt) > 1e-6 * dt)
      throw InputError(fmt::format(
          "{}: reference sample {} (t = {:.9g} s) comes {:.9g} s after the one before; the plant "
          "takes one reference sample per control period, 1 / {:g} Hz = {:.9g} s: give the "
          "reference at {:g} Hz, or uniformly at a rate that divides it ({:g} / R Hz, R whole; "
          "it is then interpolated linearly)",
          ref.description, k + 1, ref.t_s[k], step, control_rate_hz, dt, control_rate_hz,
          control_rate_hz));
  }
  for (Eigen::Index k = 0; k < n; ++k)
    if (!(ref.x_m[k] >= x_min_m && ref.x_m[k] <= x_max_m))
      throw InputError(fmt::format(
          "{}: reference sample {} (t = {:.9g} s): x_ref = {:g} m is outside the plant's travel "
          "[{:g}, {:g}] m",
          ref.description, k + 1, ref.t_s[k], ref.x_m[k], x_min_m, x_max_m));
}

}  // namespace sysid
