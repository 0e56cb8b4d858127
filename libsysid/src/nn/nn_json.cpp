// JSON of the training and hidden-size sweep options and results (docs/cli.md: train, sweep).
#include <cmath>
#include <cstdint>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "core/json_text.hpp"
#include "nn/nn_json.hpp"
#include "sysid/nn.hpp"

namespace sysid {
namespace {
using internal::JsonNode;
using internal::NumberOrNull;
using Json = nlohmann::ordered_json;

TrainingStop StopFromJson(const JsonNode& node) {
  const std::string s = node.String();
  constexpr TrainingStop kStops[] = {
      TrainingStop::kMaxEpochs,          TrainingStop::kGoalReached, TrainingStop::kSmallGradient,
      TrainingStop::kMuTooLarge,         TrainingStop::kValidationFailures,
      TrainingStop::kConverged,          TrainingStop::kNumericalFailure};
  std::string names;
  for (auto stop : kStops) {
    if (ToString(stop) == s) return stop;
    names += (names.empty() ? "" : ", ") + ToString(stop);
  }
  node.Expected("a stopping rule (" + names + ")");
}

NeuralTrainer TrainerFromJson(const JsonNode& node) {
  const std::string s = node.String();
  for (auto t : {NeuralTrainer::kLevenbergMarquardt, NeuralTrainer::kCeres})
    if (ToString(t) == s) return t;
  node.Expected("a trainer (" + ToString(NeuralTrainer::kLevenbergMarquardt) + " or " +
                ToString(NeuralTrainer::kCeres) + ")");
}

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

NeuralTrainingResult NeuralTrainingResultFromJson(std::string_view text,
                                                  const std::string& source_name,
                                                  NeuralTrainingOptions* options) {
  const internal::JsonDocument doc(text, source_name);
  const JsonNode root = doc.Root();
  root.ExpectObject({"hidden", "parameters", "trainer", "momentum", "solve_output_layer", "seed",
                     "restart", "epochs", "train_mse", "validation_mse", "termination",
                     "stop_reason", "message", "warnings", "wall_time_s", "history"});
  using Rule = internal::NumberRule;
  constexpr long kMaxEpochs = std::numeric_limits<int>::max();
  // The options part is read (and checked) always, stored only when asked for.
  NeuralTrainingOptions o;
  o.hidden = static_cast<int>(root.Get("hidden").Integer(1, 100000));
  // The weights live in the network file; the report's P = H n + 2 H + 1 must still fit some
  // n >= 1 inputs.
  const long p = root.Get("parameters").Integer(1, std::numeric_limits<int>::max());
  if (p < 3L * o.hidden + 1 || (p - 2L * o.hidden - 1) % o.hidden != 0)
    root.Get("parameters")
        .Expected("H n + 2 H + 1 parameters for hidden = " + std::to_string(o.hidden) +
                  " and some n >= 1 inputs");
  o.trainer = TrainerFromJson(root.Get("trainer"));
  o.momentum = root.Get("momentum").Number(Rule{0.0, 1.0, false, true});
  o.solve_output_layer = root.Get("solve_output_layer").Boolean();
  o.seed = internal::Uint64FromJson(root.Get("seed"));
  if (options) {
    options->hidden = o.hidden;
    options->trainer = o.trainer;
    options->momentum = o.momentum;
    options->solve_output_layer = o.solve_output_layer;
    options->seed = o.seed;
  }
  NeuralTrainingResult r;
  r.restart = static_cast<int>(root.Get("restart").Integer(0, kMaxEpochs));
  r.epochs = static_cast<int>(root.Get("epochs").Integer(0, kMaxEpochs));
  r.train_mse = root.Get("train_mse").Number(Rule::NonNegative());
  r.validation_mse = root.Get("validation_mse").NumberOrNaN(Rule::NonNegative());
  r.termination = internal::TerminationFromJson(root.Get("termination"));
  r.stop = StopFromJson(root.Get("stop_reason"));
  if (r.termination != TerminationOf(r.stop))
    root.Get("termination")
        .Expected("\"" + ToString(TerminationOf(r.stop)) + "\" (stop_reason \"" +
                  ToString(r.stop) + "\")");
  r.message = root.Get("message").String();
  const JsonNode w = root.Get("warnings");
  w.ExpectArray();
  for (size_t i = 0; i < w.Size(); ++i) r.warnings.push_back(w.Element(i).String());
  r.wall_time_s = root.Get("wall_time_s").Number(Rule::NonNegative());
  const JsonNode h = root.Get("history");
  h.ExpectArray();
  for (size_t i = 0; i < h.Size(); ++i) {
    const JsonNode e = h.Element(i);
    e.ExpectObject({"restart", "epoch", "mu", "train_mse", "validation_mse", "gradient_norm"});
    EpochRecord rec;
    rec.restart = static_cast<int>(e.Get("restart").Integer(0, kMaxEpochs));
    rec.epoch = static_cast<int>(e.Get("epoch").Integer(0, kMaxEpochs));
    rec.mu = e.Get("mu").Number(Rule::NonNegative());
    rec.train_mse = e.Get("train_mse").Number(Rule::NonNegative());
    rec.validation_mse = e.Get("validation_mse").NumberOrNaN(Rule::NonNegative());
    rec.gradient_norm = e.Get("gradient_norm").Number(Rule::NonNegative());
    r.history.push_back(rec);
  }
  return r;
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

// ---- Options ----

namespace {

std::string InitName(NeuralInit init) {
  return init == NeuralInit::kUniform ? "uniform" : "nguyen-widrow";
}

Json RangeJson(const std::pair<double, double>& r) { return Json::array({r.first, r.second}); }

std::pair<double, double> RangeFromJson(const JsonNode& node) {
  const std::vector<double> v = node.Numbers(2);
  return {v[0], v[1]};
}

}  // namespace

namespace internal {

nlohmann::ordered_json NeuralTrainingOptionsJson(const NeuralTrainingOptions& o) {
  Json j;
  j["hidden"] = o.hidden;
  j["trainer"] = ToString(o.trainer);
  j["init"] = InitName(o.init);
  j["momentum"] = o.momentum;
  j["solve_output_layer"] = o.solve_output_layer;
  j["mu_initial"] = o.mu_initial;
  j["mu_decrease"] = o.mu_decrease;
  j["mu_increase"] = o.mu_increase;
  j["mu_max"] = o.mu_max;
  j["gradient_tolerance"] = o.gradient_tolerance;
  j["max_epochs"] = o.max_epochs;
  j["max_validation_failures"] = o.max_validation_failures;
  j["goal_mse"] = o.goal_mse;
  j["seed"] = o.seed;
  j["restarts"] = o.restarts;
  j["input_ranges"] = Json::array();
  for (const auto& r : o.input_ranges) j["input_ranges"].push_back(RangeJson(r));
  j["output_range"] = o.output_range ? RangeJson(*o.output_range) : Json(nullptr);
  j["initial_parameters"] =
      o.initial_parameters ? VectorJson(*o.initial_parameters) : Json(nullptr);
  j["ceres_block_size"] = o.ceres_block_size;
  j["threads"] = o.threads;
  return j;
}

void ReadNeuralTrainingOptions(const JsonNode& node, NeuralTrainingOptions& o) {
  node.ExpectObject({"hidden", "trainer", "init", "momentum", "solve_output_layer", "mu_initial",
                     "mu_decrease", "mu_increase", "mu_max", "gradient_tolerance", "max_epochs",
                     "max_validation_failures", "goal_mse", "seed", "restarts", "input_ranges",
                     "output_range", "initial_parameters", "ceres_block_size", "threads"});
  ReadOptional(node, "hidden", o.hidden);
  if (node.Has("trainer")) o.trainer = TrainerFromJson(node.Get("trainer"));
  if (node.Has("init")) {
    const JsonNode n = node.Get("init");
    const std::string s = n.String();
    if (s == InitName(NeuralInit::kNguyenWidrow)) o.init = NeuralInit::kNguyenWidrow;
    else if (s == InitName(NeuralInit::kUniform)) o.init = NeuralInit::kUniform;
    else n.Expected("\"nguyen-widrow\" or \"uniform\"");
  }
  ReadOptional(node, "momentum", o.momentum);
  ReadOptional(node, "solve_output_layer", o.solve_output_layer);
  ReadOptional(node, "mu_initial", o.mu_initial);
  ReadOptional(node, "mu_decrease", o.mu_decrease);
  ReadOptional(node, "mu_increase", o.mu_increase);
  ReadOptional(node, "mu_max", o.mu_max);
  ReadOptional(node, "gradient_tolerance", o.gradient_tolerance);
  ReadOptional(node, "max_epochs", o.max_epochs);
  ReadOptional(node, "max_validation_failures", o.max_validation_failures);
  ReadOptional(node, "goal_mse", o.goal_mse);
  ReadOptional(node, "seed", o.seed);
  ReadOptional(node, "restarts", o.restarts);
  if (node.Has("input_ranges")) {
    const JsonNode list = node.Get("input_ranges");
    list.ExpectArray();
    o.input_ranges.clear();
    for (size_t i = 0; i < list.Size(); ++i) o.input_ranges.push_back(RangeFromJson(list.Element(i)));
  }
  if (node.Has("output_range")) {
    const JsonNode r = node.Get("output_range");
    if (r.json().is_null()) o.output_range.reset();
    else o.output_range = RangeFromJson(r);
  }
  if (node.Has("initial_parameters")) {
    const JsonNode p = node.Get("initial_parameters");
    if (p.json().is_null()) o.initial_parameters.reset();
    else o.initial_parameters = VectorFromJson(p);
  }
  ReadOptional(node, "ceres_block_size", o.ceres_block_size);
  ReadOptional(node, "threads", o.threads);
}

}  // namespace internal

std::string ToJson(const NeuralTrainingOptions& o, int indent) {
  return internal::DumpJson(internal::NeuralTrainingOptionsJson(o), indent);
}

NeuralTrainingOptions NeuralTrainingOptionsFromJson(std::string_view text,
                                                    const std::string& source_name) {
  return internal::OptionsFromJson<NeuralTrainingOptions>(text, source_name,
                                                          internal::ReadNeuralTrainingOptions);
}

std::string ToJson(const HiddenSweepOptions& o, int indent) {
  Json j;
  j["hidden_sizes"] = o.hidden_sizes;
  j["training"] = internal::NeuralTrainingOptionsJson(o.training);
  j["threads"] = o.threads;
  return internal::DumpJson(j, indent);
}

HiddenSweepOptions HiddenSweepOptionsFromJson(std::string_view text,
                                              const std::string& source_name) {
  auto read = [](const JsonNode& node, HiddenSweepOptions& o) {
    node.ExpectObject({"hidden_sizes", "training", "threads"});
    internal::ReadOptional(node, "hidden_sizes", o.hidden_sizes);
    if (node.Has("training")) internal::ReadNeuralTrainingOptions(node.Get("training"), o.training);
    internal::ReadOptional(node, "threads", o.threads);
  };
  return internal::OptionsFromJson<HiddenSweepOptions>(text, source_name, read);
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
