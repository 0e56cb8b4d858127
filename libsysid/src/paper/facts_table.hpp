// Private: each fact's text, the report layer of the facts: the one-line statement, the
// paper's value, the stage's, the criterion, the note and the named numbers of
// `sysid stage facts` and its JSON, made from the typed results.
#ifndef SYSID_SRC_PAPER_FACTS_TABLE_HPP_
#define SYSID_SRC_PAPER_FACTS_TABLE_HPP_

#include <string>
#include <vector>

#include "paper/facts_results.hpp"
#include "sysid/stage_facts.hpp"

namespace sysid::paper {

/// One row per fact that was run, in id order.
std::vector<StageFact> FactsTable(const FactsResults& results, const FactsOptions& options);

}  // namespace sysid::paper

#endif  // SYSID_SRC_PAPER_FACTS_TABLE_HPP_
