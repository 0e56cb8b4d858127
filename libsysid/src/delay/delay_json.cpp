// JSON of the delay-tuning and refinement options and results (docs/cli.md: tune-delay, refine).
#include "delay/delay_json.hpp"

#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "core/json_fields.hpp"
#include "core/json_text.hpp"
#include "identify/identify_json.hpp"
#include "model/model_json.hpp"
#include "motion/motion_json.hpp"
#include "sysid/delay.hpp"
#include "sysid/model.hpp"

namespace sysid {
namespace {
using internal::JsonNode;
using Json = nlohmann::ordered_json;
constexpr long kMaxCount = std::numeric_limits<long>::max();
}  // namespace

std::string ToJson(const DelayTuningResult& r, int indent) {
  Json j;
  j["tau"] = r.tau_s;
  j["cost"] = r.cost;
  j["rms_error_mps"] = r.rms_error_mps;
  j["evaluations"] = r.evaluations;
  j["simulations"] = r.simulations;
  j["segments"] = r.segments;
  j["samples"] = r.samples;
  j["termination"] = ToString(r.termination);
  j["message"] = r.message;
  j["wall_time_s"] = r.wall_time_s;
  j["warnings"] = r.warnings;
  Json c = Json::array();
  for (const auto& [t, f] : r.curve) c.push_back({{"tau", t}, {"cost", f}});
  j["curve"] = c;
  j["model"] = Json::parse(ModelToJson(r.model, -1));
  return internal::DumpJson(j, indent);
}

DelayTuningResult DelayTuningResultFromJson(std::string_view text, const std::string& source_name) {
  const internal::JsonDocument doc(text, source_name);
  const JsonNode root = doc.Root();
  root.ExpectObject({"tau", "cost", "rms_error_mps", "evaluations", "simulations", "segments",
                     "samples", "termination", "message", "wall_time_s", "warnings", "curve",
                     "model"});
  using Rule = internal::NumberRule;
  DelayTuningResult r;
  r.tau_s = root.Get("tau").Number(Rule::NonNegative());
  r.cost = root.Get("cost").Number(Rule::NonNegative());
  r.rms_error_mps = root.Get("rms_error_mps").Number(Rule::NonNegative());
  r.evaluations = static_cast<int>(root.Get("evaluations").Integer(0, 1L << 30));
  r.simulations = root.Get("simulations").Integer(0, kMaxCount);
  r.segments = static_cast<int>(root.Get("segments").Integer(0, 1L << 30));
  r.samples = root.Get("samples").Integer(0, kMaxCount);
  r.termination = internal::TerminationFromJson(root.Get("termination"));
  r.message = root.Get("message").String();
  r.wall_time_s = root.Get("wall_time_s").Number(Rule::NonNegative());
  const JsonNode w = root.Get("warnings");
  w.ExpectArray();
  for (size_t i = 0; i < w.Size(); ++i) r.warnings.push_back(w.Element(i).String());
  const JsonNode c = root.Get("curve");
  c.ExpectArray();
  for (size_t i = 0; i < c.Size(); ++i) {
    const JsonNode e = c.Element(i);
    e.ExpectObject({"tau", "cost"});
    r.curve.emplace_back(e.Get("tau").Number(), e.Get("cost").NumberOrNaN());
  }
  r.model = internal::ModelFromJson(doc, root.Get("model"), {"units"});
  return r;
}

std::string ToJson(const RefineResult& r, int indent) {
  Json j = Json::parse(ModelToJson(r.model, -1));
  Json se = Json::object();
  for (size_t i = 0; i < r.names.size(); ++i)
    se[r.names[i]] = internal::NumberOrNull(r.std_error[static_cast<Eigen::Index>(i)]);
  j["diagnostics"] = {{"method", "output-error"},
                      {"std_error", se},
                      {"initial_cost", r.initial_cost},
                      {"final_cost", r.final_cost},
                      {"rms_error_mps", r.rms_error_mps},
                      {"iterations", r.iterations},
                      {"simulations", r.simulations},
                      {"termination", ToString(r.termination)},
                      {"message", r.message},
                      {"warnings", r.warnings}};
  return internal::DumpJson(j, indent);
}

RefineResult RefineResultFromJson(std::string_view text, const std::string& source_name) {
  RefineResult r;
  const internal::JsonDocument doc(text, source_name);
  r.model = internal::ModelFromJson(doc, doc.Root(), {"units", "diagnostics"});
  const JsonNode d = doc.Root().Get("diagnostics");
  d.ExpectObject({"method", "std_error", "initial_cost", "final_cost", "rms_error_mps",
                  "iterations", "simulations", "termination", "message", "warnings",
                  "wall_time_s"});
  if (d.Get("method").String() != "output-error") d.Get("method").Expected("\"output-error\"");
  using Rule = internal::NumberRule;
  // std_error keeps the order written (the refined parameters' order): read the raw object.
  const JsonNode se = d.Get("std_error");
  se.ExpectObject({"a1p", "a1n", "a2p", "a2n", "a3", "tau"});
  std::vector<double> values;
  for (const auto& name : {"a1p", "a1n", "a2p", "a2n", "a3", "tau"})
    if (se.Has(name)) {
      r.names.emplace_back(name);
      values.push_back(se.Get(name).NumberOrNaN(Rule::NonNegative()));
    }
  r.std_error =
      Eigen::Map<const Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(values.size()));
  r.initial_cost = d.Get("initial_cost").Number(Rule::NonNegative());
  r.final_cost = d.Get("final_cost").Number(Rule::NonNegative());
  r.rms_error_mps = d.Get("rms_error_mps").Number(Rule::NonNegative());
  r.iterations = static_cast<int>(d.Get("iterations").Integer(0, 1L << 30));
  r.simulations = d.Get("simulations").Integer(0, kMaxCount);
  r.termination = internal::TerminationFromJson(d.Get("termination"));
  r.message = d.Get("message").String();
  // Files written before warnings existed have none; older ones carried wall_time_s.
  if (d.Has("warnings")) {
    const JsonNode w = d.Get("warnings");
    w.ExpectArray();
    for (size_t i = 0; i < w.Size(); ++i) r.warnings.push_back(w.Element(i).String());
  }
  if (d.Has("wall_time_s")) r.wall_time_s = d.Get("wall_time_s").Number(Rule::NonNegative());
  return r;
}

// ---- Options ----


std::string ToJson(const SegmentOptions& o, int indent) {
  return internal::FieldsToJson(o, indent);
}

SegmentOptions SegmentOptionsFromJson(std::string_view text, const std::string& source_name) {
  return internal::FieldsFromJson<SegmentOptions>(text, source_name);
}

std::string ToJson(const DelayTuningOptions& o, int indent) {
  return internal::FieldsToJson(o, indent);
}

DelayTuningOptions DelayTuningOptionsFromJson(std::string_view text,
                                              const std::string& source_name) {
  return internal::FieldsFromJson<DelayTuningOptions>(text, source_name);
}

std::string ToJson(const RefineOptions& o, int indent) { return internal::FieldsToJson(o, indent); }

RefineOptions RefineOptionsFromJson(std::string_view text, const std::string& source_name) {
  return internal::FieldsFromJson<RefineOptions>(text, source_name);
}

}  // namespace sysid
