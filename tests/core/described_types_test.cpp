// Every described struct (sysid/serialize.hpp) against its own field list: each field is moved
// off its default by a rule that knows nothing of the struct (numbers shifted, flags flipped,
// strings and lists extended, enums stepped), the struct is written, read back over a default
// one and written again. The reference is the perturbed struct itself: the second text must
// equal the first, and every key must differ from the default's text, so a field the reader
// drops, or that the writer leaves out, fails here.
#include <Eigen/Core>
#include <catch2/catch.hpp>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "control/control_json.hpp"
#include "core/json_fields.hpp"
#include "dominance/dominance_json.hpp"
#include "hysteresis/hysteresis_json.hpp"
#include "identify/identify_json.hpp"
#include "nn/nn_json.hpp"
#include "signal/signal_json.hpp"
#include "simulate/simulate_json.hpp"
#include "stack/stack_json.hpp"
#include "sysid/compare.hpp"
#include "sysid/compare_stack.hpp"
#include "sysid/control.hpp"
#include "sysid/control_tuning.hpp"
#include "sysid/delay.hpp"
#include "sysid/dominance.hpp"
#include "sysid/hysteresis.hpp"
#include "sysid/hysteresis_bouc_wen.hpp"
#include "sysid/hysteresis_model.hpp"
#include "sysid/identify.hpp"
#include "sysid/model.hpp"
#include "sysid/motion.hpp"
#include "sysid/nn.hpp"
#include "sysid/nn_irreducible.hpp"
#include "sysid/pipeline.hpp"
#include "sysid/signal.hpp"
#include "sysid/simulate.hpp"
#include "sysid/stack.hpp"
#include "sysid/stage.hpp"
#include "sysid/stage_facts.hpp"
#include "sysid/validate.hpp"

namespace {

using sysid::NameValue;
using sysid::internal::IsDescribed;

template <class V>
struct IsOptional : std::false_type {};
template <class V>
struct IsOptional<std::optional<V>> : std::true_type {};

template <class V>
struct IsPair : std::false_type {};
template <class A, class B>
struct IsPair<std::pair<A, B>> : std::true_type {};

class PerturbArchive {
 public:
  template <class V>
  void Visit(const NameValue<V>& nv) {
    Perturb(*nv.value());
  }

 private:
  template <class V>
  void Perturb(V& v) {
    if constexpr (IsDescribed<V>::value) {
      v.Serialize(this);
    } else if constexpr (std::is_same_v<V, double>) {
      v = std::isfinite(v) ? 1.5 * v + 0.25 : 2.5;
    } else if constexpr (std::is_same_v<V, bool>) {
      v = !v;
    } else if constexpr (std::is_integral_v<V>) {
      v = static_cast<V>(v + 1);
    } else if constexpr (std::is_enum_v<V>) {
      // Enums count from 0 without gaps: a step down, or up from the first, is another value.
      const int k = static_cast<int>(v);
      v = static_cast<V>(k == 0 ? 1 : k - 1);
    } else if constexpr (std::is_same_v<V, std::string>) {
      v += "x";
    } else if constexpr (std::is_same_v<V, std::pair<double, double>>) {
      v = {v.first - 0.5, v.second + 1.5};
    } else if constexpr (IsPair<V>::value) {
      Perturb(v.first);
      Perturb(v.second);
    } else if constexpr (std::is_same_v<V, Eigen::VectorXd>) {
      v.conservativeResize(v.size() + 1);
      v(v.size() - 1) = 0.5;
    } else if constexpr (IsOptional<V>::value) {
      if (!v) v.emplace();
      Perturb(*v);
    } else {  // a list: one element more, itself moved off its default
      v.emplace_back();
      Perturb(v.back());
    }
  }
};

// The keys of `a` whose value equals `b`'s, recursing into objects.
void SameKeys(const nlohmann::ordered_json& a, const nlohmann::ordered_json& b,
              const std::string& path, std::vector<std::string>* same) {
  for (auto it = a.begin(); it != a.end(); ++it) {
    if (it.key() == "units") continue;  // stated by the struct, the same for any value
    const std::string key = path + "/" + it.key();
    if (!b.contains(it.key()))  // a list left out when empty (NameValue::OmitEmpty)
      continue;
    if (it.value().is_object())
      SameKeys(it.value(), b.at(it.key()), key, same);
    else if (it.value() == b.at(it.key()))
      same->push_back(key);
  }
}

// The structs live on the heap: GCC 12 warns of a maybe-uninitialised vector in a large
// value-initialised aggregate on the stack (a false positive).
template <class T>
void CheckRoundTrip(const char* name) {
  INFO(name);
  const auto defaults = std::make_unique<T>();
  auto perturbed = std::make_unique<T>();
  PerturbArchive perturb;
  perturbed->Serialize(&perturb);
  const nlohmann::ordered_json written = sysid::internal::WriteFields(*perturbed);
  nlohmann::ordered_json fields = written;  // the keys of the fields, without their units
  fields.erase("units");

  std::vector<std::string> same;
  SameKeys(written, sysid::internal::WriteFields(*defaults), "", &same);
  CAPTURE(same);
  CHECK(same.empty());

  const std::string text = written.dump(2);  // the document keeps a reference to its text
  const sysid::internal::JsonDocument doc(text, "perturbed.json");
  auto read = std::make_unique<T>();
  sysid::internal::ReadFields(doc.Root(), *read);
  CHECK(sysid::internal::WriteFields(*read).dump() == written.dump());

  std::vector<std::string> keys;
  for (auto it = fields.begin(); it != fields.end(); ++it) keys.push_back(it.key());
  CHECK(keys == sysid::internal::FieldNamesOf(*defaults));
}

}  // namespace

TEST_CASE("every described options struct round-trips each of its fields through JSON") {
  CheckRoundTrip<sysid::DerivativeOptions>("DerivativeOptions");
  CheckRoundTrip<sysid::MotionOptions>("MotionOptions");
  CheckRoundTrip<sysid::PulseDetectionOptions>("PulseDetectionOptions");
  CheckRoundTrip<sysid::PlateauOptions>("PlateauOptions");
  CheckRoundTrip<sysid::PulseFitOptions>("PulseFitOptions");
  CheckRoundTrip<sysid::PulseIdentificationOptions>("PulseIdentificationOptions");
  CheckRoundTrip<sysid::TrajectoryOptions>("TrajectoryOptions");
  CheckRoundTrip<sysid::SegmentOptions>("SegmentOptions");
  CheckRoundTrip<sysid::DelayTuningOptions>("DelayTuningOptions");
  CheckRoundTrip<sysid::RefineOptions>("RefineOptions");
  CheckRoundTrip<sysid::NeuralTrainingOptions>("NeuralTrainingOptions");
  CheckRoundTrip<sysid::HiddenSweepOptions>("HiddenSweepOptions");
  CheckRoundTrip<sysid::DominanceOptions>("DominanceOptions");
  CheckRoundTrip<sysid::CompareOptions>("CompareOptions");
  CheckRoundTrip<sysid::PiOptions>("PiOptions");
  CheckRoundTrip<sysid::SmoothProfileOptions>("SmoothProfileOptions");
  CheckRoundTrip<sysid::PulseProcedure>("PulseProcedure");
  CheckRoundTrip<sysid::FactsOptions>("FactsOptions");
  CheckRoundTrip<sysid::PipelineOptions>("PipelineOptions");
  CheckRoundTrip<sysid::StackHysteresis>("StackHysteresis");
  CheckRoundTrip<sysid::StackCreep>("StackCreep");
  CheckRoundTrip<sysid::StackMechanics>("StackMechanics");
  CheckRoundTrip<sysid::StackRig>("StackRig");
  CheckRoundTrip<sysid::StackIntegrator>("StackIntegrator");
  CheckRoundTrip<sysid::DriverSettings>("DriverSettings");
  CheckRoundTrip<sysid::RigSettings>("RigSettings");
  CheckRoundTrip<sysid::IntegratorSettings>("IntegratorSettings");
  CheckRoundTrip<sysid::FrictionBranch>("FrictionBranch");
  CheckRoundTrip<sysid::RailFriction>("RailFriction");
  CheckRoundTrip<sysid::MotorParameters>("MotorParameters");
  CheckRoundTrip<sysid::DriveHysteresis>("DriveHysteresis");
  CheckRoundTrip<sysid::DriveCreep>("DriveCreep");
  CheckRoundTrip<sysid::VelocitySourcePlant>("VelocitySourcePlant");
  CheckRoundTrip<sysid::ActuatorDelayPlant>("ActuatorDelayPlant");
  CheckRoundTrip<sysid::SimulationOptions>("SimulationOptions");
  CheckRoundTrip<sysid::ResidualTestOptions>("ResidualTestOptions");
  CheckRoundTrip<sysid::ValidationOptions>("ValidationOptions");
}

TEST_CASE("every described model and result type round-trips each of its fields through JSON") {
  CheckRoundTrip<sysid::FrictionModel>("FrictionModel");
  CheckRoundTrip<sysid::Pulse>("Pulse");
  CheckRoundTrip<sysid::PulseEstimate>("PulseEstimate");
  CheckRoundTrip<sysid::PulsePoint>("PulsePoint");
  CheckRoundTrip<sysid::LinearFit>("LinearFit");
  CheckRoundTrip<sysid::PulseIdentificationResult>("PulseIdentificationResult");
  CheckRoundTrip<sysid::TrajectoryIdentificationResult>("TrajectoryIdentificationResult");
  CheckRoundTrip<sysid::DelayTuningResult>("DelayTuningResult");
  CheckRoundTrip<sysid::RefineResult>("RefineResult");
  CheckRoundTrip<sysid::TermStats>("TermStats");
  CheckRoundTrip<sysid::DominanceResult>("DominanceResult");
  CheckRoundTrip<sysid::PredictionErrors>("PredictionErrors");
  CheckRoundTrip<sysid::HysteresisInverseResult>("HysteresisInverseResult");
  CheckRoundTrip<sysid::TrackingResult>("TrackingResult");
  CheckRoundTrip<sysid::SchemeTracking>("SchemeTracking");
  CheckRoundTrip<sysid::LoopMargins>("LoopMargins");
  CheckRoundTrip<sysid::PiMarginsDirection>("PiMarginsDirection");
  CheckRoundTrip<sysid::PiMarginsReport>("PiMarginsReport");
  CheckRoundTrip<sysid::PiTuningResult>("PiTuningResult");
  CheckRoundTrip<sysid::TunePiSummary>("TunePiSummary");
  CheckRoundTrip<sysid::LimitCycleCheck>("LimitCycleCheck");
  CheckRoundTrip<sysid::PiStepResponse>("PiStepResponse");
  CheckRoundTrip<sysid::PiSineResponse>("PiSineResponse");
  CheckRoundTrip<sysid::PiBehaviour>("PiBehaviour");
  CheckRoundTrip<sysid::FitScores>("FitScores");
  CheckRoundTrip<sysid::CorrelationTest>("CorrelationTest");
  CheckRoundTrip<sysid::OutputValidation>("OutputValidation");
  CheckRoundTrip<sysid::Validation>("Validation");
  CheckRoundTrip<sysid::SimulationEvent>("SimulationEvent");
  CheckRoundTrip<sysid::SimulationSummary>("SimulationSummary");
  CheckRoundTrip<sysid::TrackingRow>("TrackingRow");
  CheckRoundTrip<sysid::PipelineResult>("PipelineResult");
  CheckRoundTrip<sysid::HysteresisSplitScore>("HysteresisSplitScore");
  CheckRoundTrip<sysid::StackDominanceRow>("StackDominanceRow");
  CheckRoundTrip<sysid::StackSummary>("StackSummary");
  CheckRoundTrip<sysid::EpochRecord>("EpochRecord");
  CheckRoundTrip<sysid::NeuralTrainingResult>("NeuralTrainingResult");
  CheckRoundTrip<sysid::HiddenSweepRow>("HiddenSweepRow");
  CheckRoundTrip<sysid::HiddenSweepResult>("HiddenSweepResult");
  CheckRoundTrip<sysid::ScaledVariable>("ScaledVariable");
  CheckRoundTrip<sysid::IrreducibleError>("IrreducibleError");
  CheckRoundTrip<sysid::HysteresisParameter>("HysteresisParameter");
  CheckRoundTrip<sysid::HysteresisFitSummary>("HysteresisFitSummary");
  CheckRoundTrip<sysid::BoucWenSimulationOptions>("BoucWenSimulationOptions");
  CheckRoundTrip<sysid::MechanicalBoucWenParameters>("MechanicalBoucWenParameters");
  CheckRoundTrip<sysid::PiezoBoucWenParameters>("PiezoBoucWenParameters");
  CheckRoundTrip<sysid::PiParameters>("PiParameters");
}

TEST_CASE("a limit written as null reads back as the infinity of its side") {
  sysid::PlateauOptions o;
  o.travel_min_m = -0.5;
  const auto j = sysid::internal::WriteFields(sysid::PlateauOptions{});
  CHECK(j.at("max_speed_mps").is_null());
  CHECK(j.at("travel_min_m").is_null());
  const sysid::internal::JsonDocument doc(j.dump(), "limits.json");
  sysid::internal::ReadFields(doc.Root(), o);
  CHECK(o.travel_min_m == -std::numeric_limits<double>::infinity());
  CHECK(o.travel_max_m == std::numeric_limits<double>::infinity());
  CHECK(o.max_speed_mps == std::numeric_limits<double>::infinity());
}
