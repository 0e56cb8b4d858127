// JSON of the stage-facts options (the facts' results are StageFacts::ToJson).
#include "paper/facts_json.hpp"

#include <string>
#include <string_view>
#include <vector>

#include "control/control_json.hpp"
#include "delay/delay_json.hpp"
#include "nn/nn_json.hpp"
#include "stage/stage_json.hpp"

namespace sysid {
namespace internal {

namespace {

// The options' field table (FieldList): writer, allowed keys and reader.
const FieldList<FactsOptions>& FactsFields() {
  using O = FactsOptions;
  static const FieldList<O> fields =
      FieldList<O>()
          .Nested("facts", &O::facts, NamesJson, ReadNames)
          .Add("seed", &O::seed)
          .Add("threads", &O::threads)
          .Nested("pulse", &O::pulse, PulseProcedureJson, ReadPulseProcedure)
          .Nested("delay", &O::delay, DelayTuningOptionsJson, ReadDelayTuningOptions)
          .Nested("pi", &O::pi, PiOptionsJson, ReadPiOptions)
          .Add("track_frequencies_hz", &O::track_frequencies_hz)
          .Add("track_amplitude_m", &O::track_amplitude_m)
          .Add("track_cycles", &O::track_cycles)
          .Add("ripple_tolerance_m", &O::ripple_tolerance_m)
          .Add("motion_ripple_tolerance_m", &O::motion_ripple_tolerance_m)
          .Add("motion_ripple_window_s", &O::motion_ripple_window_s)
          .Nested("training", &O::training, NeuralTrainingOptionsJson, ReadNeuralTrainingOptions)
          .Add("typical_hidden", &O::typical_hidden)
          .Add("typical_max_epochs", &O::typical_max_epochs)
          .Add("typical_stride", &O::typical_stride)
          .Add("collection_kp_v_per_m", &O::collection_kp_v_per_m)
          .Add("network_initializations", &O::network_initializations)
          .Add("dominance_amplitude_v", &O::dominance_amplitude_v)
          .Add("dominance_omega_rad_s", &O::dominance_omega_rad_s)
          .Add("dominance_offset_v", &O::dominance_offset_v)
          .Add("dominance_duration_s", &O::dominance_duration_s)
          .Add("dominance_min_speed_mps", &O::dominance_min_speed_mps)
          .Add("loop_period_s", &O::loop_period_s)
          .Add("loop_peak_forward_v", &O::loop_peak_forward_v)
          .Add("loop_peak_backward_v", &O::loop_peak_backward_v)
          .Add("loop_levels_v", &O::loop_levels_v)
          .Add("loop_min_relative_width", &O::loop_min_relative_width)
          .Add("loop_min_start_ratio", &O::loop_min_start_ratio)
          .Add("loop_sine_offset_v", &O::loop_sine_offset_v)
          .Add("loop_sine_amplitude_v", &O::loop_sine_amplitude_v)
          .Add("loop_sine_frequencies_hz", &O::loop_sine_frequencies_hz)
          .Add("loop_sine_frequency_hz", &O::loop_sine_frequency_hz)
          .Add("loop_sine_amplitudes_v", &O::loop_sine_amplitudes_v)
          .Add("loop_min_rate_ratio", &O::loop_min_rate_ratio)
          .Add("loop_min_amplitude_change", &O::loop_min_amplitude_change);
  return fields;
}

}  // namespace

nlohmann::ordered_json FactsOptionsJson(const FactsOptions& o) { return FactsFields().Write(o); }

void ReadFactsOptions(const JsonNode& node, FactsOptions& o) { FactsFields().Read(node, o); }

}  // namespace internal

std::string ToJson(const FactsOptions& options, int indent) {
  return internal::DumpJson(internal::FactsOptionsJson(options), indent);
}

FactsOptions FactsOptionsFromJson(std::string_view text, const std::string& source_name) {
  return internal::OptionsFromJson<FactsOptions>(text, source_name, internal::ReadFactsOptions);
}

}  // namespace sysid
