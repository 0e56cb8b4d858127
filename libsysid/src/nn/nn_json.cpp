// JSON of the training and hidden-size sweep options and results (docs/cli.md: train, sweep).
#include <cmath>
#include <cstdint>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/json_text.hpp"
#include "nn/nn_json.hpp"
#include "sysid/nn.hpp"
#include "sysid/nn_irreducible.hpp"

namespace sysid {
namespace {
using internal::JsonNode;
using Json = nlohmann::ordered_json;

TrainingStop StopFromJson(const JsonNode& node) {
  return internal::ReadName(
      node,
      {TrainingStop::kMaxEpochs, TrainingStop::kGoalReached, TrainingStop::kSmallGradient,
       TrainingStop::kMuTooLarge, TrainingStop::kValidationFailures, TrainingStop::kConverged,
       TrainingStop::kNumericalFailure},
      [](TrainingStop t) { return ToString(t); }, "a stopping rule");
}

NeuralTrainer TrainerFromJson(const JsonNode& node) {
  return internal::ReadName(node, {NeuralTrainer::kLevenbergMarquardt, NeuralTrainer::kCeres},
                            [](NeuralTrainer t) { return ToString(t); }, "a trainer");
}

}  // namespace

std::string ToJson(const NeuralTrainingResult& r, const NeuralTrainingOptions& o, int indent) {
  // The options the run used and the network's size, then the described fields.
  Json j;
  j["hidden"] = o.hidden;
  j["parameters"] = r.network.parameter_count();
  j["trainer"] = ToString(o.trainer);
  j["momentum"] = o.momentum;
  j["solve_output_layer"] = o.solve_output_layer;
  j["seed"] = o.seed;
  j.update(internal::WriteFields(r));
  return internal::DumpJson(j, indent);
}

NeuralTrainingResult NeuralTrainingResultFromJson(std::string_view text,
                                                  const std::string& source_name,
                                                  NeuralTrainingOptions* options) {
  const internal::JsonDocument doc(text, source_name);
  const JsonNode root = doc.Root();
  NeuralTrainingResult r;
  internal::ReadFields(root, r,
                       {"hidden", "parameters", "trainer", "momentum", "solve_output_layer",
                        "seed"});
  // The options part is read (and checked) always, stored only when asked for.
  NeuralTrainingOptions o;
  o.hidden = static_cast<int>(root.Get("hidden").Integer(1, kMaxHiddenUnits));
  // The weights live in the network file; the report's P = H n + 2 H + 1 must still fit some
  // n >= 1 inputs.
  const long p = root.Get("parameters").Integer(1, std::numeric_limits<int>::max());
  if (p < 3L * o.hidden + 1 || (p - 2L * o.hidden - 1) % o.hidden != 0)
    root.Get("parameters")
        .Expected("H n + 2 H + 1 parameters for hidden = " + std::to_string(o.hidden) +
                  " and some n >= 1 inputs");
  o.trainer = TrainerFromJson(root.Get("trainer"));
  o.momentum = root.Get("momentum").Number(internal::NumberRule{0.0, 1.0, false, true});
  o.solve_output_layer = root.Get("solve_output_layer").Boolean();
  o.seed = internal::Uint64FromJson(root.Get("seed"));
  if (options) {
    options->hidden = o.hidden;
    options->trainer = o.trainer;
    options->momentum = o.momentum;
    options->solve_output_layer = o.solve_output_layer;
    options->seed = o.seed;
  }
  if (r.termination != TerminationOf(r.stop))
    root.Get("termination")
        .Expected("\"" + ToString(TerminationOf(r.stop)) + "\" (stop_reason \"" +
                  ToString(r.stop) + "\")");
  return r;
}

std::string ToJson(const HiddenSweepResult& r, const HiddenSweepOptions& o, int indent) {
  Json j;
  j["trainer"] = ToString(o.training.trainer);
  j["momentum"] = o.training.momentum;
  j["seed"] = o.training.seed;
  // The described fields, with the chosen row's hidden size after the rows.
  const Json fields = internal::WriteFields(r);
  for (auto it = fields.begin(); it != fields.end(); ++it) {
    j[it.key()] = *it;
    if (it.key() == "rows")
      j["chosen_hidden"] =
          r.chosen >= 0 ? Json(r.rows[static_cast<size_t>(r.chosen)].hidden) : Json(nullptr);
  }
  return internal::DumpJson(j, indent);
}

std::string ToJson(const IrreducibleError& e, int indent) {
  Json j = internal::WriteFields(e);
  j["interval95"] = {e.mse_low, e.mse_high};
  j["unexplained_share"] = e.unexplained_share();
  return internal::DumpJson(j, indent);
}

// ---- Options ----

namespace {

std::string InitName(NeuralInit init) {
  return init == NeuralInit::kUniform ? "uniform" : "nguyen-widrow";
}

}  // namespace

namespace internal {

Json JsonForm<NeuralTrainer>::Write(const NeuralTrainer& trainer) { return ToString(trainer); }
void JsonForm<NeuralTrainer>::Read(const JsonNode& node, NeuralTrainer& trainer) {
  trainer = TrainerFromJson(node);
}

Json JsonForm<TrainingStop>::Write(const TrainingStop& stop) { return ToString(stop); }
void JsonForm<TrainingStop>::Read(const JsonNode& node, TrainingStop& stop) {
  stop = StopFromJson(node);
}

Json JsonForm<NeuralInit>::Write(const NeuralInit& init) { return InitName(init); }
void JsonForm<NeuralInit>::Read(const JsonNode& node, NeuralInit& init) {
  init = ReadName(node, {NeuralInit::kNguyenWidrow, NeuralInit::kUniform}, InitName);
}

}  // namespace internal

std::string ToJson(const NeuralTrainingOptions& o, int indent) {
  return internal::FieldsToJson(o, indent);
}

NeuralTrainingOptions NeuralTrainingOptionsFromJson(std::string_view text,
                                                    const std::string& source_name) {
  return internal::FieldsFromJson<NeuralTrainingOptions>(text, source_name);
}

std::string ToJson(const HiddenSweepOptions& o, int indent) {
  return internal::FieldsToJson(o, indent);
}

HiddenSweepOptions HiddenSweepOptionsFromJson(std::string_view text,
                                              const std::string& source_name) {
  return internal::FieldsFromJson<HiddenSweepOptions>(text, source_name);
}

std::string ToJson(const NetworkPrediction& p, int indent) {
  Json j;
  j["rows"] = p.rows;
  j["column"] = p.column;
  j["rows_outside_input_range"] = p.rows_outside_input_range;
  if (!std::isnan(p.mse)) j["mse"] = p.mse;
  return internal::DumpJson(j, indent);
}

}  // namespace sysid
