// The checks every folder of plots passes (its plots.json, PlotIndexJson): the rules of
// docs/architecture.md ("Plots") that a test can read without looking at the images.
#ifndef SYSID_TESTS_SUPPORT_PLOT_INDEX_CHECK_HPP_
#define SYSID_TESTS_SUPPORT_PLOT_INDEX_CHECK_HPP_

#include <string>

namespace sysid::test {

/// Reads DIR/plots.json and checks, with Catch, for every plot: a title; an x and a y label each
/// ending in a unit in brackets ("t [s]"); at least one series, each labelled, with points and a
/// "#rrggbb" colour; the series labelled "measured" black and drawn last; one colour per label
/// across all the folder's plots, and different labels in one plot in different colours; when
/// gnuplot is present, the image exists. Returns the number of plots.
int CheckPlotIndex(const std::string& dir);

}  // namespace sysid::test

#endif  // SYSID_TESTS_SUPPORT_PLOT_INDEX_CHECK_HPP_
