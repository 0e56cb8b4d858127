// Decimation behind a zero-phase anti-alias low-pass.
#include <string>

#include "core/option_rule.hpp"
#include "signal/checks.hpp"
#include "sysid/error.hpp"
#include "sysid/signal.hpp"

namespace sysid {

Eigen::VectorXd Decimate(const Eigen::VectorXd& y, double dt_s, int factor) {
  internal::CheckSampleInterval("Decimate", dt_s);
  if (factor < 1) internal::FailOption("Decimate", "factor", factor, "factor >= 1");
  if (factor == 1) return y;
  const double cutoff_hz = kDecimateCutoffFraction * 0.5 / (factor * dt_s);
  const Eigen::VectorXd filtered =
      ButterworthFiltFilt(y, dt_s, cutoff_hz, kDecimateButterworthOrder);
  const Eigen::Index m = (y.size() + factor - 1) / factor;
  Eigen::VectorXd out(m);
  for (Eigen::Index i = 0; i < m; ++i) out[i] = filtered[i * factor];
  return out;
}

Recording DecimateRecording(const Recording& recording, double dt_s, int factor) {
  Recording out;
  out.source = recording.source;
  out.metadata = recording.metadata;
  for (size_t c = 0; c < recording.names.size(); ++c) {
    const Eigen::VectorXd column = recording.data.col(static_cast<Eigen::Index>(c));
    Eigen::VectorXd kept;
    if (recording.names[c] == "t") {  // time is subsampled, never filtered
      internal::CheckSampleInterval("DecimateRecording", dt_s);
      if (factor < 1) internal::FailOption("DecimateRecording", "factor", factor, "factor >= 1");
      kept.resize((column.size() + factor - 1) / factor);
      for (Eigen::Index i = 0; i < kept.size(); ++i) kept[i] = column[i * factor];
    } else {
      kept = Decimate(column, dt_s, factor);
    }
    out.SetColumn(recording.names[c], kept);
  }
  return out;
}

}  // namespace sysid
