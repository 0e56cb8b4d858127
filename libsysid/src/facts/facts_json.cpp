// JSON of the stage-facts options (the facts' results are StageFacts::ToJson).
#include "facts/facts_json.hpp"

#include <string>
#include <string_view>

#include "control/control_json.hpp"
#include "delay/delay_json.hpp"
#include "nn/nn_json.hpp"
#include "stage/stage_json.hpp"

namespace sysid {
namespace internal {

nlohmann::ordered_json FactsOptionsJson(const FactsOptions& o) {
  nlohmann::ordered_json j;
  j["facts"] = o.facts;
  j["seed"] = o.seed;
  j["threads"] = o.threads;
  j["pulse"] = PulseProcedureJson(o.pulse);
  j["delay"] = DelayTuningOptionsJson(o.delay);
  j["pi"] = PiOptionsJson(o.pi);
  j["track_frequencies_hz"] = o.track_frequencies_hz;
  j["track_amplitude_m"] = o.track_amplitude_m;
  j["track_cycles"] = o.track_cycles;
  j["ripple_tolerance_m"] = o.ripple_tolerance_m;
  j["training"] = NeuralTrainingOptionsJson(o.training);
  j["typical_hidden"] = o.typical_hidden;
  j["typical_max_epochs"] = o.typical_max_epochs;
  j["typical_stride"] = o.typical_stride;
  j["dominance_amplitude_v"] = o.dominance_amplitude_v;
  j["dominance_omega_rad_s"] = o.dominance_omega_rad_s;
  j["dominance_offset_v"] = o.dominance_offset_v;
  j["dominance_duration_s"] = o.dominance_duration_s;
  j["dominance_min_speed_mps"] = o.dominance_min_speed_mps;
  return j;
}

void ReadFactsOptions(const JsonNode& node, FactsOptions& o) {
  node.ExpectObject({"facts", "seed", "threads", "pulse", "delay", "pi", "track_frequencies_hz",
                     "track_amplitude_m", "track_cycles", "ripple_tolerance_m", "training",
                     "typical_hidden", "typical_max_epochs", "typical_stride",
                     "dominance_amplitude_v", "dominance_omega_rad_s", "dominance_offset_v",
                     "dominance_duration_s", "dominance_min_speed_mps"});
  if (node.Has("facts")) {
    const JsonNode ids = node.Get("facts");
    ids.ExpectArray();
    o.facts.clear();
    for (size_t i = 0; i < ids.Size(); ++i) o.facts.push_back(ids.Element(i).String(true));
  }
  ReadOptional(node, "seed", o.seed);
  ReadOptional(node, "threads", o.threads);
  if (node.Has("pulse")) ReadPulseProcedure(node.Get("pulse"), o.pulse);
  if (node.Has("delay")) ReadDelayTuningOptions(node.Get("delay"), o.delay);
  if (node.Has("pi")) ReadPiOptions(node.Get("pi"), o.pi);
  ReadOptional(node, "track_frequencies_hz", o.track_frequencies_hz);
  ReadOptional(node, "track_amplitude_m", o.track_amplitude_m);
  ReadOptional(node, "track_cycles", o.track_cycles);
  ReadOptional(node, "ripple_tolerance_m", o.ripple_tolerance_m);
  if (node.Has("training")) ReadNeuralTrainingOptions(node.Get("training"), o.training);
  ReadOptional(node, "typical_hidden", o.typical_hidden);
  ReadOptional(node, "typical_max_epochs", o.typical_max_epochs);
  ReadOptional(node, "typical_stride", o.typical_stride);
  ReadOptional(node, "dominance_amplitude_v", o.dominance_amplitude_v);
  ReadOptional(node, "dominance_omega_rad_s", o.dominance_omega_rad_s);
  ReadOptional(node, "dominance_offset_v", o.dominance_offset_v);
  ReadOptional(node, "dominance_duration_s", o.dominance_duration_s);
  ReadOptional(node, "dominance_min_speed_mps", o.dominance_min_speed_mps);
}

}  // namespace internal

std::string ToJson(const FactsOptions& options, int indent) {
  return internal::DumpJson(internal::FactsOptionsJson(options), indent);
}

FactsOptions FactsOptionsFromJson(std::string_view text, const std::string& source_name) {
  return internal::OptionsFromJson<FactsOptions>(text, source_name, internal::ReadFactsOptions);
}

}  // namespace sysid
