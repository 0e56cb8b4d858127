// JSON of the training and hidden-size sweep results (docs/cli.md: train, sweep).
#include <nlohmann/json.hpp>
#include <string>

#include "core/json_text.hpp"
#include "sysid/nn.hpp"

namespace sysid {
namespace {
using internal::NumberOrNull;
using Json = nlohmann::ordered_json;
}  // namespace

std::string ToJson(const NeuralTrainingResult& r, const NeuralTrainingOptions& o, int indent) {
  Json j;
  j["hidden"] = o.hidden;
  j["parameters"] = r.network.parameter_count();
  j["trainer"] = ToString(o.trainer);
  j["momentum"] = o.momentum;
  j["solve_output_layer"] = o.solve_output_layer;
  j["seed"] = o.seed;
  j["restart"] = r.restart;
  j["epochs"] = r.epochs;
  j["train_mse"] = r.train_mse;
  j["validation_mse"] = NumberOrNull(r.validation_mse);
  j["termination"] = ToString(r.termination);
  j["stop_reason"] = ToString(r.stop);
  j["message"] = r.message;
  j["warnings"] = r.warnings;
  j["wall_time_s"] = r.wall_time_s;
  Json h = Json::array();
  for (const auto& e : r.history)
    h.push_back({{"restart", e.restart},
                 {"epoch", e.epoch},
                 {"mu", e.mu},
                 {"train_mse", e.train_mse},
                 {"validation_mse", NumberOrNull(e.validation_mse)},
                 {"gradient_norm", e.gradient_norm}});
  j["history"] = h;
  return internal::DumpJson(j, indent);
}

std::string ToJson(const HiddenSweepResult& r, const HiddenSweepOptions& o, int indent) {
  Json j;
  j["trainer"] = ToString(o.training.trainer);
  j["momentum"] = o.training.momentum;
  j["seed"] = o.training.seed;
  j["rows"] = Json::array();
  for (const auto& row : r.rows)
    j["rows"].push_back({{"hidden", row.hidden},
                         {"epochs", row.epochs},
                         {"train_mse", row.train_mse},
                         {"validation_mse", NumberOrNull(row.validation_mse)},
                         {"test_mse", NumberOrNull(row.test_mse)},
                         {"stop_reason", ToString(row.stop)},
                         {"wall_time_s", row.wall_time_s}});
  j["chosen_hidden"] =
      r.chosen >= 0 ? Json(r.rows[static_cast<size_t>(r.chosen)].hidden) : Json(nullptr);
  j["rule"] = r.rule;
  j["wall_time_s"] = r.wall_time_s;
  j["warnings"] = r.warnings;
  return internal::DumpJson(j, indent);
}

}  // namespace sysid
