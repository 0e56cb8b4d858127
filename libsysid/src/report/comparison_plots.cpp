// The plots of `sysid compare -o` per recording: the inverse models' u over the measured u, their
// errors, a zoomed window where the models differ, and the u-x loop of the hysteresis models.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "sysid/compare.hpp"
#include "sysid/report.hpp"

namespace sysid {
namespace {

struct ModelTrace {
  std::string label;
  const Eigen::VectorXd* u_v;
};

std::vector<ModelTrace> Models(const InverseComparison& c) {
  std::vector<ModelTrace> out;
  if (c.has_analytic) out.push_back({"analytic inverse", &c.u_analytic_v});
  if (c.has_nn) out.push_back({"NN inverse", &c.u_nn_v});
  for (const auto& h : c.hysteresis) out.push_back({h.label + " inverse", &h.u_v});
  return out;
}

}  // namespace

std::vector<std::pair<std::string, PlotSpec>> ComparisonPlots(const InverseComparison& c,
                                                              const std::string& stem,
                                                              PlotColours& colours) {
  const std::vector<ModelTrace> models = Models(c);
  const Eigen::Index n = c.t_s.size();
  std::vector<std::pair<std::string, PlotSpec>> out;
  auto add = [&](std::string file, PlotSpec spec) {
    DrawMeasuredLast(spec);
    colours.Apply(spec);
    out.emplace_back(std::move(file), std::move(spec));
  };

  PlotSpec all{"inverse models on " + stem, "t [s]", "u [V]", {}, false, 1100, 500};
  for (const auto& m : models) all.series.push_back({m.label, c.t_s, *m.u_v});
  all.series.push_back({"measured", c.t_s, c.u_measured_v});
  add(stem + ".png", all);

  PlotSpec err{"inverse models on " + stem + ": error, model minus measured", "t [s]",
               "u_model - u [V]", {}, false, 1100, 450};
  Eigen::Index worst = 0;
  double worst_error = -1;
  std::string worst_label;
  for (const auto& m : models) {
    const Eigen::VectorXd e = *m.u_v - c.u_measured_v;
    Eigen::Index k = 0;
    if (n > 0 && e.cwiseAbs().maxCoeff(&k) > worst_error) {
      worst_error = std::abs(e[k]);
      worst = k;
      worst_label = m.label;
    }
    err.series.push_back({m.label, c.t_s, e});
  }
  add(stem + "_error.png", err);

  if (n > kCompareZoomAbove) {
    const Eigen::Index w = n / 10;
    const Eigen::Index start = std::clamp<Eigen::Index>(worst - w / 2, 0, n - w);
    PlotSpec zoom{fmt::format("inverse models on {}: t = {:.4g} to {:.4g} s, around the largest "
                              "error ({})",
                              stem, c.t_s[start], c.t_s[start + w - 1], worst_label),
                  "t [s]", "u [V]", {}, false, 1100, 500};
    const Eigen::VectorXd t = c.t_s.segment(start, w);
    for (const auto& m : models) zoom.series.push_back({m.label, t, m.u_v->segment(start, w)});
    zoom.series.push_back({"measured", t, c.u_measured_v.segment(start, w)});
    add(stem + "_zoom.png", zoom);
  }

  if (!c.hysteresis.empty() && c.x_m.size() == n) {
    PlotSpec loop{"u-x loop on " + stem + ": hysteresis models inverted on the measured x",
                  "x [um]", "u [V]", {}, false, 800, 650};
    const Eigen::VectorXd x_um = 1e6 * c.x_m;
    for (const auto& h : c.hysteresis) loop.series.push_back({h.label + " inverse", x_um, h.u_v});
    loop.series.push_back({"measured", x_um, c.u_measured_v});
    add(stem + "_loop.png", loop);
  }
  return out;
}

}  // namespace sysid
