// The colour map of a report's plots (PlotColours) and their drawing order: keyed by series label, so a model's colour
// does not depend on which other series a plot holds or on their order.
#include <algorithm>
#include <array>
#include <string>

#include "sysid/report.hpp"

namespace sysid {
namespace {

// Matplotlib's tab10, then ten of tab20b's that none of those resembles: a pipeline report holds
// about 20 labels, and two of them in one plot must not share (or nearly share) a colour.
constexpr std::array<const char*, 20> kPalette = {
    "#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2",
    "#7f7f7f", "#bcbd22", "#17becf", "#393b79", "#637939", "#e7ba52", "#843c39",
    "#7b4173", "#6b6ecf", "#b5cf6b", "#ad494a", "#a55194", "#8c6d31"};

}  // namespace

std::string PlotColours::For(const std::string& label) {
  if (label == "measured") return "#000000";
  auto it = std::find(labels_.begin(), labels_.end(), label);
  if (it == labels_.end()) it = labels_.insert(labels_.end(), label);
  return kPalette[static_cast<size_t>(it - labels_.begin()) % kPalette.size()];
}

void PlotColours::Apply(PlotSpec& spec) {
  for (PlotSeries& s : spec.series)
    if (s.colour.empty()) s.colour = For(s.label);
}

void DrawMeasuredLast(PlotSpec& spec) {
  std::stable_partition(spec.series.begin(), spec.series.end(),
                        [](const PlotSeries& s) { return s.label != "measured"; });
}

}  // namespace sysid
