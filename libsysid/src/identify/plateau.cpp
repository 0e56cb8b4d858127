// Steady-state velocity of a pulse: the mean velocity over the end of the pulse, with checks.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/option_rule.hpp"
#include "sysid/error.hpp"
#include "sysid/identify.hpp"

namespace sysid {

std::string ToString(PulseStatus status) {
  switch (status) {
    case PulseStatus::kOk:
      return "ok";
    case PulseStatus::kUnsettled:
      return "unsettled";
    case PulseStatus::kStuck:
      return "stuck";
    case PulseStatus::kWrongDirection:
      return "wrong-direction";
    case PulseStatus::kVelocityLimit:
      return "velocity-limit";
    case PulseStatus::kTravelLimit:
      return "travel-limit";
    case PulseStatus::kTooFewSamples:
      return "too-few-samples";
  }
  return "?";
}

void PlateauOptions::Validate() const {
  auto rule = [](const char* field, double value, const char* what) {
    internal::FailOption("PlateauOptions", field, value, what);
  };
  if (!(window_fraction > 0 && window_fraction <= 1))
    rule("window_fraction", window_fraction, "0 < window_fraction <= 1");
  if (!(settle_tolerance > 0) || !std::isfinite(settle_tolerance))
    rule("settle_tolerance", settle_tolerance, "settle_tolerance > 0");
  if (!(min_speed_mps >= 0) || !std::isfinite(min_speed_mps))
    rule("min_speed_mps", min_speed_mps, "min_speed_mps >= 0 [m/s]");
  if (!(max_speed_mps > min_speed_mps))
    rule("max_speed_mps", max_speed_mps, "max_speed_mps > min_speed_mps [m/s]");
  if (!(travel_max_m > travel_min_m))
    rule("travel_max_m", travel_max_m, "travel_max_m > travel_min_m [m]");
  if (min_window_samples < 3)
    rule("min_window_samples", min_window_samples, "min_window_samples >= 3");
}

namespace {

// Standard error of the mean of a correlated series by non-overlapping batch means: numerical
// differentiation correlates neighbouring samples, so s/sqrt(n) would be too optimistic.
double BatchMeansStdError(const Eigen::VectorXd& y) {
  const Eigen::Index n = y.size();
  const Eigen::Index batches = std::min<Eigen::Index>(10, n / 2);
  if (batches < 2) return std::numeric_limits<double>::quiet_NaN();
  const Eigen::Index len = n / batches;
  Eigen::VectorXd means(batches);
  for (Eigen::Index b = 0; b < batches; ++b) means[b] = y.segment(b * len, len).mean();
  const double m = means.mean();
  const double var = (means.array() - m).square().sum() / static_cast<double>(batches - 1);
  return std::sqrt(var / static_cast<double>(batches));
}

}  // namespace

std::vector<PulseEstimate> EstimatePlateaus(const MotionSignals& motion,
                                            const std::vector<Pulse>& pulses,
                                            const PlateauOptions& options) {
  options.Validate();
  std::vector<PulseEstimate> out;
  for (const Pulse& p : pulses) {
    PulseEstimate e;
    e.pulse = p;
    const Eigen::Index len = p.end_row - p.first_row;
    const Eigen::Index wlen =
        static_cast<Eigen::Index>(std::floor(options.window_fraction * static_cast<double>(len)));
    e.window_samples = static_cast<int>(wlen);
    if (wlen < options.min_window_samples) {
      e.status = PulseStatus::kTooFewSamples;
      e.reason =
          fmt::format("plateau window has {} samples (< {})", wlen, options.min_window_samples);
      out.push_back(std::move(e));
      continue;
    }
    const Eigen::Index w0 = p.end_row - wlen;
    const Eigen::VectorXd v = motion.v_mps.segment(w0, wlen);
    const Eigen::VectorXd t = motion.t_s.segment(w0, wlen);
    e.v_mps = v.mean();
    e.v_stderr_mps = BatchMeansStdError(v);
    // Straight-line fit v = c0 + c1 (t - tbar): c1 T_w is the drift across the window.
    const Eigen::ArrayXd tc = t.array() - t.mean();
    const double sxx = tc.square().sum();
    const double c1 = (tc * (v.array() - e.v_mps)).sum() / sxx;
    const double span = t[wlen - 1] - t[0];
    e.drift_mps = c1 * span;
    const double res_var =
        ((v.array() - e.v_mps) - c1 * tc).square().sum() / static_cast<double>(wlen - 2);
    const double drift_se = std::sqrt(res_var / sxx) * span;
    const double vmax_pulse = motion.v_mps.segment(p.first_row, len).cwiseAbs().maxCoeff();
    const Eigen::Index last = p.end_row - 1;
    auto fail = [&](PulseStatus s, std::string why) {
      e.status = s;
      e.reason = std::move(why);
    };
    if (vmax_pulse > options.max_speed_mps) {
      fail(PulseStatus::kVelocityLimit, fmt::format("|v| reaches {:.4g} m/s > max_speed_mps {:.4g}",
                                                    vmax_pulse, options.max_speed_mps));
    } else if (motion.x_m.size() > 0 &&
               (motion.x_m.segment(p.first_row, len).maxCoeff() >= options.travel_max_m ||
                motion.x_m.segment(p.first_row, len).minCoeff() <= options.travel_min_m)) {
      fail(PulseStatus::kTravelLimit,
           fmt::format("position leaves the travel range [{:.6g}, {:.6g}] m", options.travel_min_m,
                       options.travel_max_m));
    } else if (std::abs(e.v_mps) < options.min_speed_mps) {
      fail(PulseStatus::kStuck,
           vmax_pulse > 10 * options.min_speed_mps
               ? fmt::format("moved (|v| up to {:.4g} m/s) but stopped while driven: end stop "
                             "or travel limit?",
                             vmax_pulse)
               : fmt::format("never moved: |v| = {:.3g} m/s < min_speed_mps {:.3g} (u below "
                             "breakaway?)",
                             std::abs(e.v_mps), options.min_speed_mps));
    } else if ((e.v_mps > 0) != (p.amplitude_v > 0)) {
      fail(PulseStatus::kWrongDirection,
           fmt::format("v = {:.4g} m/s opposes u = {:.4g} V", e.v_mps, p.amplitude_v));
    } else if (std::abs(e.drift_mps) >
               options.settle_tolerance * std::abs(e.v_mps) + 3 * drift_se) {
      fail(PulseStatus::kUnsettled,
           fmt::format("never settles: v drifts {:.3g} m/s ({:.2g} %) across the plateau window "
                       "(t = {:.6g} .. {:.6g} s); allowed {:.2g} %",
                       e.drift_mps, 100 * e.drift_mps / e.v_mps, t[0], motion.t_s[last],
                       100 * options.settle_tolerance));
    }
    out.push_back(std::move(e));
  }
  return out;
}

}  // namespace sysid
