// Private: the loop over the feedforward schemes that every tracking experiment runs (the
// virtual stage, an identified model as the plant, the piezo stack); only the plant differs.
#ifndef SYSID_SRC_CONTROL_SCHEME_LOOP_HPP_
#define SYSID_SRC_CONTROL_SCHEME_LOOP_HPP_

#include <cstddef>
#include <functional>
#include <vector>

#include "sysid/control.hpp"

namespace sysid::internal {

/// Runs `pi` with each scheme's feedforward (SchemeFeedforward over `reference` every
/// `pi.sample_time_s`) on a fresh plant: `run_on_fresh_plant` builds the plant, runs the loop and
/// fills the run's result and stage_limits. `on_scheme` (optional) is told each scheme first.
std::vector<SchemeTracking> TrackEachScheme(
    const PositionReference& reference, const PiOptions& pi,
    const std::vector<FeedforwardScheme>& schemes, const InverseModels& models,
    const std::function<void(FeedforwardScheme, std::size_t)>& on_scheme,
    const std::function<void(const Feedforward& ff, SchemeTracking* run)>& run_on_fresh_plant);

}  // namespace sysid::internal

#endif  // SYSID_SRC_CONTROL_SCHEME_LOOP_HPP_
