// The stage facts at several seeds: ParseFactsSeeds, RunStageFactsOverSeeds and the sweep's
// JSON and Markdown.
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "sysid/error.hpp"
#include "sysid/stage_facts.hpp"

namespace sysid {
namespace {

[[noreturn]] void BadSeeds(const std::string& text, const std::string& why) {
  throw OptionsError("seeds '" + text + "': " + why, "seeds");
}

// A decimal seed in [0, 2^62] (the range --seed accepts).
std::uint64_t ParseSeed(const std::string& text, const std::string& item) {
  if (item.empty() ||
      !std::all_of(item.begin(), item.end(), [](unsigned char c) { return std::isdigit(c); }))
    BadSeeds(text, "expected 'A-B' or 'A,B,...' with non-negative integers, got '" + item + "'");
  // 19 digits always fit in 64 bits; 2^62 has 19.
  if (item.size() > 19 || std::stoull(item) > (std::uint64_t{1} << 62))
    BadSeeds(text, "seed " + item + " is above 2^62");
  const std::uint64_t v = std::stoull(item);
  return v;
}

std::string JoinSeeds(const std::vector<std::uint64_t>& seeds) {
  std::string out;
  for (std::uint64_t s : seeds) out += (out.empty() ? "" : ", ") + std::to_string(s);
  return out.empty() ? "-" : out;
}

}  // namespace

std::vector<std::uint64_t> ParseFactsSeeds(const std::string& text) {
  const std::size_t dash = text.find('-');
  if (dash != std::string::npos) {
    const std::uint64_t a = ParseSeed(text, text.substr(0, dash));
    const std::uint64_t b = ParseSeed(text, text.substr(dash + 1));
    if (b < a) BadSeeds(text, "the range runs backwards");
    if (b - a >= kMaxFactsSeeds)
      BadSeeds(text, fmt::format("at most {} seeds per sweep", kMaxFactsSeeds));
    std::vector<std::uint64_t> seeds;
    for (std::uint64_t s = a; s <= b; ++s) seeds.push_back(s);
    return seeds;
  }
  std::vector<std::uint64_t> seeds;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    if (seeds.size() == kMaxFactsSeeds)
      BadSeeds(text, fmt::format("at most {} seeds per sweep", kMaxFactsSeeds));
    const std::uint64_t seed = ParseSeed(text, text.substr(start, comma - start));
    // A repeated seed reruns the same experiments: "3 of 3" over 1,1,1 would count one seed
    // three times.
    if (std::find(seeds.begin(), seeds.end(), seed) != seeds.end())
      BadSeeds(text, fmt::format("seed {} is given twice", seed));
    seeds.push_back(seed);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return seeds;
}

FactsSeedSweep RunStageFactsOverSeeds(const StageParameters& stage,
                                      const std::vector<std::uint64_t>& seeds,
                                      const FactsOptions& options, const FactsProgress& progress) {
  if (seeds.empty()) throw OptionsError("seeds: expected at least one seed", "seeds");
  if (seeds.size() > kMaxFactsSeeds)
    throw OptionsError(fmt::format("seeds: at most {} per sweep", kMaxFactsSeeds), "seeds");
  FactsSeedSweep sweep;
  sweep.seeds = seeds;
  for (std::size_t k = 0; k < seeds.size(); ++k) {
    FactsOptions o = options;
    o.seed = seeds[k];
    const std::string prefix = fmt::format("seed {} ({}/{}): ", seeds[k], k + 1, seeds.size());
    sweep.runs.push_back(RunStageFacts(stage, o, [&](const std::string& step) {
      if (progress) progress(prefix + step);
    }));
  }
  sweep.stage_name = sweep.runs.front().stage_name;
  return sweep;
}

std::vector<std::uint64_t> FactsSeedSweep::MetAt(const std::string& id) const {
  std::vector<std::uint64_t> met;
  for (std::size_t k = 0; k < runs.size(); ++k) {
    const StageFact* f = runs[k].Find(id);
    if (f && f->met) met.push_back(seeds[k]);
  }
  return met;
}

bool FactsSeedSweep::RequiredMetEverywhere() const {
  return std::all_of(runs.begin(), runs.end(), [](const StageFacts& r) { return r.RequiredMet(); });
}

std::string FactsSeedSweep::ToJson() const {
  nlohmann::ordered_json j;
  j["stage"] = stage_name;
  j["seeds"] = seeds;
  j["facts"] = nlohmann::ordered_json::array();
  if (!runs.empty()) {
    for (const StageFact& f : runs.front().facts) {
      nlohmann::ordered_json o;
      o["id"] = f.id;
      o["fact"] = f.fact;
      o["required"] = f.required;
      const std::vector<std::uint64_t> met = MetAt(f.id);
      o["met_count"] = met.size();
      o["runs"] = runs.size();
      o["met_seeds"] = met;
      nlohmann::ordered_json texts = nlohmann::ordered_json::array();
      for (const StageFacts& r : runs) texts.push_back(r.Find(f.id)->virtual_value);
      o["virtual"] = texts;
      j["facts"].push_back(o);
    }
  }
  j["required_met_everywhere"] = RequiredMetEverywhere();
  return j.dump(2);
}

std::string FactsSeedSweep::ToMarkdown() const {
  std::string md = fmt::format(
      "Seeds: {}\n\n| id | fact | met at | not met at |\n|---|---|---|---|\n", JoinSeeds(seeds));
  if (runs.empty()) return md;
  for (const StageFact& f : runs.front().facts) {
    const std::vector<std::uint64_t> met = MetAt(f.id);
    std::vector<std::uint64_t> missed;
    for (std::uint64_t s : seeds)
      if (std::find(met.begin(), met.end(), s) == met.end()) missed.push_back(s);
    md += fmt::format("| {}{} | {} | {} of {} | {} |\n", f.id, f.required ? "" : " (reported)",
                      f.fact, met.size(), seeds.size(), JoinSeeds(missed));
  }
  return md;
}

}  // namespace sysid
