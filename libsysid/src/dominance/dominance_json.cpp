// JSON of the dominant-variable analysis (docs/cli.md: dominance --json).
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>

#include "core/json_text.hpp"
#include "sysid/dominance.hpp"
#include "sysid/error.hpp"

namespace sysid {
namespace {

using Json = nlohmann::ordered_json;

// A ranked variable (with its ratio bounds) or a term of the inverse model.
Json StatsJson(const TermStats& s, bool ranking) {
  Json j;
  j[ranking ? "variable" : "term"] = s.name;
  j["rms"] = s.rms;
  j["peak"] = s.peak;
  j["ratio_to_top"] = s.ratio_to_top;
  if (ranking) {
    j["ratio_bound"] = s.ratio_bound;
    j["ratio_max"] = s.ratio_max;
    j["negligible"] = s.negligible;
  }
  return j;
}

Json ResultJson(const DominanceResult& r) {
  Json j;
  j["source"] = r.source;
  Json rank = Json::array();
  for (const auto& s : r.ranking) rank.push_back(StatsJson(s, true));
  j["ranking"] = rank;
  j["dominant"] = r.dominant;
  j["margin"] = internal::NumberOrNull(r.margin);
  Json terms = Json::array();
  for (const auto& s : r.terms) terms.push_back(StatsJson(s, false));
  j["terms"] = terms;
  j["peak_ratio"] = r.peak_ratio;
  j["pointwise_ratio_quantile"] = r.pointwise_ratio_quantile;
  j["pointwise_ratio_max"] = r.pointwise_ratio_max;
  j["samples"] = r.samples;
  j["moving_samples"] = r.moving_samples;
  return j;
}

}  // namespace

std::string ToJson(const DominanceResult& result, int indent) {
  return internal::DumpJson(ResultJson(result), indent);
}

DominanceResult DominanceResultFromJson(std::string_view text, const std::string& source_name) {
  const internal::JsonDocument doc(text, source_name);
  const internal::JsonNode root = doc.Root();
  root.ExpectObject({"source", "ranking", "dominant", "margin", "terms", "peak_ratio",
                     "pointwise_ratio_quantile", "pointwise_ratio_max", "samples",
                     "moving_samples"});
  using Rule = internal::NumberRule;
  auto stats = [&](const internal::JsonNode& list, bool ranking) {
    list.ExpectArray();
    std::vector<TermStats> out;
    for (size_t i = 0; i < list.Size(); ++i) {
      const internal::JsonNode e = list.Element(i);
      if (ranking)
        e.ExpectObject({"variable", "rms", "peak", "ratio_to_top", "ratio_bound", "ratio_max",
                        "negligible"});
      else
        e.ExpectObject({"term", "rms", "peak", "ratio_to_top"});
      TermStats t;
      t.name = e.Get(ranking ? "variable" : "term").String(true);
      t.rms = e.Get("rms").Number(Rule::NonNegative());
      t.peak = e.Get("peak").Number(Rule::NonNegative());
      t.ratio_to_top = e.Get("ratio_to_top").Number(Rule::NonNegative());
      if (ranking) {
        t.ratio_bound = e.Get("ratio_bound").Number(Rule::NonNegative());
        t.ratio_max = e.Get("ratio_max").Number(Rule::NonNegative());
        t.negligible = e.Get("negligible").Boolean();
      }
      out.push_back(t);
    }
    return out;
  };
  DominanceResult r;
  r.source = root.Get("source").String();
  r.ranking = stats(root.Get("ranking"), true);
  r.dominant = root.Get("dominant").String();
  const double margin = root.Get("margin").NumberOrNaN(Rule::NonNegative());
  r.margin = std::isnan(margin) ? std::numeric_limits<double>::infinity() : margin;
  r.terms = stats(root.Get("terms"), false);
  r.peak_ratio = root.Get("peak_ratio").Number(Rule::NonNegative());
  r.pointwise_ratio_quantile = root.Get("pointwise_ratio_quantile").Number(Rule::NonNegative());
  r.pointwise_ratio_max = root.Get("pointwise_ratio_max").Number(Rule::NonNegative());
  r.samples = root.Get("samples").Integer(0, 1L << 40);
  r.moving_samples = root.Get("moving_samples").Integer(0, r.samples);
  return r;
}

std::string ToJson(const DominanceSummary& s, int indent) {
  Json j;
  Json rank = Json::array();
  // Pooled statistics have no pointwise ratios: only the RMS-based fields.
  for (const auto& t : s.ranking)
    rank.push_back({{"variable", t.name},
                    {"rms", t.rms},
                    {"peak", t.peak},
                    {"ratio_to_top", t.ratio_to_top},
                    {"negligible", t.negligible}});
  j["ranking"] = rank;
  j["dominant"] = s.ranking.empty() ? Json(nullptr) : Json(s.ranking[0].name);
  j["negligible_ratio"] = s.negligible_ratio;
  j["min_speed_mps"] = s.min_speed_mps;
  Json counts = Json::object();
  for (const auto& [k, c] : s.dominant_counts) counts[k] = c;
  j["summary"] = {{"recordings", s.results.size()},
                  {"dominant_counts", counts},
                  {"min_margin", s.min_margin},
                  {"median_margin", s.median_margin}};
  Json per = Json::array();
  for (const auto& r : s.results) per.push_back(ResultJson(r));
  j["recordings"] = per;
  return internal::DumpJson(j, indent);
}

}  // namespace sysid
