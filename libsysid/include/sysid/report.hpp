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
  PlotSeries() = default;
  PlotSeries(std::string label_, Eigen::VectorXd x_, Eigen::VectorXd y_,
             std::string style_ = "lines", std::string colour_ = {})
      : label(std::move(label_)),
        x(std::move(x_)),
        y(std::move(y_)),
        style(std::move(style_)),
        colour(std::move(colour_)) {}

  std::string label;
  Eigen::VectorXd x;
  Eigen::VectorXd y;
  std::string style = "lines";  ///< gnuplot style: "lines", "points", "linespoints"
  std::string colour;           ///< "#rrggbb"; empty (or anything else): gnuplot's next colour
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

/// One colour per series label across the plots of a report, so a model keeps its colour from
/// plot to plot whichever series the others hold: "measured" is black, every other label takes
/// the next colour of a 20-colour palette on its first use (after 20, the palette repeats).
class PlotColours {
 public:
  /// The colour of `label` ("#rrggbb").
  std::string For(const std::string& label);
  /// Gives every series of `spec` without a colour the colour of its label.
  void Apply(PlotSpec& spec);

 private:
  std::vector<std::string> labels_;  ///< in order of first use
};

/// Moves the series labelled "measured" after the others, keeping their order: drawn last, the
/// measured trace lies on top of the models'.
void DrawMeasuredLast(PlotSpec& spec);

/// The gnuplot script WritePlot runs: `image` is the output file, data_files[i] holds series i
/// as "x y" rows. Text is sanitised (back quotes, '$', '@', '"', '\\' and control characters
/// dropped: gnuplot would substitute or end the string there), a series' colour is set when it
/// is "#rrggbb", the legend goes below the frame.
std::string GnuplotScript(const PlotSpec& spec, const std::string& image,
                          const std::vector<std::string>& data_files);

/// What each plot of a folder shows, as JSON ({"FILE.png": {"title", "x_label", "y_label",
/// "log_y", "series": [{"label", "colour", "style", "points"}]}}, in drawing order: the last
/// series is on top). The pipeline report and `sysid compare -o` write it as plots.json, whether
/// or not gnuplot drew the images.
std::string PlotIndexJson(const std::vector<std::pair<std::string, PlotSpec>>& plots);

/// True when a gnuplot executable is on PATH (checked once).
bool GnuplotAvailable();

/// Renders `spec` to `path` (.png or .svg by extension) with gnuplot, atomically. Returns
/// written = false and the reason when gnuplot is missing or fails; never throws for that.
PlotOutcome WritePlot(const std::string& path, const PlotSpec& spec);

/// The plots of a tracking run per feedforward scheme, by file name: "tracking_error.png"
/// (e [mm] against t [s]) and "control_signal.png" (u [V]), one series per scheme, each scheme
/// in one colour in both (`sysid track -o`, which writes their plots.json too).
std::vector<std::pair<std::string, PlotSpec>> TrackingPlots(const std::vector<SchemeTracking>& runs);

/// The plots of a validation, by file name, per output y: "STEM_y.png" (the simulated and the
/// measured y against t, measured drawn last, on top; m and m/s shown as mm and mm/s) and
/// "STEM_y_residual_tests.png" (r_e and r_eu against the lag with the ±z/sqrt(N) band).
std::vector<std::pair<std::string, PlotSpec>> ValidationPlots(const Validation& validation,
                                                              const std::string& stem);

/// The plots of one recording's inverse-model comparison (`sysid compare -o`), by file name,
/// every model in one colour (`colours`) across them and the measured trace black, drawn last:
/// "STEM.png" (u against t, the whole recording), "STEM_error.png" (each model's u - measured u
/// against t), "STEM_zoom.png" when the recording has more than kCompareZoomAbove samples (u over
/// the window of a tenth of the samples centred on the largest |error| of any model: over the
/// whole length the traces overlap) and, with hysteresis models and an x column, "STEM_loop.png"
/// (u against x [um]: each hysteresis model's inverse and the measured loop).
std::vector<std::pair<std::string, PlotSpec>> ComparisonPlots(const InverseComparison& comparison,
                                                              const std::string& stem,
                                                              PlotColours& colours);
constexpr Eigen::Index kCompareZoomAbove = 1000;  ///< [samples]

/// Writes into `out_dir`: report.md, model.json, nn.json (and nn_typical.json), tables as CSV,
/// traces and PNG plots. Returns notes about skipped plots (gnuplot missing).
std::vector<std::string> WritePipelineReport(const PipelineResult& result,
                                             const std::string& out_dir);

/// The report of a stack data set (result.inputs.IsStack(); WritePipelineReport calls it):
/// report.md (the split, the dominance of x, v, a, the hysteresis models' table, forward and
/// inverse plots), models.csv, summary.json (ToJson(StackSummaryOf)) and model_<row>_<kind>.json.
std::vector<std::string> WriteStackReport(const PipelineResult& result, const std::string& out_dir);

/// A GitHub-flavoured markdown table.
std::string MarkdownTable(const std::vector<std::string>& header,
                          const std::vector<std::vector<std::string>>& rows);

}  // namespace sysid

#endif  // SYSID_REPORT_HPP_
