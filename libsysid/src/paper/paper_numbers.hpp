// Private: the numbers the paper printed, which the facts compare the stage's against.
#ifndef SYSID_SRC_PAPER_PAPER_NUMBERS_HPP_
#define SYSID_SRC_PAPER_PAPER_NUMBERS_HPP_

#include <utility>
#include <vector>

#include "sysid/control.hpp"
#include "sysid/model.hpp"

namespace sysid::paper {

/// The pulse table: (amplitude [V], steady velocity [m/s]), as in datasets/paper, in the pulse
/// order of PulseProcedure's default amplitudes.
const std::vector<std::pair<double, double>>& PulseTable();
/// The pulse least squares: a1p 104.0154, a1n 117.1441, a2p 3.1023, a2n 6.8216 (tau = 0).
FrictionModel PulseModel();
constexpr double kTauS = 0.0035;  ///< [s] the paper's delay
/// Max tracking error [m] of the tracking table at 0.5 Hz and 1 Hz for kNone, kAnalytic and
/// kNetwork; NaN for any other frequency or scheme.
double TrackingMaxErrorM(double frequency_hz, FeedforwardScheme scheme);
constexpr double kDominantTrainMseV2 = 0.118161;  ///< [V^2] H = 24
constexpr double kDominantTestMseV2 = 0.052982;   ///< [V^2] H = 24

}  // namespace sysid::paper

#endif  // SYSID_SRC_PAPER_PAPER_NUMBERS_HPP_
