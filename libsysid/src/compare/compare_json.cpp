// JSON of the inverse-model comparison (docs/cli.md: compare --json "recordings" entries) and
// its options; the comparisons' CSV table (compare -o's summary.csv).
#include <fmt/format.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "core/json_fields.hpp"
#include "core/json_text.hpp"
#include "signal/signal_json.hpp"
#include "sysid/compare.hpp"
#include "sysid/io_csv_table.hpp"

namespace sysid {
namespace {
using Json = nlohmann::ordered_json;

Json ErrorsJson(const PredictionErrors& e) { return internal::WriteFields(e); }
}  // namespace

std::string ToJson(const PredictionErrors& errors, int indent) {
  return internal::FieldsToJson(errors, indent);
}

PredictionErrors PredictionErrorsFromJson(std::string_view text, const std::string& source_name) {
  const internal::JsonDocument doc(text, source_name);
  PredictionErrors e;
  internal::ReadFields(doc.Root(), e);
  return e;
}

std::string ToJson(const InverseComparison& c, int indent) {
  Json j;
  j["file"] = c.source;
  j["samples"] = c.t_s.size();
  j["v_a_from"] = c.motion_from;
  if (c.has_analytic) j["analytic"] = ErrorsJson(c.analytic);
  if (c.has_nn) j["nn"] = ErrorsJson(c.nn);
  if (!c.hysteresis.empty()) {
    j["hysteresis"] = internal::JsonForm<std::vector<HysteresisInverseResult>>::Write(c.hysteresis);
  }
  return internal::DumpJson(j, indent);
}

std::string ToJson(const CompareOptions& o, int indent) {
  return internal::FieldsToJson(o, indent);
}

CompareOptions CompareOptionsFromJson(std::string_view text, const std::string& source_name) {
  return internal::FieldsFromJson<CompareOptions>(text, source_name);
}

std::string ComparisonTableCsv(const std::vector<InverseComparison>& comparisons) {
  CsvTable csv({"recording", "model", "rmse_v", "peak_error_v", "nrmse_range", "r2"});
  for (const auto& c : comparisons) {
    const std::string name = std::filesystem::path(c.source).stem().string();
    auto row = [&](const std::string& which, const PredictionErrors& e) {
      csv.Text(name).Text(which).Number(e.rmse_v).Number(e.peak_error_v).Number(e.nrmse_range)
          .Number(e.r2).EndRow();
    };
    if (c.has_analytic) row("analytic", c.analytic);
    if (c.has_nn) row("nn", c.nn);
    for (const auto& h : c.hysteresis) row(h.label, h.errors);
  }
  return csv.str();
}

}  // namespace sysid
