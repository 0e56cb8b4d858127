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
  // Each scheme keeps its colour from one plot to the other, and the two differ.
  for (int i = 0; i < 2; ++i) {
    CHECK(plots[0].second.series[i].colour.size() == 7);
    CHECK(plots[0].second.series[i].colour == plots[1].second.series[i].colour);
  }
  CHECK(plots[0].second.series[0].colour != plots[0].second.series[1].colour);
}

TEST_CASE("gnuplot's script keeps x'' and sets each series' colour", "[report]") {
  sysid::PlotSpec spec;
  spec.title = "terms `rm -rf` $HOME @macro \"quoted\"";
  spec.x_label = "t [s]";
  spec.y_label = "term [m/s^2]";
  const Eigen::VectorXd t = Eigen::VectorXd::LinSpaced(3, 0, 1);
  spec.series.push_back({"acceleration term x'' = a", t, t, "lines", "#1f77b4"});
  spec.series.push_back({"no colour", t, t, "lines", "red; system"});
  const std::string gp = sysid::GnuplotScript(spec, "/tmp/i.png", {"/tmp/s0.dat", "/tmp/s1.dat"});
  CHECK_THAT(gp, Catch::Contains("with lines lc rgb \"#1f77b4\" title \"acceleration term x'' = a\""));
  CHECK_THAT(gp, Catch::Contains("\"/tmp/s1.dat\" using 1:2 with lines title \"no colour\""));
  CHECK_THAT(gp, Catch::Contains("set title \"terms rm -rf HOME macro quoted\" noenhanced"));
  CHECK_THAT(gp, Catch::Contains("set ylabel \"term [m/s^2]\" noenhanced"));
  CHECK_THAT(gp, Catch::Contains("set key below"));
  if (!sysid::GnuplotAvailable()) return;
  sysid::test::TempDir dir;
  CHECK(sysid::WritePlot(dir / "quote.png", spec).written);  // gnuplot parses it
}

TEST_CASE("a report's colours follow the label, measured is black and drawn last", "[report]") {
  sysid::PlotColours colours;
  const Eigen::VectorXd t = Eigen::VectorXd::LinSpaced(3, 0, 1);
  sysid::PlotSpec a, b;
  a.series = {{"measured", t, t}, {"model 1", t, t}, {"model 2", t, t}};
  b.series = {{"model 2", t, t}, {"measured", t, t}};  // model 1 missing: model 2 keeps its colour
  for (auto* s : {&a, &b}) {
    sysid::DrawMeasuredLast(*s);
    colours.Apply(*s);
  }
  CHECK(a.series[0].label == "model 1");
  CHECK(a.series[2].label == "measured");
  CHECK(a.series[2].colour == "#000000");
  CHECK(b.series[0].label == "model 2");
  CHECK(b.series[1].label == "measured");
  CHECK(b.series[0].colour == a.series[1].colour);
  CHECK(a.series[0].colour != a.series[1].colour);
  CHECK(colours.For("model 1") == a.series[0].colour);
}

TEST_CASE("compare's plots: models under measured, their errors, a zoom and the u-x loop",
          "[report][compare]") {
  const Eigen::Index n = 2000;
  sysid::InverseComparison c;
  c.source = "rec.csv";
  c.t_s = Eigen::VectorXd::LinSpaced(n, 0, 0.001 * static_cast<double>(n - 1));
  c.u_measured_v = (2 * M_PI * c.t_s).array().sin().matrix();
  c.x_m = 1e-6 * c.u_measured_v;
  c.has_analytic = true;
  c.u_analytic_v = c.u_measured_v;
  c.u_analytic_v[1500] += 0.5;  // the largest error: the zoom is centred there
  sysid::HysteresisInverseResult h;
  h.label = "pi:h";
  h.kind = "pi";
  h.u_v = c.u_measured_v.array() + 0.1;
  c.hysteresis.push_back(h);
  sysid::PlotColours colours;
  const auto plots = sysid::ComparisonPlots(c, "rec", colours);
  REQUIRE(plots.size() == 4);
  CHECK(plots[0].first == "rec.png");
  CHECK(plots[1].first == "rec_error.png");
  CHECK(plots[2].first == "rec_zoom.png");
  CHECK(plots[3].first == "rec_loop.png");
  const sysid::PlotSpec& all = plots[0].second;
  REQUIRE(all.series.size() == 3);
  CHECK(all.series[2].label == "measured");
  const sysid::PlotSpec& err = plots[1].second;
  REQUIRE(err.series.size() == 2);  // no error trace for the measured one
  CHECK(err.y_label == "u_model - u [V]");
  CHECK(err.series[0].y[1500] == Approx(0.5));
  CHECK(err.series[1].y[7] == Approx(0.1));
  CHECK(err.series[0].colour == all.series[0].colour);
  CHECK(err.series[1].colour == all.series[1].colour);
  const sysid::PlotSpec& zoom = plots[2].second;
  REQUIRE(zoom.series.size() == 3);
  CHECK(zoom.series[0].x.size() == n / 10);
  CHECK(zoom.series[0].x[0] == c.t_s[1500 - n / 20]);
  CHECK_THAT(zoom.title, Catch::Contains("largest error (analytic inverse)"));
  const sysid::PlotSpec& loop = plots[3].second;
  CHECK(loop.x_label == "x [um]");
  REQUIRE(loop.series.size() == 2);  // the hysteresis model and the measured loop
  CHECK(loop.series[0].x == 1e6 * c.x_m);
  CHECK(loop.series[0].colour == all.series[1].colour);
  // A short recording without hysteresis models: the whole trace and the errors only.
  c.hysteresis.clear();
  CHECK(sysid::ComparisonPlots(c, "rec", colours).size() == 3);  // no loop
  sysid::InverseComparison short_c = c;
  short_c.t_s = c.t_s.head(100);
  short_c.u_measured_v = c.u_measured_v.head(100);
  short_c.u_analytic_v = c.u_analytic_v.head(100);
  CHECK(sysid::ComparisonPlots(short_c, "rec", colours).size() == 2);  // no zoom
}
