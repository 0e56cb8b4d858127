#include "support/plot_index_check.hpp"

#include <catch2/catch.hpp>

#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <string>

#include "support/test_support.hpp"
#include "sysid/report.hpp"

namespace sysid::test {

int CheckPlotIndex(const std::string& dir) {
  const auto index = nlohmann::json::parse(ReadText(dir + "/plots.json"));
  const std::regex unit(R"(.*\[[^\]]+\]$)"), colour("#[0-9a-f]{6}");
  std::map<std::string, std::string> colour_of;
  int plots = 0;
  for (const auto& [file, p] : index.items()) {
    INFO(dir << "/" << file);
    ++plots;
    CHECK_FALSE(p["title"].get<std::string>().empty());
    CHECK(std::regex_match(p["x_label"].get<std::string>(), unit));
    CHECK(std::regex_match(p["y_label"].get<std::string>(), unit));
    REQUIRE(p["series"].size() > 0);
    std::set<std::string> colours_here;
    for (std::size_t i = 0; i < p["series"].size(); ++i) {
      const auto& s = p["series"][i];
      const std::string label = s["label"], c = s["colour"];
      INFO("series " << label);
      CHECK_FALSE(label.empty());
      CHECK(s["points"].get<long>() > 0);
      CHECK(std::regex_match(c, colour));
      if (label == "measured") {
        CHECK(c == "#000000");
        CHECK(i + 1 == p["series"].size());
      }
      const auto [it, fresh] = colour_of.emplace(label, c);
      CHECK(it->second == c);  // one colour per label across the folder
      (void)fresh;
      CHECK(colours_here.insert(c).second);  // told apart within the plot
    }
    if (GnuplotAvailable()) CHECK(std::filesystem::exists(dir + "/" + file));
  }
  return plots;
}

}  // namespace sysid::test
