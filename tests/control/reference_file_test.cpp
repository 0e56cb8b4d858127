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
