// The tracking experiment on an identified friction model as the plant (`sysid track --plant
// M.json`): the same schemes and loop as on the virtual stage, the plant the model itself.
#include <string>

#include "control/scheme_loop.hpp"
#include "sysid/control.hpp"
#include "sysid/error.hpp"
#include "sysid/simulate.hpp"

namespace sysid {

std::vector<SchemeTracking> TrackModelSchemes(
    const FrictionModel& plant, double sample_time_s, const PositionReference& reference,
    PiOptions pi, const std::vector<FeedforwardScheme>& schemes, const InverseModels& models,
    const std::function<void(FeedforwardScheme, std::size_t)>& on_scheme) {
  pi.sample_time_s = sample_time_s;
  pi.Validate();
  plant.Validate();
  for (auto s : schemes)
    if (s == FeedforwardScheme::kHysteresis)
      throw OptionsError(
          "the hysteresis scheme inverts a voltage-to-position model: it is for the piezo stack "
          "(--plant piezo-stack), not a friction model",
          "schemes");
  return internal::TrackEachScheme(
      reference, pi, schemes, models, on_scheme, [&](const Feedforward& ff, SchemeTracking* run) {
        SimulationOptions start;
        start.x0_m = reference.x_m.size() > 0 ? reference.x_m[0] : 0.0;
        FrictionModelPlant model_plant(plant, sample_time_s, start);
        run->result = RunClosedLoop([&model_plant](double u) { return model_plant.Step(u); },
                                    model_plant.position_m(), reference, pi, ff);
        run->stage_limits =
            "model plant: " + std::to_string(model_plant.events()) + " stick/slip events";
      });
}

}  // namespace sysid
