// Private: the facts' typed results, each fact's numbers as fields (its criterion in its own
// file, f1_plateaus.hpp ... f8_voltage_loop.hpp), and the experiments behind them. The text
// of each fact (what `sysid stage facts` prints) is made from these in facts_table.cpp.
#ifndef SYSID_SRC_PAPER_FACTS_RESULTS_HPP_
#define SYSID_SRC_PAPER_FACTS_RESULTS_HPP_

#include <optional>
#include <string>
#include <vector>

#include "paper/experiments.hpp"
#include "paper/f1_plateaus.hpp"
#include "paper/f2_pulse_model.hpp"
#include "paper/f3_delay.hpp"
#include "paper/f4_paper_gains.hpp"
#include "paper/f5_tracking.hpp"
#include "paper/f6_dominance.hpp"
#include "paper/f7_networks.hpp"
#include "paper/f8_voltage_loop.hpp"

namespace sysid::paper {

struct FactsResults {
  // Each fact that was run (FactsOptions::facts).
  std::optional<PlateausFact> f1;
  std::optional<PulseModelFact> f2;
  std::optional<DelayFact> f3;
  std::optional<PaperGainsFact> f4;
  std::optional<TrackingFact> f5;
  std::optional<DominanceFact> f6;
  std::optional<NetworksFact> f7;
  std::optional<VoltageLoopFact> f8;
  // The experiments they read, as far as they were run.
  std::optional<PulseExperiment> pulse;
  std::optional<DelayExperiment> delay;
  std::vector<TrackingRun> tracking;  ///< in the order run
};

/// The ids F1..F8 in order.
const std::vector<std::string>& FactIds();

/// Runs the experiments the facts in `options.facts` need (all when empty), once each, and
/// checks those facts. `options` and `stage` are not validated here (RunStageFacts does).
FactsResults CheckFacts(const StageParameters& stage, const FactsOptions& options,
                        const FactsProgress& progress);

}  // namespace sysid::paper

#endif  // SYSID_SRC_PAPER_FACTS_RESULTS_HPP_
