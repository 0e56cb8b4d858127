// Velocity and acceleration of a recording, from its position or a measured-velocity column.
#include <fmt/format.h>

#include <cmath>

#include "sysid/error.hpp"
#include "sysid/motion.hpp"
#include "sysid/io.hpp"
#include "sysid/signal.hpp"

namespace sysid {

void MotionOptions::Validate() const {
  if (!(max_relative_jitter >= 0) || !std::isfinite(max_relative_jitter))
    throw OptionsError(
        fmt::format("MotionOptions::max_relative_jitter = {}. Violated "
                    "constraint: max_relative_jitter >= 0",
                    max_relative_jitter));
  if (velocity_column.empty())
    throw OptionsError(
        "MotionOptions::velocity_column is empty. Violated constraint: a column "
        "name");
}

MotionSignals ExtractMotion(const Recording& recording, const MotionOptions& options) {
  options.Validate();
  MotionSignals m;
  m.source = recording.source;
  if (recording.rows() < 3)
    throw InputError(fmt::format("{}: {} samples: at least 3 are needed to differentiate",
                                 recording.source, recording.rows()));
  m.t_s = recording.column("t");
  m.u_v = recording.column("u");
  const SamplingReport s = AnalyzeSampling(m.t_s, options.max_relative_jitter);
  if (s.irregular)
    throw InputError(fmt::format(
        "{}:{}: irregular sampling: interval {:.6g} s deviates {:.3g} % from the nominal "
        "{:.6g} s (allowed {:.3g} %); resample first (sysid::Resample)",
        recording.source, s.worst_index + 2, m.t_s[s.worst_index + 1] - m.t_s[s.worst_index],
        100 * s.max_relative_jitter, s.nominal_dt_s, 100 * options.max_relative_jitter));
  m.dt_s = s.nominal_dt_s;
  const bool has_v = recording.has(options.velocity_column);
  const bool use_v = has_v && (options.prefer_velocity_column || !recording.has("x"));
  if (use_v) {
    m.v_mps = recording.column(options.velocity_column);
    if (recording.has("x")) m.x_m = recording.column("x");
    // The velocity is measured: the acceleration is its derivative with the chosen filter.
    const DerivativeOptions& d = options.derivative;
    d.Validate(m.dt_s);
    switch (d.method) {
      case DerivativeMethod::kCentral:
        m.a_mps2 = CentralDifference(m.v_mps, m.dt_s);
        break;
      case DerivativeMethod::kButterworthCentral:
        m.a_mps2 = CentralDifference(
            ButterworthFiltFilt(m.v_mps, m.dt_s, d.cutoff_hz, d.butterworth_order), m.dt_s);
        break;
      case DerivativeMethod::kSavitzkyGolay:
        m.a_mps2 = SavitzkyGolay(m.v_mps, m.dt_s, d.savgol_window, d.savgol_order, 1);
        break;
    }
    m.velocity_from = "column " + options.velocity_column;
    return m;
  }
  if (!recording.has("x"))
    throw InputError(fmt::format("{}: no position column 'x' and no velocity column '{}'",
                                 recording.source, options.velocity_column));
  m.x_m = recording.column("x");
  Derivatives d = Differentiate(m.x_m, m.dt_s, options.derivative);
  m.v_mps = std::move(d.v_mps);
  m.a_mps2 = std::move(d.a_mps2);
  m.velocity_from = "x (" + ToString(options.derivative.method) + ")";
  return m;
}

}  // namespace sysid
