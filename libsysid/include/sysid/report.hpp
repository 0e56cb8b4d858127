// Reports (target sysid::report, above the numerical library): plots through gnuplot (Debian's
// gnuplot-nox, run as a child process), markdown tables and the pipeline's written report.
// Plotting is optional: when gnuplot is missing the plot is skipped with a clear message and
// the report says so; numbers and CSV traces never depend on it.
#ifndef SYSID_REPORT_HPP_
#define SYSID_REPORT_HPP_

#include <Eigen/Core>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "sysid/pipeline.hpp"
#include "sysid/validate.hpp"

namespace sysid {

struct PlotSeries {
  std::string label;
  Eigen::VectorXd x;
  Eigen::VectorXd y;
  std::string style = "lines";  ///< gnuplot style: "lines", "points", "linespoints"
};

struct PlotSpec {
  std::string title;
  std::string x_label;   ///< with unit, e.g. "t [s]"
  std::string y_label;   ///< with unit, e.g. "u [V]"
  std::vector<PlotSeries> series;
  bool log_y = false;
  int width_px = 900;
  int height_px = 500;
  /// [y unit] a fixed y range when both are finite and y_min < y_max (points outside are cut at
  /// the frame); otherwise gnuplot's autoscale.
  double y_min = std::numeric_limits<double>::quiet_NaN();
  double y_max = std::numeric_limits<double>::quiet_NaN();
};

struct PlotOutcome {
  bool written = false;
  std::string message;  ///< why not, when not written
};

/// True when a gnuplot executable is on PATH (checked once).
bool GnuplotAvailable();

/// Renders `spec` to `path` (.png or .svg by extension) with gnuplot, atomically. Returns
/// written = false and the reason when gnuplot is missing or fails; never throws for that.
PlotOutcome WritePlot(const std::string& path, const PlotSpec& spec);

/// The plots of a tracking run per feedforward scheme, by file name: "tracking_error.png"
/// (e [mm] against t [s]) and "control_signal.png" (u [V]), one series per scheme
/// (`sysid track -o`).
std::vector<std::pair<std::string, PlotSpec>> TrackingPlots(const std::vector<SchemeTracking>& runs);

/// The plots of a validation, by file name, per output y: "STEM_y.png" (the simulated and the
/// measured y against t, measured drawn last, on top; m and m/s shown as mm and mm/s) and
/// "STEM_y_residual_tests.png" (r_e and r_eu against the lag with the ±z/sqrt(N) band).
std::vector<std::pair<std::string, PlotSpec>> ValidationPlots(const Validation& validation,
                                                              const std::string& stem);

/// Writes into `out_dir`: report.md, model.json, nn.json (and nn_typical.json), tables as CSV,
/// traces and PNG plots. Returns notes about skipped plots (gnuplot missing).
std::vector<std::string> WritePipelineReport(const PipelineResult& result,
                                             const std::string& out_dir);

/// The report of a stack data set (result.inputs.IsStack(); WritePipelineReport calls it):
/// report.md (the split, the dominance of x, v, a, the hysteresis models' table, forward and
/// inverse plots), models.csv, summary.json (StackSummaryJson) and model_<row>_<kind>.json.
std::vector<std::string> WriteStackReport(const PipelineResult& result, const std::string& out_dir);

/// A GitHub-flavoured markdown table.
std::string MarkdownTable(const std::vector<std::string>& header,
                          const std::vector<std::vector<std::string>>& rows);

}  // namespace sysid

#endif  // SYSID_REPORT_HPP_
