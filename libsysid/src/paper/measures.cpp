// The measures F4 and F8 read from a run: ripple at rest and in motion, loop widths.
#include "paper/measures.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <unsupported/Eigen/FFT>
#include <vector>

#include "core/option_rule.hpp"
#include "sysid/error.hpp"

namespace sysid::paper {

double RippleAmplitude(const Eigen::VectorXd& e_m, const SmoothProfileOptions& p) {
  const double period = 1.0 / p.frequency_hz, dwell = p.dwell_fraction * period;
  const double tm = 0.5 * period - dwell;
  double ripple = 0;
  for (int c = 1; c < p.cycles; ++c) {
    for (const double start : {c * period, c * period + dwell + tm}) {
      // The last half of the dwell: [start + dwell/2, start + dwell).
      const auto k0 =
          static_cast<Eigen::Index>(std::ceil((start + 0.5 * dwell) * p.sample_rate_hz));
      const auto k1 = std::min<Eigen::Index>(
          e_m.size(), static_cast<Eigen::Index>(std::ceil((start + dwell) * p.sample_rate_hz)));
      if (k1 - k0 < 1) continue;
      const Eigen::VectorXd w = e_m.segment(k0, k1 - k0);
      ripple = std::max(ripple, 0.5 * (w.maxCoeff() - w.minCoeff()));
    }
  }
  return ripple;
}

MotionRipple MotionRippleOf(const Eigen::VectorXd& e_m, const SmoothProfileOptions& p,
                            double window_s, bool ringing_frequency) {
  if (!(window_s > 0) || !std::isfinite(window_s))
    internal::FailOption("MotionRippleOf", "window_s", window_s, "window_s > 0");
  const Eigen::Index n = e_m.size();
  const auto half = static_cast<Eigen::Index>(std::llround(0.5 * window_s * p.sample_rate_hz));
  // After the first cycle, and only where the whole window lies inside the run.
  const Eigen::Index first = std::max(
      half, static_cast<Eigen::Index>(std::ceil(p.sample_rate_hz / p.frequency_hz - 1e-9)));
  const Eigen::Index last = n - half;  // exclusive
  MotionRipple out;
  if (last - first < 1) return out;
  // Centred moving sums from prefix sums (long double: e spans ~1e-4 m over ~1e5 samples).
  std::vector<long double> prefix(static_cast<std::size_t>(n) + 1, 0.0L);
  for (Eigen::Index k = 0; k < n; ++k)
    prefix[static_cast<std::size_t>(k) + 1] = prefix[static_cast<std::size_t>(k)] + e_m[k];
  const auto width = static_cast<long double>(2 * half + 1);
  // Each stroke's breakaway transient is left out: from the reference leaving a dwell to one
  // window after the largest |e| in the stroke's first half. A PI on a dead-zone stage winds
  // up while the stage sticks and overshoots at breakaway; that hump is the tracking error F5
  // measures (the paper's "greatest at the onset of motion"), not a ring, and counting it
  // would fail the paper's own PI row (docs/virtual_stage.md, "F4 in motion at 1 Hz").
  std::vector<bool> left_out(static_cast<std::size_t>(n), false);
  const double period = 1.0 / p.frequency_hz, dwell = p.dwell_fraction * period;
  const double stroke = 0.5 * period - dwell;
  const auto window = static_cast<Eigen::Index>(std::llround(window_s * p.sample_rate_hz));
  for (int c = 0; c < p.cycles; ++c)
    for (const double start : {c * period + dwell, c * period + 2 * dwell + stroke}) {
      const auto k0 = static_cast<Eigen::Index>(std::ceil(start * p.sample_rate_hz - 1e-9));
      const auto k1 = std::min<Eigen::Index>(
          n, static_cast<Eigen::Index>(std::ceil((start + 0.5 * stroke) * p.sample_rate_hz)));
      if (k0 >= k1) continue;
      Eigen::Index peak = 0;
      e_m.segment(k0, k1 - k0).cwiseAbs().maxCoeff(&peak);
      for (Eigen::Index k = k0; k <= std::min(n - 1, k0 + peak + window); ++k)
        left_out[static_cast<std::size_t>(k)] = true;
    }
  std::vector<double> residual(static_cast<std::size_t>(last - first), 0.0);
  double sum2 = 0;
  for (Eigen::Index k = first; k < last; ++k) {
    if (left_out[static_cast<std::size_t>(k)]) {
      ++out.breakaway_samples;
      continue;  // its residual stays 0 in the periodogram below
    }
    const long double mean = (prefix[static_cast<std::size_t>(k + half + 1)] -
                              prefix[static_cast<std::size_t>(k - half)]) /
                             width;
    const double r = e_m[k] - static_cast<double>(mean);
    residual[static_cast<std::size_t>(k - first)] = r;
    sum2 += r * r;
    ++out.samples;
  }
  if (out.samples < 1) return out;
  out.rms_m = std::sqrt(sum2 / static_cast<double>(out.samples));
  if (!ringing_frequency || residual.size() < 4) return out;
  // The ringing frequency: the largest bin of the Hann-windowed periodogram (DC left out).
  const std::size_t m = residual.size();
  for (std::size_t k = 0; k < m; ++k)
    residual[k] *= 0.5 - 0.5 * std::cos(2 * 3.14159265358979323846 * static_cast<double>(k) /
                                        static_cast<double>(m - 1));
  Eigen::FFT<double> fft;
  std::vector<std::complex<double>> spectrum;
  fft.fwd(spectrum, residual);
  std::size_t peak = 1;
  for (std::size_t k = 2; k <= m / 2; ++k)
    if (std::norm(spectrum[k]) > std::norm(spectrum[peak])) peak = k;
  out.ringing_hz = static_cast<double>(peak) * p.sample_rate_hz / static_cast<double>(m);
  return out;
}

double LoopMeanWidth(const VoltageLoop& loop) {
  const double span = loop.span_forward_v + loop.span_backward_v;
  return span > 0 ? (loop.area_forward_v_mps + loop.area_backward_v_mps) / span : std::nan("");
}

double LoopRelativeWidth(const VoltageLoopLevel& level) {
  const double mean = 0.5 * (std::abs(level.v_rising_mps) + std::abs(level.v_falling_mps));
  return mean > 0 ? level.WidthMps() / mean : std::nan("");
}

double StartRatio(const VoltageLoop& loop) {
  const double f = std::abs(loop.start_forward_v), b = std::abs(loop.start_backward_v);
  if (!(f > 0) || !(b > 0)) return std::nan("");
  return std::max(f, b) / std::min(f, b);
}

}  // namespace sysid::paper
