// JSON of the dominant-variable analysis and its options (docs/cli.md: dominance --json).
#include "dominance/dominance_json.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>

#include "core/json_fields.hpp"
#include "core/json_text.hpp"
#include "signal/signal_json.hpp"
#include "sysid/dominance.hpp"
#include "sysid/error.hpp"

namespace sysid {
namespace {

using Json = nlohmann::ordered_json;

// A term of the inverse model: no pointwise ratios.
Json TermJson(const TermStats& s) {
  Json j;
  j["term"] = s.name;
  j["rms"] = s.rms;
  j["peak"] = s.peak;
  j["ratio_to_top"] = s.ratio_to_top;
  return j;
}

// The described fields, with the terms written after the margin (their own, shorter form).
Json ResultJson(const DominanceResult& r) {
  Json j;
  const Json fields = internal::WriteFields(r);
  for (auto it = fields.begin(); it != fields.end(); ++it) {
    j[it.key()] = *it;
    if (it.key() == "margin") {
      Json terms = Json::array();
      for (const auto& s : r.terms) terms.push_back(TermJson(s));
      j["terms"] = terms;
    }
  }
  return j;
}

using internal::JsonNode;
using Rule = internal::NumberRule;

// What a TermStats entry carries beside a ranked variable's described fields: a term of the
// inverse model or a variable of the pooled ranking (no pointwise ratios).
enum class StatsKind { kTerm, kPooled };

std::vector<TermStats> StatsFromJson(const JsonNode& list, StatsKind kind) {
  list.ExpectArray();
  std::vector<TermStats> out;
  for (size_t i = 0; i < list.Size(); ++i) {
    const JsonNode e = list.Element(i);
    if (kind == StatsKind::kTerm)
      e.ExpectObject({"term", "rms", "peak", "ratio_to_top"});
    else
      e.ExpectObject({"variable", "rms", "peak", "ratio_to_top", "negligible"});
    TermStats t;
    t.name = e.Get(kind == StatsKind::kTerm ? "term" : "variable").String(true);
    t.rms = e.Get("rms").Number(Rule::NonNegative());
    t.peak = e.Get("peak").Number(Rule::NonNegative());
    t.ratio_to_top = e.Get("ratio_to_top").Number(Rule::NonNegative());
    if (kind != StatsKind::kTerm) t.negligible = e.Get("negligible").Boolean();
    out.push_back(t);
  }
  return out;
}

// A margin statistic written as null when infinite (a single candidate).
double MarginFromJson(const JsonNode& node) {
  const double m = node.NumberOrNaN(Rule::NonNegative());
  return std::isnan(m) ? std::numeric_limits<double>::infinity() : m;
}

// One recording's object: the whole text of ToJson(DominanceResult), or a `recordings` entry.
DominanceResult ResultFromJson(const JsonNode& root) {
  DominanceResult r;
  internal::ReadFields(root, r, {"terms"});
  r.terms = StatsFromJson(root.Get("terms"), StatsKind::kTerm);
  root.Get("moving_samples").Integer(0, r.samples);  // a part of the record: checked, not kept
  return r;
}

}  // namespace

std::string ToJson(const DominanceResult& result, int indent) {
  return internal::DumpJson(ResultJson(result), indent);
}

DominanceResult DominanceResultFromJson(std::string_view text, const std::string& source_name) {
  const internal::JsonDocument doc(text, source_name);
  return ResultFromJson(doc.Root());
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

DominanceSummary DominanceSummaryFromJson(std::string_view text, const std::string& source_name) {
  const internal::JsonDocument doc(text, source_name);
  const JsonNode root = doc.Root();
  root.ExpectObject({"ranking", "dominant", "negligible_ratio", "min_speed_mps", "summary",
                     "recordings"});
  DominanceSummary s;
  s.ranking = StatsFromJson(root.Get("ranking"), StatsKind::kPooled);
  // "dominant" is the pooled ranking's top (null when empty): derived, so only checked.
  const JsonNode top = root.Get("dominant");
  if (s.ranking.empty() ? !top.json().is_null() : top.String() != s.ranking[0].name)
    top.Expected(s.ranking.empty() ? "null (the ranking is empty)"
                                   : "\"" + s.ranking[0].name + "\" (the ranking's first)");
  s.negligible_ratio = root.Get("negligible_ratio").Number(Rule{0.0, 1.0, true, true});
  s.min_speed_mps = root.Get("min_speed_mps").Number(Rule::NonNegative());
  const JsonNode per = root.Get("recordings");
  per.ExpectArray();
  for (size_t i = 0; i < per.Size(); ++i) s.results.push_back(ResultFromJson(per.Element(i)));
  const JsonNode sum = root.Get("summary");
  sum.ExpectObject({"recordings", "dominant_counts", "min_margin", "median_margin"});
  const long n = static_cast<long>(s.results.size());
  sum.Get("recordings").Integer(n, n);  // the length of "recordings"
  const JsonNode counts = sum.Get("dominant_counts");
  if (!counts.json().is_object()) counts.Expected("an object of variable: recordings");
  // The reader's objects iterate keys in sorted order, as AnalyzeDominanceBatch's std::map
  // does: the same stable sort by count, descending, gives the library's (and the text's) order.
  for (const auto& item : counts.json().items())
    s.dominant_counts.emplace_back(item.key(),
                                   static_cast<int>(counts.Get(item.key()).Integer(1, n)));
  std::stable_sort(s.dominant_counts.begin(), s.dominant_counts.end(),
                   [](const auto& a, const auto& b) { return a.second > b.second; });
  if (!s.dominant_counts.empty()) s.dominant = s.dominant_counts[0].first;
  s.min_margin = MarginFromJson(sum.Get("min_margin"));
  s.median_margin = MarginFromJson(sum.Get("median_margin"));
  return s;
}

namespace internal {

Json JsonForm<std::vector<CandidateTerm>>::Write(const std::vector<CandidateTerm>& candidates) {
  Json j = Json::array();
  for (const auto& c : candidates)
    j.push_back({{"variable", c.variable}, {"column", c.column}, {"gain", c.gain}});
  return j;
}

void JsonForm<std::vector<CandidateTerm>>::Read(const JsonNode& list,
                                                std::vector<CandidateTerm>& candidates) {
  list.ExpectArray();
  candidates.clear();
  for (size_t i = 0; i < list.Size(); ++i) {
    const JsonNode c = list.Element(i);
    c.ExpectObject({"variable", "column", "gain"});
    CandidateTerm term;
    term.variable = c.Get("variable").String(true);
    term.column = c.Get("column").String(true);
    ReadOptional(c, "gain", term.gain);
    candidates.push_back(term);
  }
}

}  // namespace internal

std::string ToJson(const DominanceOptions& o, int indent) {
  return internal::FieldsToJson(o, indent);
}

DominanceOptions DominanceOptionsFromJson(std::string_view text, const std::string& source_name) {
  return internal::FieldsFromJson<DominanceOptions>(text, source_name);
}

}  // namespace sysid
