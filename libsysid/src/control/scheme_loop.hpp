// Private: the loop over the feedforward schemes that every tracking experiment runs (the
// virtual stage, an identified model as the plant, the piezo stack); only the plant differs,
// and it enters through TrackedPlant.
#ifndef SYSID_SRC_CONTROL_SCHEME_LOOP_HPP_
#define SYSID_SRC_CONTROL_SCHEME_LOOP_HPP_

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "sysid/control.hpp"

namespace sysid::internal {

/// A plant the scheme loop tracks with: every scheme runs on the same fresh plant (the same
/// parameters, start and noise stream), one control sample per Step.
class TrackedPlant {
 public:
  virtual ~TrackedPlant() = default;
  /// Makes the plant fresh: as built, at t = 0, its noise stream from the start.
  virtual void Reset() = 0;
  /// Holds u_v [V] for one control period; returns the reading [m] at the next sample.
  virtual double Step(double u_v) = 0;
  /// [m] the reading at the current sample.
  virtual double measured_position_m() const = 0;
  /// What the run reached (end stops, clipping, stick/slip events): SchemeTracking::stage_limits.
  virtual std::string DescribeLimits() const = 0;
};

/// Runs `pi` (its sample_time_s the plant's) once per scheme over `reference` on
/// `plant`, Reset before each run: the scheme's feedforward (SchemeFeedforward over `reference`
/// every pi.sample_time_s, built before the plant is reset) and the PI loop (RunClosedLoop, which
/// records the run). `on_scheme` (optional) is told each scheme first.
std::vector<SchemeTracking> TrackEachScheme(
    TrackedPlant& plant, const PositionReference& reference, const PiOptions& pi,
    const std::vector<FeedforwardScheme>& schemes, const InverseModels& models,
    const std::function<void(FeedforwardScheme, std::size_t)>& on_scheme);

}  // namespace sysid::internal

#endif  // SYSID_SRC_CONTROL_SCHEME_LOOP_HPP_
