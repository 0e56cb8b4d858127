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

TEST_CASE("a plot's fixed y range replaces the autoscale, and only a valid one", "[report]") {
  if (!sysid::GnuplotAvailable()) return;
  sysid::test::TempDir dir;
  sysid::PlotSpec spec;
  spec.title = "sine";
  const Eigen::VectorXd t = Eigen::VectorXd::LinSpaced(50, 0, 1);
  spec.series.push_back({"sin", t, t.array().sin().matrix(), "lines"});
  REQUIRE(sysid::WritePlot(dir / "auto.png", spec).written);
  spec.y_min = -10;
  spec.y_max = 10;
  REQUIRE(sysid::WritePlot(dir / "fixed.png", spec).written);
  spec.y_min = 10;  // backwards: ignored
  spec.y_max = -10;
  REQUIRE(sysid::WritePlot(dir / "backwards.png", spec).written);
  const std::string autoscaled = sysid::test::ReadText(dir / "auto.png");
  CHECK(sysid::test::ReadText(dir / "fixed.png") != autoscaled);
  CHECK(sysid::test::ReadText(dir / "backwards.png") == autoscaled);
}

TEST_CASE("tracking plots: error in mm and control signal, one series per scheme", "[report]") {
  sysid::SchemeTracking none, nn;
  nn.scheme = sysid::FeedforwardScheme::kNetwork;
  for (auto* run : {&none, &nn}) {
    run->result.t_s = Eigen::Vector2d(0, 0.001);
    run->result.e_m = Eigen::Vector2d(1e-3, -2e-3);
    run->result.u_v = Eigen::Vector2d(0.5, 1.5);
  }
  const auto plots = sysid::TrackingPlots({none, nn});
  REQUIRE(plots.size() == 2);
  CHECK(plots[0].first == "tracking_error.png");
  CHECK(plots[0].second.y_label == "e [mm]");
  REQUIRE(plots[0].second.series.size() == 2);
  CHECK(plots[0].second.series[1].label == "nn");
  CHECK(plots[0].second.series[1].y[1] == Approx(-2.0));  // mm
  CHECK(plots[1].first == "control_signal.png");
  CHECK(plots[1].second.series[0].label == "none");
  CHECK(plots[1].second.series[0].y[1] == 1.5);
}
