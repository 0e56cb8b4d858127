// Central differences against polynomials (exact), sines (Taylor bounds) and a quantised sine
// (Taylor bound + q/(2h) noise bound).
#include <catch2/catch.hpp>

#include "signal_test_util.hpp"
#include "sysid/error.hpp"
#include "sysid/signal.hpp"

using namespace sysid;
using namespace sysid::test;

TEST_CASE("central difference is exact on quadratics, ends included", "[signal][central]") {
  const double dt = 1e-3;
  const auto x = Sample([](double t) { return 0.3 - 2.0 * t + 7.5 * t * t; }, 50, dt);
  const Eigen::VectorXd v = CentralDifference(x, dt);
  const Eigen::VectorXd a = CentralDifference(v, dt);
  const auto v_ref = Sample([](double t) { return -2.0 + 15.0 * t; }, 50, dt);
  // Both stencils are exact on degree 2; what remains is rounding of x (~1e-16) over 2h.
  CHECK(MaxError(v, v_ref, 0, 50) < 1e-11);
  // a = D(D x): D is exact on the linear v, so a is the constant 15 up to rounding / h^2.
  CHECK((a.array() - 15.0).abs().maxCoeff() < 1e-7);
}

TEST_CASE("central difference of a sine meets the Taylor bounds", "[signal][central]") {
  const double amp = 0.01, w = 2 * kPi * 3.0, dt = 1e-3;
  const Eigen::Index n = 2000;
  const auto x = Sample([&](double t) { return amp * std::sin(w * t + 0.4); }, n, dt);
  const auto v_ref = Sample([&](double t) { return amp * w * std::cos(w * t + 0.4); }, n, dt);
  const auto a_ref = Sample([&](double t) { return -amp * w * w * std::sin(w * t + 0.4); }, n, dt);
  const Eigen::VectorXd v = CentralDifference(x, dt);
  const Eigen::VectorXd a = CentralDifference(v, dt);
  const double m3 = amp * std::pow(w, 3), m4 = amp * std::pow(w, 4);
  // Interior: (y[k+1]-y[k-1])/2h - y' = h^2/12 (y'''(xi1) + y'''(xi2)).
  const double v_bound = dt * dt / 6 * m3;
  const double v_err = MaxError(v, v_ref, 1, n - 1);
  CHECK(v_err <= v_bound);
  CHECK(v_err > 0.5 * v_bound);  // the bound is tight (leading term h^2/6 y''')
  // Ends: the one-sided stencil (-3, 4, -1)/2h, exact to degree 2.
  const double v_end_bound = StencilBound({-1.5, 2.0, -0.5}, {0, 1, 2}, 2, 1, dt, m3);
  CHECK(std::abs(v[0] - v_ref[0]) <= v_end_bound);
  CHECK(std::abs(v[n - 1] - v_ref[n - 1]) <= v_end_bound);
  // Interior of D(D x): (x[k+2] - 2x[k] + x[k-2]) / (4h^2), a second difference of step 2h.
  const double a_bound = StencilBound({0.25, -0.5, 0.25}, {-2, 0, 2}, 3, 2, dt, m4);
  CHECK(MaxError(a, a_ref, 2, n - 2) <= a_bound);
  // a[0] = (5 x0 - 11 x1 + 7 x2 - x3) / (4h^2): exact to degree 2 only, so O(h) at the ends.
  const double a_end_bound = StencilBound({1.25, -2.75, 1.75, -0.25}, {0, 1, 2, 3}, 2, 2, dt, m3);
  CHECK(std::abs(a[0] - a_ref[0]) <= a_end_bound);
  CHECK(std::abs(a[n - 1] - a_ref[n - 1]) <= a_end_bound);
}

TEST_CASE("central difference of a quantised sine: truncation plus q/(2h)", "[signal][central]") {
  // An encoder of 1 um resolution at 1 kHz on a 5 mm, 2 Hz motion.
  const double amp = 5e-3, w = 2 * kPi * 2.0, dt = 1e-3, q = 1e-6;
  const Eigen::Index n = 3000;
  const auto x = Quantize(Sample([&](double t) { return amp * std::sin(w * t); }, n, dt), q);
  const auto v_ref = Sample([&](double t) { return amp * w * std::cos(w * t); }, n, dt);
  const auto a_ref = Sample([&](double t) { return -amp * w * w * std::sin(w * t); }, n, dt);
  const Eigen::VectorXd v = CentralDifference(x, dt);
  const Eigen::VectorXd a = CentralDifference(v, dt);
  // |e_k| <= q/2, so the difference adds at most (q/2 + q/2)/(2h) = q/(2h).
  const double v_bound = dt * dt / 6 * amp * std::pow(w, 3) + q / (2 * dt);
  const double v_err = MaxError(v, v_ref, 1, n - 1);
  CHECK(v_err <= v_bound);
  CHECK(v_err > 0.5 * v_bound);  // the quantisation term dominates and is nearly reached
  // (e[k+2] - 2e[k] + e[k-2]) / 4h^2 <= (q/2)(1 + 2 + 1)/(4h^2) = q/(2h^2).
  const double a_bound =
      StencilBound({0.25, -0.5, 0.25}, {-2, 0, 2}, 3, 2, dt, amp * std::pow(w, 4)) +
      q / (2 * dt * dt);
  CHECK(MaxError(a, a_ref, 2, n - 2) <= a_bound);
}

TEST_CASE("central difference rejects bad arguments", "[signal][central]") {
  const Eigen::VectorXd y = Eigen::VectorXd::LinSpaced(5, 0, 1);
  CHECK_THROWS_WITH(CentralDifference(y, 0.0),
                    Catch::Contains("dt_s = 0 s. Violated constraint: dt_s > 0"));
  CHECK_THROWS_AS(CentralDifference(y.head(2), 1e-3), InputError);
  CHECK_THROWS_WITH(CentralDifference(y.head(2), 1e-3), Catch::Contains("has 2 samples"));
  Eigen::VectorXd bad = y;
  bad[3] = std::nan("");
  CHECK_THROWS_WITH(CentralDifference(bad, 1e-3), Catch::Contains("sample 3 (0-based)"));
}
