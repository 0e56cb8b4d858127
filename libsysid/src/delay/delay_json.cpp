// JSON of the delay-tuning and refinement options and results (docs/cli.md: tune-delay, refine).
#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "core/json_fields.hpp"
#include "core/json_text.hpp"
#include "model/model_json.hpp"
#include "signal/signal_json.hpp"
#include "sysid/delay.hpp"
#include "sysid/model.hpp"

namespace sysid {
namespace {

using internal::JsonNode;
using Json = nlohmann::ordered_json;

// The refined parameters' standard errors by name, in the model's order; NaN (singular) as null.
Json StdErrors(const RefineResult& r) {
  Json se = Json::object();
  for (size_t i = 0; i < r.names.size(); ++i)
    se[r.names[i]] = internal::NumberOrNull(r.std_error[static_cast<Eigen::Index>(i)]);
  return se;
}

void ReadStdErrors(const JsonNode& se, RefineResult& r) {
  const std::vector<std::string> model_keys = internal::FieldNamesOf(r.model);
  se.ExpectObject(model_keys);
  // The written order is the refined parameters' order, a subset of the model's.
  std::vector<double> values;
  for (const auto& name : model_keys)
    if (se.Has(name)) {
      r.names.push_back(name);
      values.push_back(se.Get(name).NumberOrNaN(internal::NumberRule::NonNegative()));
    }
  r.std_error =
      Eigen::Map<const Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(values.size()));
}

constexpr char kRefineMethod[] = "output-error";

}  // namespace

std::string ToJson(const DelayTuningResult& r, int indent) {
  return internal::FieldsToJson(r, indent);
}

DelayTuningResult DelayTuningResultFromJson(std::string_view text, const std::string& source_name) {
  const internal::JsonDocument doc(text, source_name);
  DelayTuningResult r;
  internal::ReadFields(doc.Root(), r);
  return r;
}

std::string ToJson(const RefineResult& r, int indent) {
  Json j = internal::ModelJson(r.model);  // a model file, the diagnostics after it
  Json d = {{"method", kRefineMethod}, {"std_error", StdErrors(r)}};
  d.update(internal::WriteFields(r));
  j["diagnostics"] = d;
  return internal::DumpJson(j, indent);
}

RefineResult RefineResultFromJson(std::string_view text, const std::string& source_name) {
  RefineResult r;
  const internal::JsonDocument doc(text, source_name);
  r.model = internal::ModelFromJson(doc, doc.Root(), {"units", "diagnostics"});
  const JsonNode d = doc.Root().Get("diagnostics");
  // Older files carried the wall time; it is not read (files stay identical run to run).
  internal::ReadFields(d, r, {"method", "std_error", "wall_time_s"});
  if (d.Get("method").String() != kRefineMethod)
    d.Get("method").Expected(std::string("\"") + kRefineMethod + "\"");
  ReadStdErrors(d.Get("std_error"), r);
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
