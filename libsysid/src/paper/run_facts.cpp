// RunStageFacts: the facts run on one experiment cache, then their text.
#include <algorithm>
#include <memory>
#include <set>
#include <string>

#include "paper/facts_results.hpp"
#include "paper/facts_table.hpp"

namespace sysid {
namespace paper {
namespace {

// Each fact by its id, in id order: what it stores from the experiments it reads.
struct FactEntry {
  const char* id;
  void (*check)(Experiments& experiments, FactsResults& results);
};

const FactEntry kFacts[] = {
    {"F1", [](Experiments& x, FactsResults& r) { r.f1 = CheckPlateaus(x); }},
    {"F2", [](Experiments& x, FactsResults& r) { r.f2 = CheckPulseModel(x); }},
    {"F3", [](Experiments& x, FactsResults& r) { r.f3 = CheckDelay(x); }},
    {"F4", [](Experiments& x, FactsResults& r) { r.f4 = CheckPaperGains(x); }},
    {"F5", [](Experiments& x, FactsResults& r) { r.f5 = CheckTracking(x); }},
    {"F6", [](Experiments& x, FactsResults& r) { r.f6 = CheckDominance(x); }},
    {"F7", [](Experiments& x, FactsResults& r) { r.f7 = CheckNetworks(x); }},
    {"F8", [](Experiments& x, FactsResults& r) { r.f8 = CheckVoltageLoop(x); }},
};

}  // namespace

const std::vector<std::string>& FactIds() {
  static const std::vector<std::string> ids = [] {
    std::vector<std::string> out;
    for (const FactEntry& e : kFacts) out.push_back(e.id);
    return out;
  }();
  return ids;
}

FactsResults CheckFacts(const StageParameters& stage, const FactsOptions& options,
                        const FactsProgress& progress) {
  std::set<std::string> want(options.facts.begin(), options.facts.end());
  if (want.empty()) want.insert(FactIds().begin(), FactIds().end());
  // The typical network trains with the dominant one, on the same sets, when F7 reads it.
  Experiments experiments(stage, options, progress, want.count("F7") > 0);
  FactsResults r;
  for (const FactEntry& e : kFacts)
    if (want.count(e.id)) e.check(experiments, r);
  r.pulse = experiments.pulses_run();
  r.delay = experiments.delay_run();
  r.tracking = experiments.tracking_runs();
  return r;
}

}  // namespace paper

StageFacts RunStageFacts(const StageParameters& stage, const FactsOptions& options,
                         const FactsProgress& progress) {
  options.Validate();
  stage.Validate();
  auto results = std::make_shared<paper::FactsResults>(paper::CheckFacts(stage, options, progress));
  StageFacts r;
  r.stage_name = stage.name;
  r.facts = paper::FactsTable(*results, options);
  r.results = std::move(results);
  return r;
}

}  // namespace sysid
