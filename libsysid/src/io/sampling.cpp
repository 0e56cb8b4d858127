#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/option_rule.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"

namespace sysid {

SamplingReport AnalyzeSampling(const Eigen::VectorXd& t, double tolerance) {
  Eigen::VectorXd scratch;
  return AnalyzeSampling(t, tolerance, &scratch);
}

SamplingReport AnalyzeSampling(const Eigen::VectorXd& t, double tolerance,
                               Eigen::VectorXd* scratch) {
  if (t.size() < 2) throw InputError("sampling: need at least 2 samples, found " +
                                     std::to_string(t.size()));
  SYSID_CHECK(scratch != &t, "AnalyzeSampling: scratch must not be t");
  const Eigen::Index n = t.size() - 1;
  // The first n values of the scratch; it only grows, so that a caller's buffer of the
  // signal's length (ExtractMotion lends a_mps2) is not reallocated to n and back.
  if (scratch->size() < n) scratch->resize(n);
  double* sorted = scratch->data();
  for (Eigen::Index k = 0; k < n; ++k) sorted[k] = t[k + 1] - t[k];
  // The median, not the mean: a few gaps (dropped samples) must not shift the nominal rate.
  std::nth_element(sorted, sorted + n / 2, sorted + n);
  SamplingReport r;
  r.nominal_dt_s = sorted[n / 2];
  r.sample_rate_hz = 1.0 / r.nominal_dt_s;
  for (Eigen::Index k = 0; k < n; ++k) {
    const double d = std::abs((t[k + 1] - t[k]) - r.nominal_dt_s);
    if (d > r.max_jitter_s) {
      r.max_jitter_s = d;
      r.worst_index = k;
    }
  }
  // Relative to the largest deviation: squares of steps near 1e200 s do not overflow.
  double sum2 = 0;
  if (r.max_jitter_s > 0)
    for (Eigen::Index k = 0; k < n; ++k) {
      const double d = std::abs((t[k + 1] - t[k]) - r.nominal_dt_s) / r.max_jitter_s;
      sum2 += d * d;
    }
  r.rms_jitter_s = r.max_jitter_s * std::sqrt(sum2 / static_cast<double>(n));
  r.max_relative_jitter = r.max_jitter_s / r.nominal_dt_s;
  r.irregular = r.max_relative_jitter > tolerance;
  return r;
}

Recording Resample(const Recording& recording, double rate_hz) {
  if (!(rate_hz > 0) || !std::isfinite(rate_hz))
    internal::FailOption("Resample", "rate_hz", rate_hz, "rate_hz > 0");
  const auto t = recording.column("t");
  if (t.size() < 2) throw InputError(recording.source + ": resampling needs at least 2 rows");
  const double t0 = t[0], t1 = t[t.size() - 1], dt = 1.0 / rate_hz;
  // k * dt rather than accumulated sums: no drift over long records.
  // The grid's size is bounded before allocation: rate x duration (a long gap counts).
  const double samples = std::floor((t1 - t0) / dt * (1 + 1e-12)) + 1;
  if (!(samples <= kMaxSignalSamples))
    internal::FailOption("Resample", "rate_hz",
                         fmt::format("{:.6g} Hz ({:.6g} samples over the {:.6g} s of {})", rate_hz,
                                     samples, t1 - t0, recording.source),
                         "rate_hz x duration <= kMaxSignalSamples = 2e7; lower the rate");
  const auto n = static_cast<Eigen::Index>(samples);
  Recording out;
  out.source = recording.source;
  out.names = recording.names;
  out.metadata = recording.metadata;
  out.metadata.emplace_back("resampled", std::to_string(rate_hz) + " Hz (linear interpolation)");
  out.data.resize(n, recording.data.cols());
  const int ti = recording.index_of("t");
  Eigen::Index j = 0;
  for (Eigen::Index k = 0; k < n; ++k) {
    const double tk = t0 + static_cast<double>(k) * dt;
    while (j + 2 < t.size() && t[j + 1] <= tk) ++j;
    const double w = std::clamp((tk - t[j]) / (t[j + 1] - t[j]), 0.0, 1.0);
    out.data.row(k) = (1 - w) * recording.data.row(j) + w * recording.data.row(j + 1);
    out.data(k, ti) = tk;
  }
  return out;
}

}  // namespace sysid
