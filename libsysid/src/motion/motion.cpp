// Velocity and acceleration of a recording, from its position or a measured-velocity column.
#include "sysid/motion.hpp"

#include <fmt/format.h>

#include <cmath>
#include <utility>

#include "core/option_rule.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"
#include "sysid/signal.hpp"

namespace sysid {

void MotionOptions::Validate() const {
  if (!(max_relative_jitter >= 0) || !std::isfinite(max_relative_jitter))
    internal::FailOption("MotionOptions", "max_relative_jitter", max_relative_jitter,
                         "max_relative_jitter >= 0");
  if (velocity_column.empty())
    internal::FailOption("MotionOptions", "velocity_column", "empty", "a column name");
}

namespace {

// `t` is `recording`'s time column; the error names the file line of the interval's end.
double CheckedSampleInterval(const Recording& recording, const Eigen::VectorXd& t,
                             double max_relative_jitter, Eigen::VectorXd* scratch) {
  const SamplingReport s = AnalyzeSampling(t, max_relative_jitter, scratch);
  if (s.irregular)
    throw InputError(fmt::format(
        "{}: irregular sampling: interval {:.6g} s deviates {:.3g} % from the nominal "
        "{:.6g} s (allowed {:.3g} %); resample first (sysid::Resample, sysid derive --resample)",
        recording.where(s.worst_index + 1), t[s.worst_index + 1] - t[s.worst_index],
        100 * s.max_relative_jitter, s.nominal_dt_s, 100 * max_relative_jitter));
  return s.nominal_dt_s;
}

}  // namespace

double UniformSampleInterval(const Recording& recording, double max_relative_jitter) {
  const Eigen::VectorXd t = recording.column("t");
  Eigen::VectorXd scratch;
  return CheckedSampleInterval(recording, t, max_relative_jitter, &scratch);
}

MotionSignals ExtractMotion(const Recording& recording, const MotionOptions& options) {
  MotionSignals m;
  ExtractMotion(recording, options, &m);
  return m;
}

void ExtractMotion(const Recording& recording, const MotionOptions& options, MotionSignals* out) {
  options.Validate();
  MotionSignals& m = *out;
  m.source = recording.source;
  if (recording.rows() < 3)
    throw InputError(fmt::format("{}: {} samples: at least 3 are needed to differentiate",
                                 recording.source, recording.rows()));
  m.t_s = recording.column("t");
  m.u_v = recording.column("u");
  // a_mps2 is computed last; until then its storage is the sampling check's scratch.
  m.dt_s = CheckedSampleInterval(recording, m.t_s, options.max_relative_jitter, &m.a_mps2);
  m.velocity_from = MotionSource(recording, options);
  if (m.velocity_from.rfind("column", 0) == 0) {
    m.v_mps = recording.column(options.velocity_column);
    if (recording.has("x")) {
      m.x_m = recording.column("x");
    } else {
      m.x_m.resize(0);
    }
    if (options.prefer_velocity_column && recording.has("a")) {
      m.a_mps2 = recording.column("a");  // the data set's own acceleration, as it is
      return;
    }
    // The velocity is measured: the acceleration is its derivative with the chosen filter.
    const DerivativeOptions& d = options.derivative;
    d.Validate(m.dt_s);
    switch (d.method) {
      case DerivativeMethod::kCentral:
        CentralDifference(m.v_mps, m.dt_s, &m.a_mps2);
        break;
      case DerivativeMethod::kButterworthCentral:
        m.a_mps2 = CentralDifference(
            ButterworthFiltFilt(m.v_mps, m.dt_s, d.cutoff_hz, d.butterworth_order), m.dt_s);
        break;
      case DerivativeMethod::kSavitzkyGolay:
        m.a_mps2 = SavitzkyGolay(m.v_mps, m.dt_s, d.savgol_window, d.savgol_order, 1);
        break;
    }
    return;
  }
  m.x_m = recording.column("x");
  if (options.derivative.method == DerivativeMethod::kCentral) {
    // Differentiate's central path (v = D x, a = D v) without its copy of x.
    options.derivative.Validate(m.dt_s);
    CentralDifference(m.x_m, m.dt_s, &m.v_mps);
    CentralDifference(m.v_mps, m.dt_s, &m.a_mps2);
  } else {
    Derivatives d = Differentiate(m.x_m, m.dt_s, options.derivative);
    m.v_mps = std::move(d.v_mps);
    m.a_mps2 = std::move(d.a_mps2);
  }
}

std::string MotionSource(const Recording& recording, const MotionOptions& options) {
  const bool has_v = recording.has(options.velocity_column), has_x = recording.has("x");
  if (has_v && (options.prefer_velocity_column || !has_x)) {
    if (options.prefer_velocity_column && recording.has("a"))
      return "columns " + options.velocity_column + ", a";
    return "column " + options.velocity_column + " (a: " +
           ToString(options.derivative.method) + ")";
  }
  if (!has_x)
    throw InputError(fmt::format("{}: no position column 'x' and no velocity column '{}'",
                                 recording.source, options.velocity_column));
  return "x (" + ToString(options.derivative.method) + ")";
}

double AddDerivatives(Recording& recording, double dt_s, const DerivativeOptions& derivative,
                      int decimate) {
  if (decimate < 1) internal::FailOption("AddDerivatives", "decimate", decimate, "decimate >= 1");
  derivative.Validate(dt_s * decimate);
  if (decimate != 1) {
    recording = DecimateRecording(recording, dt_s, decimate);
    dt_s *= decimate;
  }
  const Derivatives d = Differentiate(recording.column("x"), dt_s, derivative);
  recording.SetColumn("v", d.v_mps);
  recording.SetColumn("a", d.a_mps2);
  return dt_s;
}

std::string DescribeDerivative(const DerivativeOptions& derivative, int decimate) {
  const DerivativeOptions& o = derivative;
  std::string s = "method=" + ToString(o.method);
  if (o.method == DerivativeMethod::kButterworthCentral)
    s += fmt::format(" cutoff_hz={} order={}", o.cutoff_hz, o.butterworth_order);
  if (o.method == DerivativeMethod::kSavitzkyGolay)
    s += fmt::format(" window={} order={}", o.savgol_window, o.savgol_order);
  if (decimate > 1) s += fmt::format(" decimate={}", decimate);
  return s;
}

}  // namespace sysid
