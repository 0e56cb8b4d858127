// Private: NeuralTrainingOptions and NeuralNetwork as JSON objects, for the options and
// results that hold one (the hidden sweep, the pipeline).
#ifndef SYSID_SRC_NN_NN_JSON_HPP_
#define SYSID_SRC_NN_NN_JSON_HPP_

#include <nlohmann/json.hpp>

#include "core/json_fields.hpp"
#include "core/json_text.hpp"
#include "sysid/nn.hpp"

namespace sysid::internal {

/// "lm", ... (ToString's names).
template <>
struct JsonForm<NeuralTrainer> {
  static nlohmann::ordered_json Write(const NeuralTrainer& trainer);
  static void Read(const JsonNode& node, NeuralTrainer& trainer);
};

/// "max_epochs", ... (ToString's names).
template <>
struct JsonForm<TrainingStop> {
  static nlohmann::ordered_json Write(const TrainingStop& stop);
  static void Read(const JsonNode& node, TrainingStop& stop);
};

/// "nguyen-widrow" or "uniform".
template <>
struct JsonForm<NeuralInit> {
  static nlohmann::ordered_json Write(const NeuralInit& init);
  static void Read(const JsonNode& node, NeuralInit& init);
};


/// A network file's object at `node` (the form NeuralNetworkToJson writes), checked as
/// ParseNeuralNetwork checks a file; errors name the place in the enclosing document.
NeuralNetwork NeuralNetworkFromJson(const JsonNode& node);

}  // namespace sysid::internal

#endif  // SYSID_SRC_NN_NN_JSON_HPP_
