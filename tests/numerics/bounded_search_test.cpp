// MinimizeScalar (libsysid/src/numerics) against minima known in closed form.
#include "numerics/bounded_search.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

namespace sysid::internal {
namespace {

TEST_CASE("MinimizeScalar finds the minimum of cos on [2, 4] at pi", "[numerics]") {
  ScalarSearchOptions o;
  o.lo = 2;
  o.hi = 4;
  const auto r = MinimizeScalar([](double x) { return std::cos(x); }, o);
  // cos is quadratic at pi: an x_tolerance of 1e-7 leaves x within 1e-6 and f within 1e-12.
  CHECK(r.x == Approx(M_PI).margin(1e-6));
  CHECK(r.f == Approx(-1.0).margin(1e-12));
  CHECK(r.evaluations <= o.max_evaluations);
  CHECK(static_cast<int>(r.evaluated.size()) == r.evaluations);
}

TEST_CASE("MinimizeScalar prefers the global of two local minima", "[numerics]") {
  // f has local minima near x = -0.69 (f ~ -0.2) and x = 0.72 (f ~ -1.3); the coarse DIRECT-L
  // stage sees both, the refinement must end in the deeper one.
  const auto f = [](double x) { return x * x * x * x - x * x - 0.4 * x; };
  ScalarSearchOptions o;
  o.lo = -1.5;
  o.hi = 1.5;
  o.max_evaluations = 100;
  const auto r = MinimizeScalar(f, o);
  // The minimiser solves 4x^3 - 2x - 0.4 = 0; Newton from 0.75 gives the reference.
  double x = 0.75;
  for (int i = 0; i < 50; ++i) x -= (4 * x * x * x - 2 * x - 0.4) / (12 * x * x - 2);
  CHECK(r.x == Approx(x).margin(1e-5));  // x_tolerance 1e-7 on a flat (quadratic) minimum
}

TEST_CASE("MinimizeScalar steers away from non-finite values", "[numerics]") {
  // NaN left of 0.5 (a failed simulation): the minimum of (x - 0.7)^2 is still found.
  const auto f = [](double x) {
    return x < 0.5 ? std::numeric_limits<double>::quiet_NaN() : (x - 0.7) * (x - 0.7);
  };
  ScalarSearchOptions o;
  const auto r = MinimizeScalar(f, o);
  CHECK(r.x == Approx(0.7).margin(1e-6));  // quadratic minimum, x_tolerance 1e-7
  CHECK(std::isfinite(r.f));
}

}  // namespace
}  // namespace sysid::internal
