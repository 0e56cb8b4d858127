// DelaySignal: y(t - tau) on the signal's grid, against the closed form of a delayed ramp
// (linear interpolation is exact on a ramp), and its two documented edge rules.
#include <catch2/catch.hpp>
#include <cmath>

#include "sysid/error.hpp"
#include "sysid/signal.hpp"

TEST_CASE("delaying a ramp is exact for fractional delays", "[signal][delay]") {
  const double dt = 1e-3, tau = 2.5e-3;
  Eigen::VectorXd y(20);
  for (int k = 0; k < 20; ++k) y[k] = 3.0 * k * dt;
  const Eigen::VectorXd d = sysid::DelaySignal(y, dt, tau);
  for (int k = 3; k < 20; ++k) CHECK(d[k] == Approx(3.0 * (k * dt - tau)).margin(1e-14));
  CHECK(d[0] == y[0]);  // before the start: the first sample
  CHECK_THROWS_AS(sysid::DelaySignal(y, dt, -1.0), sysid::OptionsError);
  CHECK_THROWS_AS(sysid::DelaySignal(y, 0.0, tau), sysid::OptionsError);
}

TEST_CASE("before the record: the first sample held, or NaN", "[signal][delay]") {
  const double dt = 1e-3;
  Eigen::VectorXd y(8);
  for (int k = 0; k < 8; ++k) y[k] = 1.0 + 2.0 * k;
  SECTION("a fractional delay: t_k - tau < t_0 for k <= 2") {
    const Eigen::VectorXd hold = sysid::DelaySignal(y, dt, 2.5e-3);
    const Eigen::VectorXd nan = sysid::DelaySignal(y, dt, 2.5e-3, sysid::DelayStart::kNaN);
    for (int k = 0; k < 3; ++k) {
      CHECK(std::isnan(nan[k]));
      CHECK(hold[k] == y[0]);  // the first sample held
    }
    for (int k = 3; k < 8; ++k) {
      CHECK(nan[k] == hold[k]);
      CHECK(nan[k] == Approx(1.0 + 2.0 * (k - 2.5)).margin(1e-13));
    }
  }
  SECTION("a whole-sample delay: t_k - tau = t_0 exactly is inside the record") {
    const Eigen::VectorXd nan = sysid::DelaySignal(y, dt, 2e-3, sysid::DelayStart::kNaN);
    CHECK(std::isnan(nan[1]));
    CHECK(nan[2] == y[0]);
    CHECK(nan[7] == y[5]);
  }
  SECTION("no delay is the identity") {
    CHECK(sysid::DelaySignal(y, dt, 0.0, sysid::DelayStart::kNaN) == y);
  }
}
