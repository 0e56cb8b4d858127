// Dominant-variable analysis (the paper's section "Identification of the Dominant Variable").
//
// From measured signals, each term of the inverse model
//   a3 u = x'' + a1 v(t - tau) + a2 sgn(v)            [m/s^2]
// is computed over time: acceleration term T_a = x'', viscous term T_v = a1 v(t - tau) and
// Coulomb term T_c = a2 sgn(v) (+ any user-named candidate term g * column). Candidate input
// VARIABLES are ranked by the terms they generate: the acceleration generates T_a; the velocity
// generates T_v + T_c (the Coulomb term depends on the velocity's sign only; the paper neglects
// it as "effectively a constant" — the per-term table keeps it separate). The ratio
// |T_a| / |T_v| the paper bounds is reported two ways: `peak_ratio` = max |T_a| / max |T_v|, the
// ratio of the two curves' peaks, which is how the paper read "the bound" off its figure of the
// two terms; and `pointwise_ratio_*`, statistics of the pointwise ratio |T_a(t)| / |T_v(t)|, a
// different and much larger quantity (T_v passes near zero while T_a does not).
// Statistics are taken over the moving part of the record (|v| >= min_speed_mps), where the
// sliding equation holds. A variable is negligible when its RMS is at most negligible_ratio
// times the top variable's RMS.
#ifndef SYSID_DOMINANCE_HPP_
#define SYSID_DOMINANCE_HPP_

#include <Eigen/Core>
#include <string>
#include <string_view>
#include <vector>

#include "sysid/io.hpp"
#include "sysid/model.hpp"
#include "sysid/motion.hpp"
#include "sysid/serialize.hpp"

namespace sysid {

/// The least margin, rms(top) / rms(second), at which a variable is called dominant: the top's
/// term then carries at least four times the second's power (the second at most a fifth of
/// the two). Below it the ranking is reported as "no clear dominant variable" (docs/dominance.md).
inline constexpr double kClearDominanceMargin = 2.0;

/// "dominant variable v (margin 64.7)" or "no clear dominant variable: a leads v by a margin of
/// 1.04 (< 2)": the one wording of a ranking's verdict, for every report.
std::string DominanceVerdict(const std::string& top, const std::string& second, double margin);

/// A user-named candidate: the term gain * column [m/s^2] of a recording column.
struct CandidateTerm {
  std::string variable;  ///< name in the ranking
  std::string column;    ///< recording column
  double gain = 1.0;     ///< [m/s^2 per column unit]
  /// The fields, in file order (sysid/serialize.hpp).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(variable));
    a->Visit(SYSID_NVP(column));
    a->Visit(SYSID_NVP(gain));
  }
};

struct DominanceOptions {
  MotionOptions motion;         ///< how v and x'' are obtained (default: central differences)
  double min_speed_mps = 1e-3;  ///< [m/s] the moving part: |v| >= this
  /// A variable whose term RMS is <= negligible_ratio x the top variable's is negligible. The
  /// default 0.1 is one order of magnitude, the paper's O(10^-1) criterion.
  double negligible_ratio = 0.1;
  /// Quantile of the pointwise ratio |T_i(t)| / |T_top(t)| reported as the ratio bound; the
  /// maximum is reported too, but one noisy sample can set it [0, 1].
  double bound_quantile = 0.99;
  std::vector<CandidateTerm> candidates;  ///< further candidate variables
  int threads = 0;                        ///< recordings analysed in parallel (0: hardware threads)
  /// The fields, in file order (sysid/serialize.hpp).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(motion));
    a->Visit(SYSID_NVP(min_speed_mps));
    a->Visit(SYSID_NVP(negligible_ratio));
    a->Visit(SYSID_NVP(bound_quantile));
    a->Visit(SYSID_NVP(candidates));
    a->Visit(SYSID_NVP(threads));
  }
  void Validate() const;
};

/// Size of one term (or of one variable's summed terms) over the moving part.
struct TermStats {
  std::string name;
  double rms = 0;           ///< [m/s^2]
  double peak = 0;          ///< [m/s^2] max |term|
  double ratio_to_top = 0;  ///< rms / rms of the top-ranked entry
  double ratio_bound = 0;   ///< quantile of |term(t)| / |top(t)| over the moving part
  double ratio_max = 0;     ///< max of |term(t)| / |top(t)| over the moving part
  bool negligible = false;  ///< ratio_to_top <= negligible_ratio
  /// The fields of a ranked variable, in file order (sysid/serialize.hpp). A term of the inverse
  /// model and a pooled variable are written by dominance_json.cpp with fewer keys.
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(name).Renamed("variable").Required());
    a->Visit(SYSID_NVP(rms).Minimum(0).Required());
    a->Visit(SYSID_NVP(peak).Minimum(0).Required());
    a->Visit(SYSID_NVP(ratio_to_top).Minimum(0).Required());
    a->Visit(SYSID_NVP(ratio_bound).Minimum(0).Required());
    a->Visit(SYSID_NVP(ratio_max).Minimum(0).Required());
    a->Visit(SYSID_NVP(negligible).Required());
  }
};

struct DominanceResult {
  std::string source;
  Eigen::Index samples = 0;         ///< samples in the record
  Eigen::Index moving_samples = 0;  ///< samples with |v| >= min_speed_mps
  std::vector<TermStats> terms;     ///< acceleration, viscous, coulomb, candidates (fixed order)
  std::vector<TermStats> ranking;   ///< variables, largest RMS first
  std::string dominant;             ///< ranking[0].name
  double margin = 0;                ///< rms(top) / rms(second); inf with a single candidate
  /// max |x''| / max |a1 v(t - tau)| over the moving part: the ratio of peaks (the paper's bound)
  double peak_ratio = 0;
  /// bound_quantile quantile of the pointwise ratio |x''(t)| / |a1 v(t - tau)| (not the paper's)
  double pointwise_ratio_quantile = 0;
  double pointwise_ratio_max = 0;  ///< max of the pointwise ratio |x''(t)| / |a1 v(t - tau)|
  /// The fields, in file order (sysid/serialize.hpp); `terms` (fewer keys than a ranked
  /// variable) is written between margin and peak_ratio by dominance_json.cpp.
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(source).Required());
    a->Visit(SYSID_NVP(ranking).Required());
    a->Visit(SYSID_NVP(dominant).Required());
    a->Visit(SYSID_NVP(margin).UpperLimit().Minimum(0).Required());
    a->Visit(SYSID_NVP(peak_ratio).Minimum(0).Required());
    a->Visit(SYSID_NVP(pointwise_ratio_quantile).Minimum(0).Required());
    a->Visit(SYSID_NVP(pointwise_ratio_max).Minimum(0).Required());
    a->Visit(SYSID_NVP(samples).Minimum(0).Maximum(static_cast<double>(1L << 40)).Required());
    a->Visit(SYSID_NVP(moving_samples).Minimum(0).Required());
  }
  std::string BriefReport() const;
  /// BriefReport plus every diagnostic: each term's and variable's rms, peak and ratios, the
  /// pointwise ratio quantile and maximum.
  std::string FullReport() const;
};

/// Analyses one recording. Throws InputError for a missing candidate column, NumericalError when
/// the record has no moving samples.
DominanceResult AnalyzeDominance(const FrictionModel& model, const Recording& recording,
                                 const DominanceOptions& options = {});

/// The buffers AnalyzeDominance works in, kept from one recording to the next by a caller that
/// analyses many on one thread (a batch chunk): the motion signals, the delayed velocity, the
/// moving samples' terms and the ratio scratch. After the first recording nothing of size
/// O(samples) is allocated while the recordings keep one length. Results never depend on what
/// the workspace held before. One workspace per thread.
struct DominanceWorkspace {
  MotionSignals motion;
  Eigen::VectorXd delayed_v_mps;     ///< [m/s] v(t - tau)
  std::vector<Eigen::Index> moving;  ///< indices with |v| >= min_speed_mps
  Eigen::VectorXd acceleration;      ///< [m/s^2] the terms over the moving samples (a prefix)
  Eigen::VectorXd viscous;           ///< [m/s^2]
  Eigen::VectorXd coulomb;           ///< [m/s^2]
  Eigen::VectorXd velocity;          ///< [m/s^2] viscous + coulomb
  std::vector<Eigen::VectorXd> candidates;  ///< [m/s^2] one per DominanceOptions::candidates
  std::vector<double> ratios;               ///< pointwise ratios for the quantile
};

/// AnalyzeDominance in `workspace`'s buffers: the same result, fewer allocations.
DominanceResult AnalyzeDominance(const FrictionModel& model, const Recording& recording,
                                 const DominanceOptions& options, DominanceWorkspace* workspace);

struct DominanceSummary {
  std::vector<DominanceResult> results;                      ///< one per recording, input order
  std::vector<std::pair<std::string, int>> dominant_counts;  ///< variable -> recordings
  std::string dominant;   ///< the variable dominant in most recordings
  double min_margin = 0;  ///< smallest margin over the recordings
  double median_margin = 0;
  /// Variables ranked over all recordings pooled: RMS over all moving samples, peak over all;
  /// ratio_to_top and negligible as in one recording (ratio_bound, ratio_max are not pooled).
  std::vector<TermStats> ranking;
  double negligible_ratio = 0;  ///< the options the batch ran with (DominanceOptions)
  double min_speed_mps = 0;     ///< [m/s]
};

/// Analyses many recordings in parallel threads (results in input order). The first error in
/// input order is rethrown after all threads finish.
DominanceSummary AnalyzeDominanceBatch(const FrictionModel& model,
                                       const std::vector<Recording>& recordings,
                                       const DominanceOptions& options = {});

/// The variables ranked over all recordings pooled: a variable's rms is taken over every moving
/// sample of every recording, sqrt(sum_r n_r rms_r^2 / sum_r n_r) (n_r = moving_samples), its
/// peak is the largest peak; largest rms first, ratio_to_top set, and negligible when
/// ratio_to_top <= negligible_ratio (never the top). ratio_bound and ratio_max stay 0 (they
/// are pointwise, per recording). Empty for an empty summary.
std::vector<TermStats> PooledRanking(const DominanceSummary& summary, double negligible_ratio);

/// The batch as CSV: one row per (recording, ranked variable).
std::string DominanceTableCsv(const DominanceSummary& summary);

/// The options as JSON, every field (candidates as [{"variable", "column", "gain"}]), and
/// the reader: every key optional (a candidate's gain too), the result validated, InputError
/// "SOURCE:LINE:COL: NAME: expected ..., found ..." otherwise (as MotionOptionsFromJson).
std::string ToJson(const DominanceOptions& options, int indent = 2);
DominanceOptions DominanceOptionsFromJson(std::string_view text, const std::string& source_name);

/// One recording's analysis as JSON: source, ranking, dominant, margin (null with a single
/// candidate), terms, the ratios and sample counts (a `recordings` entry of `dominance --json`).
std::string ToJson(const DominanceResult& result, int indent = 2);
/// Reads what ToJson(DominanceResult) writes (a null margin reads as infinity; the terms'
/// pointwise ratios and negligible flags, not written, stay 0/false). Throws InputError
/// "SOURCE:LINE:COL: NAME: expected ..., found ...".
DominanceResult DominanceResultFromJson(std::string_view text, const std::string& source_name);
/// The batch as `sysid dominance --json` prints it: pooled ranking, dominant, the options,
/// summary (counts, margins) and every recording's analysis.
std::string ToJson(const DominanceSummary& summary, int indent = 2);
/// Reads what ToJson(DominanceSummary) writes: each recording as DominanceResultFromJson reads
/// it, the pooled ranking (its ratio_bound and ratio_max stay 0), the options, the counts and
/// margins (null reads as infinity). `dominant` is dominant_counts' first, as the batch sets it,
/// and dominant_counts is ordered as the batch orders it (count descending, ties by name), so
/// ToJson gives the text back. The written "dominant" (the pooled ranking's first) and
/// summary.recordings (the number of recordings) are checked. Throws InputError
/// "SOURCE:LINE:COL: NAME: expected ..., found ...".
DominanceSummary DominanceSummaryFromJson(std::string_view text, const std::string& source_name);

}  // namespace sysid

#endif  // SYSID_DOMINANCE_HPP_
