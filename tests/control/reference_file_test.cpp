// A position reference read from a CSV: x_ref (or x) as written, v and a by central
// differences, exact for a quadratic x = c t^2 (v = 2 c t, a = 2 c) at interior samples.
#include <catch2/catch.hpp>
#include <fmt/format.h>

#include "support/test_support.hpp"
#include "sysid/control.hpp"
#include "sysid/error.hpp"

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
