#include <catch2/catch.hpp>

#include <filesystem>

#include "support/test_support.hpp"
#include "sysid/report.hpp"

TEST_CASE("markdown tables have a header rule and one line per row", "[report]") {
  const std::string t = sysid::MarkdownTable({"H", "MSE"}, {{"16", "0.12"}, {"24", "0.11"}});
  CHECK(t == "| H | MSE |\n|---|---|\n| 16 | 0.12 |\n| 24 | 0.11 |\n");
}

TEST_CASE("plots are written as PNG when gnuplot is present", "[report]") {
  sysid::test::TempDir dir;
  sysid::PlotSpec spec;
  spec.title = "sine";
  spec.x_label = "t [s]";
  spec.y_label = "u [V]";
  Eigen::VectorXd t = Eigen::VectorXd::LinSpaced(50, 0, 1);
  spec.series.push_back({"sin", t, t.array().sin().matrix(), "lines"});
  const auto out = sysid::WritePlot(dir / "p.png", spec);
  if (!sysid::GnuplotAvailable()) {
    CHECK_FALSE(out.written);
    CHECK_THAT(out.message, Catch::Contains("gnuplot not found"));
    return;
  }
  REQUIRE(out.written);
  const std::string png = sysid::test::ReadText(dir / "p.png");
  REQUIRE(png.size() > 8);
  CHECK(png.substr(1, 3) == "PNG");  // the PNG signature
  CHECK(std::distance(std::filesystem::directory_iterator(dir.path()),
                      std::filesystem::directory_iterator{}) == 1);  // no temp file left
}
