// Private: sections of the pipeline's report that are computed apart from the report writer
// (the networks' figure pair, F8's loop numbers). Each returns its markdown, its plots and its
// files; the writer renders the plots and writes the files atomically.
#ifndef SYSID_SRC_REPORT_REPORT_SECTIONS_HPP_
#define SYSID_SRC_REPORT_REPORT_SECTIONS_HPP_

#include <string>
#include <utility>
#include <vector>

#include "sysid/pipeline.hpp"
#include "sysid/report.hpp"
#include "sysid/stage_facts.hpp"

namespace sysid::internal {

/// " Read with `--var ... --rate ... --scale ...`." when the inputs carry a mapping (so the
/// report says how its files were read), else "".
std::string MappingSentence(const PipelineInputs& inputs);

/// The pipeline's inverse network (nn.json) as every plot of its report labels it:
/// "NN inverse (v), H = 6".
std::string NetworkLabel(const PipelineResult& result);

struct ReportPlot {
  std::string file;  ///< e.g. "network_training.png"
  PlotSpec spec;
  std::string caption;
};

struct ReportSection {
  std::string markdown;
  std::vector<ReportPlot> plots;                        ///< drawn after the markdown
  std::vector<std::pair<std::string, std::string>> files;  ///< (file name, contents)
};

/// The four MSEs of the typical and the dominant network on the pipeline's sets, as the facts'
/// F7 computes them: each network on every row of the training set and of the test set.
struct NetworkMses {
  double typical_train = 0, typical_test = 0;    ///< [V^2]
  double dominant_train = 0, dominant_test = 0;  ///< [V^2]
};

/// The paper's figure pair (its Fig. 8 for the typical network, Fig. 11 for the dominant one):
/// each network's output against the data u [V] on the training set and on the test set (two
/// plots, network_training.png and network_test.png), and the four MSEs in one table with the
/// paper's beside them (network_mse.csv). Needs result.typical; reads the training and test
/// recordings again (v and a as the pipeline made them).
ReportSection NetworkFigurePair(const PipelineResult& result, NetworkMses* mses = nullptr);

/// F8's loop numbers (the triangle at its levels, the sinusoids' mean widths by frequency and
/// by amplitude) as markdown tables, and loop_fact.csv; empty markdown without F8.
ReportSection LoopFactSection(const StageFacts& facts);

/// The final friction model validated on the held-out recordings (result.validations): a
/// table per recording and output, validation.json, and each recording's velocity plots
/// (ValidationPlots: validate_<name>_v.png, validate_<name>_v_residual_tests.png); empty
/// without validations.
ReportSection ValidationSection(const PipelineResult& result);

}  // namespace sysid::internal

#endif  // SYSID_SRC_REPORT_REPORT_SECTIONS_HPP_
