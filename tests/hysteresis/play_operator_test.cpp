#include <catch2/catch.hpp>
#include <cmath>

#include "sysid/error.hpp"
#include "sysid/hysteresis.hpp"

TEST_CASE("play operator follows a hand-worked sequence", "[hysteresis]") {
  // r = 1: the output stays put until the input is more than 1 away, then trails it by 1.
  Eigen::VectorXd u(8);
  u << 0, 0.5, 2, 3, 2.5, 1, -1, 0;
  Eigen::VectorXd expected(8);
  expected << 0, 0, 1, 2, 2, 2, 0, 0;
  CHECK(sysid::PlayOperator(u, 1.0, 0.0) == expected);  // exact: only max/min of sums
}

TEST_CASE("play operator starts from its initial state, clamped to the band", "[hysteresis]") {
  Eigen::VectorXd u(3);
  u << 0, 0, 4;
  // z0 = 5 is more than r = 1 above u = 0: the first output is u + r = 1, then 3 at u = 4.
  const Eigen::VectorXd z = sysid::PlayOperator(u, 1.0, 5.0);
  CHECK(z[0] == 1.0);
  CHECK(z[1] == 1.0);
  CHECK(z[2] == 3.0);
  // z0 inside the band is kept.
  CHECK(sysid::PlayOperator(u, 1.0, 0.3)[0] == 0.3);
  // r = 0 is the identity.
  CHECK(sysid::PlayOperator(u, 0.0, 7.0) == u);
}

TEST_CASE("play operator on samples equals the operator on the linear interpolation",
          "[hysteresis]") {
  // The claim 'exact for the input linear between samples': run the operator on a 1000x finer
  // linear interpolation (an independent, dense evaluation) and compare at the coarse samples.
  const int n = 200, fine = 1000;
  Eigen::VectorXd u(n);
  for (int k = 0; k < n; ++k) u[k] = std::sin(0.13 * k) * (1 + 0.5 * std::cos(0.031 * k));
  Eigen::VectorXd dense((n - 1) * fine + 1);
  for (int k = 0; k + 1 < n; ++k)
    for (int j = 0; j < fine; ++j)
      dense[k * fine + j] = u[k] + (u[k + 1] - u[k]) * j / static_cast<double>(fine);
  dense[(n - 1) * fine] = u[n - 1];
  for (double r : {0.05, 0.3, 0.8}) {
    const Eigen::VectorXd coarse = sysid::PlayOperator(u, r, 0.1);
    const Eigen::VectorXd reference = sysid::PlayOperator(dense, r, 0.1);
    for (int k = 0; k < n; ++k)
      CHECK(coarse[k] == Approx(reference[k * fine]).margin(1e-14));  // rounding of the dense grid
  }
}

TEST_CASE("play operator refuses a negative or non-finite threshold", "[hysteresis]") {
  const Eigen::VectorXd u = Eigen::VectorXd::Zero(3);
  CHECK_THROWS_WITH(sysid::PlayOperator(u, -0.1), Catch::Contains("r >= 0"));
  CHECK_THROWS_AS(sysid::PlayOperator(u, NAN), sysid::OptionsError);
  CHECK_THROWS_AS(sysid::PlayOperator(u, 1.0, INFINITY), sysid::OptionsError);
}
