// The paper's workflow on recordings: detect pulses, estimate plateaus, fit the table.
#include <fmt/format.h>

#include <string>
#include <vector>

#include "sysid/error.hpp"
#include "sysid/identify.hpp"

namespace sysid {

void PulseIdentificationOptions::Validate() const {
  motion.Validate();
  detection.Validate();
  plateau.Validate();
  fit.Validate();
}

PulseIdentificationResult IdentifyFromPulses(const std::vector<Recording>& recordings,
                                             const PulseIdentificationOptions& options) {
  options.Validate();
  if (recordings.empty()) throw OptionsError("IdentifyFromPulses: no recordings given");
  std::vector<PulseEstimate> all;
  std::vector<PulsePoint> points;
  for (const Recording& rec : recordings) {
    const MotionSignals m = ExtractMotion(rec, options.motion);
    const auto pulses = DetectPulses(m.t_s, m.u_v, options.detection, rec.source);
    auto estimates = EstimatePlateaus(m, pulses, options.plateau);
    for (size_t i = 0; i < estimates.size(); ++i) {
      const auto& e = estimates[i];
      if (e.usable())
        points.push_back(
            {e.pulse.amplitude_v, e.v_mps,
             fmt::format("{} pulse {} (t = {:.6g} s)", rec.source, i + 1, e.pulse.t_start_s)});
      all.push_back(e);
    }
  }
  if (all.empty())
    throw NumericalError(fmt::format(
        "a1p, a1n, a2p, a2n: no pulses found (u must hold a non-zero value for at least {} s)",
        options.detection.min_duration_s));
  try {
    PulseIdentificationResult r = FitPulseTable(points, options.fit);
    r.pulses = std::move(all);
    return r;
  } catch (const NumericalError& e) {
    // Say how many pulses were dropped and why: that is usually the real cause.
    size_t excluded = 0;
    std::string first_reason;
    for (const auto& p : all)
      if (!p.usable()) {
        if (excluded++ == 0)
          first_reason = fmt::format(" (first: {} at t = {:.6g} s: {})", p.pulse.source,
                                     p.pulse.t_start_s, p.reason);
      }
    if (excluded == 0) throw;
    throw NumericalError(fmt::format("{}; {} of {} pulses were excluded{}", e.what(), excluded,
                                     all.size(), first_reason));
  }
}

}  // namespace sysid
