// A position reference read from a CSV: x_ref (or x) as written, v and a by central
// differences, exact for a quadratic x = c t^2 (v = 2 c t, a = 2 c) at interior samples.
#include <fmt/format.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "support/test_support.hpp"
#include "sysid/control.hpp"
#include "sysid/error.hpp"
#include "sysid/model.hpp"

TEST_CASE("a reference CSV gives x_ref, and v, a of a quadratic exactly", "[control]") {
  sysid::test::TempDir dir;
  const double c = 0.02;  // [m/s^2]
  for (const char* column : {"x_ref", "x"}) {
    std::string text = fmt::format("t,{}\n", column);
    for (int k = 0; k <= 100; ++k) {
      const double t = 1e-3 * k;
      text += fmt::format("{:.17g},{:.17g}\n", t, c * t * t);
    }
    const std::string path = dir / (std::string(column) + ".csv");
    sysid::test::WriteText(path, text);
    const sysid::PositionReference ref = sysid::ReadPositionReference(path);
    INFO("column " << column);
    REQUIRE(ref.x_m.size() == 101);
    CHECK(ref.description == path);
    for (Eigen::Index k = 1; k < 100; ++k) {
      const double t = 1e-3 * static_cast<double>(k);
      CHECK(ref.x_m[k] == Approx(c * t * t).margin(1e-15));
      CHECK(ref.v_mps[k] == Approx(2 * c * t).margin(1e-12));
    }
    for (Eigen::Index k = 2; k < 99; ++k) CHECK(ref.a_mps2[k] == Approx(2 * c).epsilon(1e-6));
  }
  const std::string bad = dir / "no_position.csv";
  sysid::test::WriteText(bad, "t,u\n0,1\n0.001,1\n");
  CHECK_THROWS_AS(sysid::ReadPositionReference(bad), sysid::InputError);
}

TEST_CASE("a reference file must fit the plant: its control rate, uniform steps, its travel",
          "[control]") {
  sysid::test::TempDir dir;
  auto write = [&](const std::string& name, double dt, double x_last, int gap_at = -1) {
    std::string text = "t,x_ref\n";
    double t = 0;
    for (int k = 0; k <= 20; ++k) {
      text += fmt::format("{:.17g},{:.17g}\n", t, k == 20 ? x_last : 1e-4 * k);
      t += k == gap_at ? 50 * dt : dt;
    }
    sysid::test::WriteText(dir / name, text);
    return sysid::ReadPositionReference(dir / name);
  };
  // At 1 kHz, inside [-0.05, 0.05] m: accepted.
  CHECK_NOTHROW(sysid::CheckReferenceForPlant(write("ok.csv", 1e-3, 0.01), 1000, -0.05, 0.05));
  // The same file for a 10 kHz loop: the rate named, with the cure.
  CHECK_THROWS_WITH(sysid::CheckReferenceForPlant(write("ok.csv", 1e-3, 0.01), 10000, -0.05, 0.05),
                    Catch::Contains("ok.csv: reference sample 2") &&
                        Catch::Contains("give the reference at 10000 Hz"));
  // A gap of 50 periods after sample 6.
  CHECK_THROWS_WITH(
      sysid::CheckReferenceForPlant(write("gap.csv", 1e-3, 0.01, 5), 1000, -0.05, 0.05),
      Catch::Contains("gap.csv: reference sample 7"));
  // Past the travel (was tracked, with a 1 m error and exit 0).
  CHECK_THROWS_WITH(sysid::CheckReferenceForPlant(write("far.csv", 1e-3, 1.0), 1000, -0.05, 0.05),
                    Catch::Contains("far.csv: reference sample 21") &&
                        Catch::Contains("x_ref = 1 m is outside the plant's travel"));
}

// A reference at a rate that divides the loop's: x_ref, v_ref, a_ref linear between its samples.
// References: a line is reproduced exactly (x = b t, v = b, a = 0 at every new sample), a
// parabola within linear interpolation's bound c dt^2 / 4 (|x''| dt^2 / 8, x'' = 2c), and the
// new grid passes CheckReferenceForPlant at the loop's rate.
TEST_CASE("a reference at 1 kHz on a 10 kHz loop is interpolated linearly", "[control]") {
  const double b = 0.003, c = 0.02, dt = 1e-3;  // [m/s], [m/s^2], [s]
  Eigen::VectorXd t(201), line(201), parabola(201);
  for (Eigen::Index k = 0; k < t.size(); ++k) {
    t[k] = 0.5 + dt * static_cast<double>(k);
    line[k] = b * t[k];
    parabola[k] = c * t[k] * t[k];
  }
  const sysid::PositionReference fine_line =
      sysid::ReferenceAtControlRate(sysid::ReferenceFromPositions(t, line), 10000);
  REQUIRE(fine_line.t_s.size() == 2001);
  CHECK(fine_line.t_s[0] == t[0]);
  CHECK(fine_line.t_s[2000] == Approx(t[200]).epsilon(1e-15));
  CHECK_NOTHROW(sysid::CheckReferenceForPlant(fine_line, 10000, -1, 1));
  for (Eigen::Index i = 0; i < fine_line.t_s.size(); ++i) {
    const double ti = 0.5 + 1e-4 * static_cast<double>(i);
    CHECK(fine_line.t_s[i] == Approx(ti).epsilon(1e-14));
    CHECK(fine_line.x_m[i] == Approx(b * ti).epsilon(1e-13));
    CHECK(fine_line.v_mps[i] == Approx(b).epsilon(1e-9));
    CHECK(fine_line.a_mps2[i] == Approx(0).margin(1e-6));
  }
  const sysid::PositionReference coarse = sysid::ReferenceFromPositions(t, parabola);
  const sysid::PositionReference fine = sysid::ReferenceAtControlRate(coarse, 10000);
  double worst = 0;
  for (Eigen::Index i = 0; i < fine.t_s.size(); ++i) {
    const double ti = fine.t_s[i];
    worst = std::max(worst, std::abs(fine.x_m[i] - c * ti * ti));
    if (i % 10 == 0) CHECK(fine.x_m[i] == coarse.x_m[i / 10]);  // the samples themselves stay
  }
  CHECK(worst <= c * dt * dt / 4 * (1 + 1e-9));
  CHECK(worst > c * dt * dt / 4 * 0.9);  // the bound is reached mid-interval: linear, not a hold
  // Interior a is the parabola's 2c, interpolated between equal values.
  for (Eigen::Index i = 30; i < fine.t_s.size() - 30; ++i)
    CHECK(fine.a_mps2[i] == Approx(2 * c).epsilon(1e-6));
  // At the loop's rate, or at a rate that does not divide it: returned as it is.
  CHECK(sysid::ReferenceAtControlRate(coarse, 1000).t_s.size() == 201);
  const sysid::PositionReference third = sysid::ReferenceAtControlRate(coarse, 2500);
  CHECK(third.t_s.size() == 201);
  CHECK_THROWS_WITH(sysid::CheckReferenceForPlant(third, 2500, -1, 1),
                    Catch::Contains("at a rate that divides it"));
}

TEST_CASE("track --reference at 1 kHz runs on the 10 kHz virtual stage", "[control][cli]") {
  sysid::test::TempDir dir;
  std::string text = "t,x_ref\n";
  for (int k = 0; k <= 2000; ++k) {
    const double t = 1e-3 * k;
    text += fmt::format("{:.17g},{:.17g}\n", t, 0.002 * (1 - std::cos(3.14159265358979 * t)));
  }
  sysid::test::WriteText(dir / "ref_1khz.csv", text);
  const sysid::test::CliResult r =
      sysid::test::RunCli({"track", "--reference", dir / "ref_1khz.csv", "--json"});
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(r.out, Catch::Contains("rms_error"));
}

// The model plant takes the same reference path as the stage (ReferenceAtControlRate). The
// reference: the same positions resampled by hand to the 10 kHz loop (linear interpolation
// written here), whose run with PI alone (x_ref is all it reads) must be the same run.
TEST_CASE(
    "track --reference at 1 kHz runs on a model plant at 10 kHz, as the reference "
    "resampled by hand",
    "[control][cli]") {
  sysid::test::TempDir dir;
  sysid::WriteModel(dir / "model.json", sysid::FrictionModel::Paper());
  auto x_of = [](double t) { return 0.002 * (1 - std::cos(3.14159265358979 * t)); };
  std::string coarse = "t,x_ref\n", fine = "t,x_ref\n";
  for (int k = 0; k <= 1500; ++k)
    coarse += fmt::format("{:.17g},{:.17g}\n", 1e-3 * k, x_of(1e-3 * k));
  for (int i = 0; i <= 15000; ++i) {
    const int k = i / 10;  // the coarse interval holding t = i / 10 kHz
    const double w = (i % 10) / 10.0;
    const double x = i == 15000 ? x_of(1.5) : (1 - w) * x_of(1e-3 * k) + w * x_of(1e-3 * (k + 1));
    fine += fmt::format("{:.17g},{:.17g}\n", 1e-4 * i, x);
  }
  sysid::test::WriteText(dir / "ref_1khz.csv", coarse);
  sysid::test::WriteText(dir / "ref_10khz.csv", fine);
  auto run = [&](const std::string& ref) {
    const sysid::test::CliResult r =
        sysid::test::RunCli({"track", "--plant", dir / "model.json", "--kp", "1500", "--ki",
                             "25000", "--ff", "none,analytic", "--reference", ref, "--json"});
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    return nlohmann::json::parse(r.out)["schemes"];
  };
  const auto by_library = run(dir / "ref_1khz.csv"), by_hand = run(dir / "ref_10khz.csv");
  REQUIRE(by_library.size() == 2);
  for (const char* metric : {"max_error_m", "rms_error_m", "rms_u_v"}) {
    INFO(metric);
    CHECK(by_library[0][metric].get<double>() ==
          Approx(by_hand[0][metric].get<double>()).epsilon(1e-9));
  }
  // The analytic feedforward reads v_ref and a_ref too: interpolated from the 1 kHz samples'
  // differences, or differenced from the hand-made 10 kHz samples; near, not equal.
  CHECK(by_library[1]["rms_u_v"].get<double>() ==
        Approx(by_hand[1]["rms_u_v"].get<double>()).epsilon(0.05));
  CHECK(by_library[1]["rms_error_m"].get<double>() < by_library[0]["rms_error_m"].get<double>());
}
