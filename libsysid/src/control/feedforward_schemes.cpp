// The tracking experiment's feedforward schemes, run on the virtual stage (one loop for
// `sysid track`, the pipeline and the stage facts).
#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <sstream>
#include <utility>

#include "control/scheme_loop.hpp"
#include "sysid/compare.hpp"
#include "sysid/control.hpp"
#include "sysid/error.hpp"
#include "sysid/hysteresis_model.hpp"
#include "sysid/model.hpp"
#include "sysid/model_stepper.hpp"
#include "sysid/nn.hpp"
#include "sysid/nn_stepper.hpp"
#include "sysid/stage.hpp"

namespace sysid {

std::string ToString(FeedforwardScheme scheme) {
  switch (scheme) {
    case FeedforwardScheme::kNone:
      return "none";
    case FeedforwardScheme::kAnalytic:
      return "analytic";
    case FeedforwardScheme::kNetwork:
      return "nn";
    case FeedforwardScheme::kHysteresis:
      return "hysteresis";
  }
  SYSID_CHECK(false, "unknown FeedforwardScheme value");
}

FeedforwardScheme ParseFeedforwardScheme(const std::string& name) {
  for (auto s : {FeedforwardScheme::kNone, FeedforwardScheme::kAnalytic,
                 FeedforwardScheme::kNetwork, FeedforwardScheme::kHysteresis})
    if (ToString(s) == name) return s;
  throw OptionsError("'" + name + "' is not one of none, analytic, nn, hysteresis");
}

std::vector<FeedforwardScheme> ParseFeedforwardSchemes(const std::string& comma_list) {
  std::vector<FeedforwardScheme> out;
  std::stringstream ss(comma_list);
  std::string item;
  try {
    while (std::getline(ss, item, ',')) out.push_back(ParseFeedforwardScheme(item));
  } catch (const OptionsError& e) {
    throw OptionsError(e.what(), "schemes");
  }
  if (out.empty()) throw OptionsError("expected none, analytic, nn or hysteresis", "schemes");
  return out;
}

bool Uses(const std::vector<FeedforwardScheme>& schemes, FeedforwardScheme scheme) {
  return std::find(schemes.begin(), schemes.end(), scheme) != schemes.end();
}

namespace {

// A stepper run inside the loop: RunClosedLoop calls the feedforward once per sample, in order,
// with the reference at that sample, so each call is the stepper's next Step, as on a real-time
// target (RunClosedLoop refuses a non-finite u, naming the sample).
Feedforward AnalyticStepperFeedforward(const FrictionModel& model, double dt_s,
                                       Eigen::Index samples) {
  auto stepper = std::make_shared<FrictionInverseStepper>(model, dt_s, samples);
  return [stepper](const ReferenceSample& r) { return stepper->Step(r.v_mps, r.a_mps2); };
}

Feedforward NetworkStepperFeedforward(const NeuralNetwork& network) {
  // Which of (v, a) feeds each of the network's inputs, in its order.
  std::vector<bool> is_v;
  for (const auto& input : network.inputs()) {
    if (input.name != "v" && input.name != "a")
      throw InputError("network input '" + input.name +
                       "' is neither v [m/s] nor a [m/s^2]; an inverse-model network takes the "
                       "velocity and/or acceleration");
    is_v.push_back(input.name == "v");
  }
  auto stepper = std::make_shared<NetworkStepper>(network);
  auto inputs = std::make_shared<std::vector<double>>(is_v.size());
  return [stepper, inputs, is_v = std::move(is_v)](const ReferenceSample& r) {
    for (size_t i = 0; i < is_v.size(); ++i) (*inputs)[i] = is_v[i] ? r.v_mps : r.a_mps2;
    return stepper->Step(inputs->data());
  };
}

// The hysteresis inverse stepped on x_ref,k. A real-time target clamps a reference out of the
// model's reach (the stepper does); the experiment refuses it instead, with the batch inverse's
// own error for the references seen so far (Invert is a loop over the same stepper, so it stops
// at this sample), and the loop's run is discarded.
Feedforward HysteresisStepperFeedforward(const HysteresisModel& model, double dt_s,
                                         Eigen::Index samples) {
  std::shared_ptr<HysteresisInverseStepper> stepper = model.InverseStepper(dt_s);
  auto seen = std::make_shared<Eigen::VectorXd>(samples);  // x_ref,0..k: the error path's
  auto k = std::make_shared<Eigen::Index>(0);
  return [&model, dt_s, stepper, seen, k](const ReferenceSample& r) {
    SYSID_CHECK(*k < seen->size(),
                "feedforward called more often than the reference has samples (" +
                    std::to_string(seen->size()) + ")");
    (*seen)[*k] = r.x_m;
    const double u = stepper->Step(r.x_m);
    if (stepper->out_of_range() || !std::isfinite(r.x_m)) {
      model.Invert(seen->head(*k + 1), dt_s);  // throws InputError naming sample k
      SYSID_CHECK(false, "the " + model.kind() + " inverse stepper left its range at sample " +
                             std::to_string(*k) + " but Invert accepted the reference");
    }
    ++*k;
    return u;
  };
}

// The virtual stage, rebuilt for each scheme with the same seed: the same plant and noise.
class StagePlant final : public internal::TrackedPlant {
 public:
  StagePlant(const StageParameters& stage, std::uint64_t seed) : stage_(stage), seed_(seed) {}
  void Reset() override { plant_.emplace(stage_, seed_); }
  double Step(double u_v) override { return plant_->Step(u_v); }
  double measured_position_m() const override { return plant_->measured_position_m(); }
  std::string DescribeLimits() const override { return plant_->status().Describe(); }

 private:
  const StageParameters& stage_;
  std::uint64_t seed_;
  std::optional<VirtualStage> plant_;
};

}  // namespace

Feedforward SchemeFeedforward(FeedforwardScheme scheme, const PositionReference& reference,
                              double dt_s, const InverseModels& models) {
  switch (scheme) {
    case FeedforwardScheme::kNone:
      return {};
    case FeedforwardScheme::kAnalytic:
      if (models.model == nullptr)
        throw OptionsError("SchemeFeedforward: the analytic scheme needs InverseModels::model");
      return AnalyticStepperFeedforward(*models.model, dt_s, reference.v_mps.size());
    case FeedforwardScheme::kNetwork:
      if (models.network == nullptr)
        throw OptionsError("SchemeFeedforward: the nn scheme needs InverseModels::network");
      return NetworkStepperFeedforward(*models.network);
    case FeedforwardScheme::kHysteresis:
      if (models.hysteresis == nullptr)
        throw OptionsError("SchemeFeedforward: the hysteresis scheme needs InverseModels::hysteresis");
      // The model maps voltage to position, so its inverse of the position reference is the
      // voltage that would follow it quasi-statically.
      return HysteresisStepperFeedforward(*models.hysteresis, dt_s, reference.x_m.size());
  }
  SYSID_CHECK(false, "unknown FeedforwardScheme value");
}

namespace internal {

std::vector<SchemeTracking> TrackEachScheme(
    TrackedPlant& plant, const PositionReference& reference, const PiOptions& pi,
    const std::vector<FeedforwardScheme>& schemes, const InverseModels& models,
    const std::function<void(FeedforwardScheme, std::size_t)>& on_scheme) {
  std::vector<SchemeTracking> runs;
  for (std::size_t i = 0; i < schemes.size(); ++i) {
    if (on_scheme) on_scheme(schemes[i], i);
    SchemeTracking run;
    run.scheme = schemes[i];
    const Feedforward ff = SchemeFeedforward(schemes[i], reference, pi.sample_time_s, models);
    plant.Reset();
    run.result = RunClosedLoop([&plant](double u) { return plant.Step(u); },
                               plant.measured_position_m(), reference, pi, ff);
    run.stage_limits = plant.DescribeLimits();
    runs.push_back(std::move(run));
  }
  return runs;
}

}  // namespace internal

std::vector<SchemeTracking> TrackSchemes(
    const StageParameters& stage, std::uint64_t seed, const PositionReference& reference,
    PiOptions pi, const std::vector<FeedforwardScheme>& schemes, const InverseModels& models,
    const std::function<void(FeedforwardScheme, std::size_t)>& on_scheme) {
  pi.sample_time_s = stage.sample_time_s();
  pi.Validate();
  for (auto s : schemes)
    if (s == FeedforwardScheme::kHysteresis)
      throw OptionsError(
          "the hysteresis scheme inverts a voltage-to-position model: it is for the piezo stack "
          "(--plant piezo-stack), not the stage",
          "schemes");
  StagePlant plant(stage, seed);
  return internal::TrackEachScheme(plant, reference, pi, schemes, models, on_scheme);
}

}  // namespace sysid
