// JSON summary of a pipeline run (docs/cli.md: pipeline --json): the model, the dominant
// variable, the chosen network, the networks' MSEs, every tracking run, the facts' verdicts and
// the wall time per step; and its reader. The pipeline's options.
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "control/control_json.hpp"
#include "core/json_text.hpp"
#include "core/json_fields.hpp"
#include "model/model_json.hpp"
#include "nn/nn_json.hpp"
#include "signal/signal_json.hpp"
#include "sysid/pipeline.hpp"

namespace sysid {
namespace {
using internal::JsonNode;
using Json = nlohmann::ordered_json;
using Rule = internal::NumberRule;
}  // namespace

namespace {

// The report's path first when given, then the described keys (PipelineResult::Serialize) in
// their places, the derived and conditional ones between them.
Json SummaryJson(const PipelineResult& r, const std::string& report_path) {
  Json described = internal::WriteFields(r);
  auto take = [&](Json& j, const char* key) {
    if (described.contains(key)) j[key] = std::move(described[key]);
  };
  Json j;
  if (!report_path.empty()) j["report"] = report_path;
  take(j, "model");
  // A pulse-only run has no dominance and no network (its "skipped" says why).
  if (r.skipped.empty()) {
    j["dominant"] = r.dominance.dominant;
    j["nn_inputs"] = r.nn_inputs;
    j["hidden"] = r.network.hidden_size();
    j["network"] = Json::parse(NeuralNetworkToJson(r.network, -1));  // nn writes text only
    j["nn_test_mse"] = internal::NumberOrNull(r.network_test_mse);
  }
  take(j, "skipped");
  if (r.typical) {
    j["typical_train_mse"] = internal::NumberOrNull(r.typical->train_mse);
    j["typical_test_mse"] = internal::NumberOrNull(r.typical_test_mse);
  }
  take(j, "tracking");
  if (r.tuning)
    j["tuned_pi"] = {{"kp_v_per_m", r.tuning->pi.kp_v_per_m},
                     {"ki_v_per_m_s", r.tuning->pi.ki_v_per_m_s},
                     {"sample_time_s", r.tuning->pi.sample_time_s}};
  take(j, "model_tracking");
  if (r.margins) {
    // The PI gains' verdict per direction: margins.json (the report) holds the whole analysis.
    j["margins"] = Json::array();
    for (const auto& [name, a1, m] : r.margins->directions)
      j["margins"].push_back({{"direction", name},
                              {"crossover_rad_s", internal::NumberOrNull(m.crossover_rad_s)},
                              {"phase_margin_deg", internal::NumberOrNull(m.phase_margin_deg)},
                              {"gain_margin", internal::NumberOrNull(m.gain_margin)},
                              {"stable", m.Stable()}});
  }
  if (r.facts) {
    j["facts"] = Json::array();
    for (const auto& f : r.facts->facts)
      j["facts"].push_back({{"id", f.id}, {"required", f.required}, {"met", f.met}});
    j["facts_required_met"] = r.facts->RequiredMet();
  }
  // An array in run order (an object's keys would be re-sorted by readers that sort them).
  take(j, "steps");
  return j;
}

}  // namespace

std::string ToJson(const PipelineResult& r, int indent) {
  return internal::DumpJson(SummaryJson(r, ""), indent);
}

std::string ToJson(const PipelineResult& r, const std::string& report_path, int indent) {
  return internal::DumpJson(SummaryJson(r, report_path), indent);
}

namespace {

// The margins' verdicts only: the gains, the model's a1 and the phase crossovers are not carried.
void ReadMarginVerdicts(const JsonNode& margins, PipelineResult& r) {
  margins.ExpectArray();
  if (margins.Size() != 2) margins.Expected("two directions, forward then backward");
  r.margins.emplace();
  r.margins->directions.resize(2);
  for (size_t i = 0; i < 2; ++i) {
    const JsonNode m = margins.Element(i);
    m.ExpectObject({"direction", "crossover_rad_s", "phase_margin_deg", "gain_margin", "stable"});
    const char* name = i == 0 ? "forward" : "backward";
    if (m.Get("direction").String() != name)
      m.Get("direction").Expected(std::string("\"") + name + "\"");
    r.margins->directions[i].direction = name;
    LoopMargins& l = r.margins->directions[i].margins;
    l.crossover_rad_s = m.Get("crossover_rad_s").NumberOrNaN(Rule::Positive());
    l.phase_margin_deg = m.Get("phase_margin_deg").NumberOrNaN();
    l.gain_margin = m.Get("gain_margin").NumberOrNaN(Rule::Positive());
    const JsonNode stable = m.Get("stable");
    if (stable.Boolean() != l.Stable())
      stable.Expected(std::string(l.Stable() ? "true" : "false") +
                      " (phase margin > 0 and gain margin > 1 or none)");
  }
}

// The facts' verdicts only: facts.json (the report) holds each fact's numbers and notes.
void ReadFactVerdicts(const JsonNode& root, PipelineResult& r) {
  if (root.Has("facts") != root.Has("facts_required_met"))
    root.Fail("facts and facts_required_met come together (a run with facts)");
  if (root.Has("facts")) {
    const JsonNode facts = root.Get("facts");
    facts.ExpectArray();
    r.facts.emplace();
    for (size_t i = 0; i < facts.Size(); ++i) {
      const JsonNode f = facts.Element(i);
      f.ExpectObject({"id", "required", "met"});
      StageFact fact;
      fact.id = f.Get("id").String(true);
      fact.required = f.Get("required").Boolean();
      fact.met = f.Get("met").Boolean();
      r.facts->facts.push_back(fact);
    }
    const JsonNode met = root.Get("facts_required_met");
    if (met.Boolean() != r.facts->RequiredMet())
      met.Expected(std::string(r.facts->RequiredMet() ? "true" : "false") +
                   " (every required fact's met)");
  }
}

}  // namespace

PipelineResult PipelineResultFromJson(std::string_view text, const std::string& source_name) {
  const internal::JsonDocument doc(text, source_name);
  const JsonNode root = doc.Root();
  PipelineResult r;
  // The described keys, then the frame's. "report" is the path `sysid pipeline --json` adds in
  // front of the library's summary.
  internal::ReadFields(root, r,
                       {"dominant", "nn_inputs", "hidden", "network", "nn_test_mse",
                        "typical_train_mse", "typical_test_mse", "tuned_pi", "margins", "facts",
                        "facts_required_met", "report"});
  // The model once more through the model file's reader: its rules, placed in the text.
  r.model = internal::ModelFromJson(doc, root.Get("model"), {"units"});
  if (root.Has("skipped")) {
    // A pulse-only run: the network's keys are absent.
    for (const char* key : {"dominant", "nn_inputs", "hidden", "network", "nn_test_mse"})
      if (root.Has(key))
        root.Get(key).Expected("no network key in a run that skipped the network (\"skipped\")");
    if (r.skipped.empty()) root.Get("skipped").Expected("the steps skipped (a non-empty list)");
  } else {
    r.dominance.dominant = root.Get("dominant").String();
    const JsonNode inputs = root.Get("nn_inputs");
    inputs.ExpectArray();
    for (size_t i = 0; i < inputs.Size(); ++i)
      r.nn_inputs.push_back(inputs.Element(i).String(true));
    r.network = internal::NeuralNetworkFromJson(root.Get("network"));
    // hidden is the network's, written for readers of the summary: checked, not stored.
    const JsonNode hidden = root.Get("hidden");
    if (hidden.Integer(0, std::numeric_limits<int>::max()) != r.network.hidden_size())
      hidden.Expected(std::to_string(r.network.hidden_size()) + " (the network's hidden units)");
    r.network_test_mse = root.Get("nn_test_mse").NumberOrNaN(Rule::NonNegative());
  }
  if (root.Has("typical_train_mse") != root.Has("typical_test_mse"))
    root.Fail("typical_train_mse and typical_test_mse come together (a typical network)");
  if (root.Has("typical_train_mse")) {
    // The summary carries the typical network's MSEs, not the network.
    r.typical.emplace();
    r.typical->train_mse = root.Get("typical_train_mse").NumberOrNaN(Rule::NonNegative());
    r.typical_test_mse = root.Get("typical_test_mse").NumberOrNaN(Rule::NonNegative());
  }
  if (root.Has("tuned_pi")) {
    // The gains only: the tuning's targets and margins are in the report (tuned_pi.json).
    const JsonNode t = root.Get("tuned_pi");
    t.ExpectObject({"kp_v_per_m", "ki_v_per_m_s", "sample_time_s"});
    r.tuning.emplace();
    r.tuning->pi.kp_v_per_m = t.Get("kp_v_per_m").Number(Rule::NonNegative());
    r.tuning->pi.ki_v_per_m_s = t.Get("ki_v_per_m_s").Number(Rule::NonNegative());
    r.tuning->pi.sample_time_s = t.Get("sample_time_s").Number(Rule::Positive());
  }
  if (root.Has("margins")) ReadMarginVerdicts(root.Get("margins"), r);
  ReadFactVerdicts(root, r);
  // A step's wall time is a duration (the pair's reader takes any number).
  const JsonNode steps = root.Get("steps");
  for (size_t i = 0; i < steps.Size(); ++i)
    steps.Element(i).Get("wall_time_s").Number(Rule::NonNegative());
  return r;
}

std::string ToJson(const PipelineOptions& o, int indent) {
  return internal::FieldsToJson(o, indent);
}

PipelineOptions PipelineOptionsFromJson(std::string_view text, const std::string& source_name) {
  const internal::JsonDocument doc(text, source_name);
  PipelineOptions o;
  internal::ReadFields(doc.Root(), o);
  // The facts' options are checked as RunStageFacts checks them, after the pipeline's, and
  // their errors are placed inside "facts_options" (which repeats keys such as delay.*).
  internal::ValidateOptions(doc, [&] { o.Validate(); });
  internal::ValidateOptions(doc, [&] { o.facts_options.Validate(); }, "/facts_options");
  return o;
}

}  // namespace sysid
