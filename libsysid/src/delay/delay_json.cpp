// JSON of the delay-tuning and refinement options and results (docs/cli.md: tune-delay, refine).
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "core/json_text.hpp"
#include "delay/delay_json.hpp"
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

namespace {

using internal::ReadOptional;

Json SegmentOptionsJson(const SegmentOptions& o) {
  Json j;
  j["detection"] = internal::PulseDetectionOptionsJson(o.detection);
  j["rest_speed_mps"] = o.rest_speed_mps;
  j["reuse_identical_segments"] = o.reuse_identical_segments;
  return j;
}

void ReadSegmentOptions(const JsonNode& node, SegmentOptions& o) {
  node.ExpectObject({"detection", "rest_speed_mps", "reuse_identical_segments"});
  if (node.Has("detection"))
    internal::ReadPulseDetectionOptions(node.Get("detection"), o.detection);
  ReadOptional(node, "rest_speed_mps", o.rest_speed_mps);
  ReadOptional(node, "reuse_identical_segments", o.reuse_identical_segments);
}

void ReadRefineOptions(const JsonNode& node, RefineOptions& o) {
  node.ExpectObject({"motion", "detection", "refine_a3", "refine_tau", "tau_max_s",
                     "max_iterations", "threads", "sim_rtol"});
  if (node.Has("motion")) internal::ReadMotionOptions(node.Get("motion"), o.motion);
  if (node.Has("detection"))
    internal::ReadPulseDetectionOptions(node.Get("detection"), o.detection);
  ReadOptional(node, "refine_a3", o.refine_a3);
  ReadOptional(node, "refine_tau", o.refine_tau);
  ReadOptional(node, "tau_max_s", o.tau_max_s);
  ReadOptional(node, "max_iterations", o.max_iterations);
  ReadOptional(node, "threads", o.threads);
  ReadOptional(node, "sim_rtol", o.sim_rtol);
}

}  // namespace

namespace internal {

nlohmann::ordered_json DelayTuningOptionsJson(const DelayTuningOptions& o) {
  Json j;
  j["tau_min_s"] = o.tau_min_s;
  j["tau_max_s"] = o.tau_max_s;
  j["x_tolerance_s"] = o.x_tolerance_s;
  j["coarse_evaluations"] = o.coarse_evaluations;
  j["max_evaluations"] = o.max_evaluations;
  j["curve_points"] = o.curve_points;
  j["motion"] = MotionOptionsJson(o.motion);
  j["segments"] = SegmentOptionsJson(o.segments);
  j["sim_rtol"] = o.sim_rtol;
  j["sim_atol"] = o.sim_atol;
  j["threads"] = o.threads;
  return j;
}

void ReadDelayTuningOptions(const JsonNode& node, DelayTuningOptions& o) {
  node.ExpectObject({"tau_min_s", "tau_max_s", "x_tolerance_s", "coarse_evaluations",
                     "max_evaluations", "curve_points", "motion", "segments", "sim_rtol",
                     "sim_atol", "threads"});
  ReadOptional(node, "tau_min_s", o.tau_min_s);
  ReadOptional(node, "tau_max_s", o.tau_max_s);
  ReadOptional(node, "x_tolerance_s", o.x_tolerance_s);
  ReadOptional(node, "coarse_evaluations", o.coarse_evaluations);
  ReadOptional(node, "max_evaluations", o.max_evaluations);
  ReadOptional(node, "curve_points", o.curve_points);
  if (node.Has("motion")) ReadMotionOptions(node.Get("motion"), o.motion);
  if (node.Has("segments")) ReadSegmentOptions(node.Get("segments"), o.segments);
  ReadOptional(node, "sim_rtol", o.sim_rtol);
  ReadOptional(node, "sim_atol", o.sim_atol);
  ReadOptional(node, "threads", o.threads);
}

}  // namespace internal

std::string ToJson(const SegmentOptions& o, int indent) {
  return internal::DumpJson(SegmentOptionsJson(o), indent);
}

SegmentOptions SegmentOptionsFromJson(std::string_view text, const std::string& source_name) {
  return internal::OptionsFromJson<SegmentOptions>(text, source_name, ReadSegmentOptions);
}

std::string ToJson(const DelayTuningOptions& o, int indent) {
  return internal::DumpJson(internal::DelayTuningOptionsJson(o), indent);
}

DelayTuningOptions DelayTuningOptionsFromJson(std::string_view text,
                                              const std::string& source_name) {
  return internal::OptionsFromJson<DelayTuningOptions>(text, source_name,
                                                       internal::ReadDelayTuningOptions);
}

std::string ToJson(const RefineOptions& o, int indent) {
  Json j;
  j["motion"] = internal::MotionOptionsJson(o.motion);
  j["detection"] = internal::PulseDetectionOptionsJson(o.detection);
  j["refine_a3"] = o.refine_a3;
  j["refine_tau"] = o.refine_tau;
  j["tau_max_s"] = o.tau_max_s;
  j["max_iterations"] = o.max_iterations;
  j["threads"] = o.threads;
  j["sim_rtol"] = o.sim_rtol;
  return internal::DumpJson(j, indent);
}

RefineOptions RefineOptionsFromJson(std::string_view text, const std::string& source_name) {
  return internal::OptionsFromJson<RefineOptions>(text, source_name, ReadRefineOptions);
}

}  // namespace sysid
