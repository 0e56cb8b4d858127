// The tracking experiment on an identified friction model as the plant (`sysid track --plant
// M.json`): the same schemes and loop as on the virtual stage, the plant the model itself.
#include <optional>
#include <string>

#include "control/scheme_loop.hpp"
#include "sysid/control.hpp"
#include "sysid/error.hpp"
#include "sysid/simulate.hpp"

namespace sysid {
namespace {

// The identified model simulated from rest at the reference's start, rebuilt for each scheme;
// its reading is the exact position (no encoder).
class ModelPlant final : public internal::TrackedPlant {
 public:
  ModelPlant(const FrictionModel& model, double sample_time_s, double x0_m)
      : model_(model), sample_time_s_(sample_time_s) {
    start_.x0_m = x0_m;
  }
  void Reset() override { plant_.emplace(model_, sample_time_s_, start_); }
  double Step(double u_v) override { return plant_->Step(u_v); }
  double measured_position_m() const override { return plant_->position_m(); }
  std::string DescribeLimits() const override {
    return "model plant: " + std::to_string(plant_->events()) + " stick/slip events";
  }

 private:
  const FrictionModel& model_;
  double sample_time_s_;
  SimulationOptions start_;
  std::optional<FrictionModelPlant> plant_;
};

}  // namespace

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
  ModelPlant model_plant(plant, sample_time_s,
                         reference.x_m.size() > 0 ? reference.x_m[0] : 0.0);
  return internal::TrackEachScheme(model_plant, reference, pi, schemes, models, on_scheme);
}

}  // namespace sysid
