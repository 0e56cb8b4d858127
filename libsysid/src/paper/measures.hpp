// Private: the measures the facts read from a run (F4's ripples, F8's loop widths); the report
// reads the same ones.
#ifndef SYSID_SRC_PAPER_MEASURES_HPP_
#define SYSID_SRC_PAPER_MEASURES_HPP_

#include <Eigen/Core>

#include "sysid/control.hpp"
#include "sysid/identify.hpp"

namespace sysid::paper {

/// F4's ripple amplitude [m] of a PI run on a smooth profile made with `profile`: for every
/// dwell after the first cycle, the last half of the dwell (the reference is at rest and the
/// move's transient has had half a dwell to decay); max over these windows of
/// (max e - min e) / 2.
double RippleAmplitude(const Eigen::VectorXd& e_m, const SmoothProfileOptions& profile);

/// F4 in motion: the RMS of e minus its centred moving average over `window_s` [s] (an odd
/// number of samples, 2 round(window_s rate / 2) + 1), over the samples after the first cycle
/// whose window lies inside e [m], each stroke's breakaway transient left out (from the
/// reference leaving a dwell to `window_s` after the largest |e| in the stroke's first half:
/// the onset error F5 measures), and the frequency [Hz] of the largest peak of that
/// residual's Hann-windowed periodogram, the left-out samples as 0 (0 when there are fewer
/// than 4 samples). Without `ringing_frequency` the periodogram, most of the cost, is skipped
/// and ringing_hz stays 0.
struct MotionRipple {
  double rms_m = 0;            ///< [m]
  double ringing_hz = 0;       ///< [Hz]
  long samples = 0;            ///< samples the RMS is over
  long breakaway_samples = 0;  ///< samples after cycle 1 left out as breakaway transients
};
MotionRipple MotionRippleOf(const Eigen::VectorXd& e_m, const SmoothProfileOptions& profile,
                            double window_s = 0.05, bool ringing_frequency = true);

/// F8: a loop's mean width over both directions [m/s], (area_f + area_b) / (span_f + span_b);
/// NaN when the stage never moved.
double LoopMeanWidth(const VoltageLoop& loop);
/// F8 (a): width / mean(|v_rising|, |v_falling|) at a level; NaN without both branches.
double LoopRelativeWidth(const VoltageLoopLevel& level);
/// F8 (b): max / min of |start forward|, |start backward|; NaN when either never starts.
double StartRatio(const VoltageLoop& loop);

}  // namespace sysid::paper

#endif  // SYSID_SRC_PAPER_MEASURES_HPP_
