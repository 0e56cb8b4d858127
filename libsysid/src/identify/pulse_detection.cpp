// Pulses: runs of constant non-zero u.
#include <fmt/format.h>

#include <cmath>

#include "core/option_rule.hpp"
#include "sysid/error.hpp"
#include "sysid/identify.hpp"

namespace sysid {

void PulseDetectionOptions::Validate() const {
  auto rule = [](const char* field, double value, const char* what) {
    internal::FailOption("PulseDetectionOptions", field, value, what);
  };
  if (!(min_duration_s > 0) || !std::isfinite(min_duration_s))
    rule("min_duration_s", min_duration_s, "min_duration_s > 0 [s]");
  if (!(u_tolerance_v >= 0) || !std::isfinite(u_tolerance_v))
    rule("u_tolerance_v", u_tolerance_v, "u_tolerance_v >= 0 [V]");
  if (!(zero_tolerance_v >= 0) || !std::isfinite(zero_tolerance_v))
    rule("zero_tolerance_v", zero_tolerance_v, "zero_tolerance_v >= 0 [V]");
}

std::vector<Pulse> DetectPulses(const Eigen::VectorXd& t_s, const Eigen::VectorXd& u_v,
                                const PulseDetectionOptions& options, const std::string& source) {
  options.Validate();
  SYSID_CHECK(t_s.size() == u_v.size(), "t and u lengths differ");
  std::vector<Pulse> pulses;
  const Eigen::Index n = u_v.size();
  if (n < 2) return pulses;
  const double dt_last = t_s[n - 1] - t_s[n - 2];
  Eigen::Index k = 0;
  while (k < n) {
    const double level = u_v[k];
    Eigen::Index end = k + 1;
    while (end < n && std::abs(u_v[end] - level) <= options.u_tolerance_v) ++end;
    if (std::abs(level) > options.zero_tolerance_v) {
      Pulse p;
      p.source = source;
      p.first_row = k;
      p.end_row = end;
      p.t_start_s = t_s[k];
      // The pulse lasts until the next, different value; the last one until one interval
      // past the last sample.
      p.duration_s = (end < n ? t_s[end] : t_s[n - 1] + dt_last) - t_s[k];
      p.amplitude_v = u_v.segment(k, end - k).mean();
      p.at_record_start = k == 0;
      p.at_record_end = end == n;
      if (p.duration_s >= options.min_duration_s * (1 - 1e-9)) pulses.push_back(p);
    }
    k = end;
  }
  return pulses;
}

}  // namespace sysid
