// Private: the sections of the pipeline's report. Each is made from the PipelineResult alone
// (the report reads, simulates and fits nothing: scripts/check_modules.py checks report/ for
// such calls) and returns its markdown, its plots and its files; the writer
// (pipeline_report.cpp) renders the plots and writes the files.
#ifndef SYSID_SRC_REPORT_REPORT_SECTIONS_HPP_
#define SYSID_SRC_REPORT_REPORT_SECTIONS_HPP_

#include <cstddef>
#include <functional>
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
  /// Each drawn where AddPlot marked its place in the markdown; a plot pushed without a marker
  /// after the markdown.
  std::vector<ReportPlot> plots;
  std::vector<std::pair<std::string, std::string>> files;  ///< (file name, contents)
  /// Files that their own writer checks and writes (a model, a network, a recording):
  /// (file name, writer given the file's path); a writer may refer to the PipelineResult.
  std::vector<std::pair<std::string, std::function<void(const std::string&)>>> writes;
  std::vector<std::string> notes;  ///< for the run's notes (WritePipelineReport returns them)

  /// Queues a plot and marks its place at the end of the markdown.
  void AddPlot(std::string file, PlotSpec spec, std::string caption);
  /// `other` after this section: its markdown, plots (markers renumbered), files and notes.
  void Append(ReportSection other);
  /// The marker of plot `i` in the markdown.
  static std::string Marker(std::size_t i);
  /// A marker for every plot pushed without one, after the markdown.
  void MarkUnplaced();
};

/// `v` with `digits` significant digits (%.{digits}g).
std::string Sig(double v, int digits = 5);
/// The same, "-" for NaN (a number that was not computed).
std::string SigOrDash(double v, int digits = 4);
/// The strings of `v` separated by `sep`.
std::string JoinWith(const std::vector<std::string>& v, const std::string& sep);

// The sections in the report's order (each empty when its step did not run).
ReportSection PulseSection(const PipelineResult& result);       ///< 1: pulses.csv, model.json
ReportSection DelaySection(const PipelineResult& result);       ///< 2: cost curve, pulse response
ReportSection DominanceSection(const PipelineResult& result);   ///< 3: dominance.csv
ReportSection NetworkSection(const PipelineResult& result);     ///< 4: sweep.csv, nn.json
ReportSection ComparisonSection(const PipelineResult& result);  ///< 5: comparison.csv
ReportSection SkippedSection(const PipelineResult& result);     ///< 3-5 of a pulse-only run
ReportSection TrackingSection(const PipelineResult& result);    ///< 6: tracking.csv
ReportSection MarginsSection(const PipelineResult& result);     ///< 6: margins.json
ReportSection ModelTrackingSection(const PipelineResult& result);  ///< 6: model_tracking.csv
ReportSection FactsSection(const PipelineResult& result);          ///< 7: facts.json
ReportSection LoopsSection(const PipelineResult& result);          ///< 8: loops.csv, loop_N.json
ReportSection StepsSection(const PipelineResult& result);          ///< steps and notes

/// The four MSEs of the typical and the dominant network on the pipeline's sets, as the facts'
/// F7 computes them: each network on every row of the training set and of the test set.
struct NetworkMses {
  double typical_train = 0, typical_test = 0;    ///< [V^2]
  double dominant_train = 0, dominant_test = 0;  ///< [V^2]
};

/// The paper's figure pair (its Fig. 8 for the typical network, Fig. 11 for the dominant one):
/// each network's output against the data u [V] on the training set and on the test set (two
/// plots, network_training.png and network_test.png), and the four MSEs in one table with the
/// paper's beside them (network_mse.csv), from result.figures.networks. Needs result.typical.
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
