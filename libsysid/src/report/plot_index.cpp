// plots.json: what each plot of a report shows (labels, units, series, colours), readable
// without the images: tests check it, and a user restyling a figure finds its series there.
#include <algorithm>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "sysid/report.hpp"

namespace sysid {

std::string PlotIndexJson(const std::vector<std::pair<std::string, PlotSpec>>& plots) {
  nlohmann::ordered_json j = nlohmann::ordered_json::object();
  for (const auto& [file, spec] : plots) {
    nlohmann::ordered_json p;
    p["title"] = spec.title;
    p["x_label"] = spec.x_label;
    p["y_label"] = spec.y_label;
    p["log_y"] = spec.log_y;
    p["series"] = nlohmann::ordered_json::array();
    for (const PlotSeries& s : spec.series)
      p["series"].push_back({{"label", s.label},
                             {"colour", s.colour},
                             {"style", s.style},
                             {"points", std::min(s.x.size(), s.y.size())}});
    j[file] = std::move(p);
  }
  return j.dump(2) + "\n";
}

}  // namespace sysid
