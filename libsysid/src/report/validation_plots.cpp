// The plots of a validation (sysid validate -o, the pipeline report): per output, the measured
// trace over the free-run simulation, and both residual correlations with their 99 % band.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "sysid/report.hpp"
#include "sysid/validate.hpp"

namespace sysid {

std::vector<std::pair<std::string, PlotSpec>> ValidationPlots(const Validation& v,
                                                              const std::string& stem) {
  std::vector<std::pair<std::string, PlotSpec>> out;
  for (const OutputValidation& o : v.outputs) {
    // Millimetres read better than metres on an axis; the label says which.
    const std::string unit = o.unit == "m" ? "mm" : (o.unit == "m/s" ? "mm/s" : o.unit);
    const double scale = unit == o.unit ? 1.0 : 1e3;
    PlotSpec fit;
    fit.title = stem + ": " + o.output + " measured and simulated from u (fit " +
                (std::isfinite(o.scores.fit_percent)
                     ? std::to_string(static_cast<int>(std::lround(o.scores.fit_percent)))
                     : std::string("n/a")) +
                " %)";
    fit.x_label = "t [s]";
    fit.y_label = o.output + " [" + unit + "]";
    // Drawn in order: the measured trace last, so it lies on top of the simulation.
    fit.series.push_back({v.model_kind + " model", v.t_s, scale * o.simulated, "lines"});
    fit.series.push_back({"measured", v.t_s, scale * o.measured, "lines"});
    out.emplace_back(stem + "_" + o.output + ".png", std::move(fit));

    PlotSpec r;
    r.title = stem + ": residual of " + o.output + ", correlations and 99 % band";
    r.x_label = "lag [samples]";
    r.y_label = "normalised correlation [1]";
    auto lags = [](const CorrelationTest& t) {
      Eigen::VectorXd k(static_cast<Eigen::Index>(t.lags.size()));
      for (size_t i = 0; i < t.lags.size(); ++i) k[static_cast<Eigen::Index>(i)] = t.lags[i];
      return k;
    };
    const CorrelationTest& a = o.autocorrelation;
    const CorrelationTest& c = o.cross_correlation;
    r.series.push_back(
        {std::string("r_e ") + (a.pass ? "(pass)" : "(fail)"), lags(a), a.r, "linespoints"});
    r.series.push_back({std::string("r_eu with u ") + (c.pass ? "(pass)" : "(fail)"), lags(c), c.r,
                        "linespoints"});
    // Both edges of the band as one series: the NaN row breaks gnuplot's line between them.
    const double last = std::max(a.lags.back(), c.lags.back());
    const double nan = std::numeric_limits<double>::quiet_NaN();
    Eigen::VectorXd band_k(5), band_r(5);
    band_k << 0, last, nan, 0, last;
    band_r << a.bound, a.bound, nan, -a.bound, -a.bound;
    r.series.push_back({"99 % band", band_k, band_r, "lines"});
    out.emplace_back(stem + "_" + o.output + "_residual_tests.png", std::move(r));
  }
  return out;
}

}  // namespace sysid
