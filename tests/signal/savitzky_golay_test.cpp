// Savitzky–Golay against: exactness on polynomials up to its order (ends included), the
// classical closed-form weights (Savitzky & Golay 1964; Madden 1978), Taylor + rounding bounds
// built from those weights, and Boost.Math's discrete_lanczos_derivative (the same estimator
// computed by a different algorithm: discrete Legendre polynomial recurrences).
#include <boost/math/differentiation/lanczos_smoothing.hpp>
#include <catch2/catch.hpp>
#include <vector>

#include "signal/filters.hpp"
#include "signal_test_util.hpp"
#include "sysid/error.hpp"
#include "sysid/signal.hpp"

using namespace sysid;
using namespace sysid::test;

namespace {

// Closed-form interior weights for a window 2m+1 and polynomial order 2 or 3, offsets s = -m..m.
double SmoothWeight(int m, int s) {
  return 3.0 * (3.0 * m * m + 3.0 * m - 1 - 5.0 * s * s) /
         ((2.0 * m - 1) * (2 * m + 1) * (2 * m + 3));
}
// Order 1-2: s / sum s^2. Order 3-4 adds the Gram polynomial P3 = s^3 - k s, k = (3m^2+3m-1)/5,
// with sum P3^2 = (m-1) m (m+1) (m+2) (2m-1) (2m+1) (2m+3) / 175 and P3'(0) = -k.
double SlopeWeight(int m, int s, int order) {
  const double linear = 3.0 * s / (m * (m + 1.0) * (2 * m + 1));
  if (order <= 2) return linear;
  const double k = (3.0 * m * m + 3.0 * m - 1) / 5;
  const double p3_norm =
      (m - 1.0) * m * (m + 1.0) * (m + 2.0) * (2.0 * m - 1) * (2.0 * m + 1) * (2.0 * m + 3) / 175;
  return linear - k * (std::pow(s, 3) - k * s) / p3_norm;
}
double CurvatureWeight(int m, int s) {
  return 30.0 * (3.0 * s * s - m * (m + 1.0)) /
         (m * (m + 1.0) * (2.0 * m - 1) * (2 * m + 1) * (2 * m + 3));
}

}  // namespace

TEST_CASE("Savitzky-Golay is exact on polynomials up to its order, ends included",
          "[signal][savgol]") {
  const double dt = 2e-3;
  const Eigen::Index n = 120;
  for (int order : {2, 3, 4, 5}) {
    for (int window : {order + 1 + order % 2, 15, 41}) {
      // p(t) = sum_j c_j (t - 0.1)^j with degree = order; derivatives in closed form.
      std::vector<double> c{0.01, -0.2, 3.0, -40.0, 500.0, -2000.0};
      c.resize(order + 1);
      auto poly = [&](double t, int d) {
        double sum = 0;
        for (int j = d; j <= order; ++j) {
          double falling = 1;
          for (int r = 0; r < d; ++r) falling *= j - r;
          sum += c[j] * falling * std::pow(t - 0.1, j - d);
        }
        return sum;
      };
      const auto y = Sample([&](double t) { return poly(t, 0); }, n, dt);
      for (int d = 0; d <= 2; ++d) {
        const Eigen::VectorXd out = SavitzkyGolay(y, dt, window, order, d);
        const auto ref = Sample([&](double t) { return poly(t, d); }, n, dt);
        const double scale = ref.cwiseAbs().maxCoeff() + 1;
        INFO("order " << order << " window " << window << " deriv " << d);
        // Exact in exact arithmetic; rounding of y (~1e-17 relative) amplified by the weights'
        // sum |w| / dt^d, at most ~1e6 for the narrowest window and d = 2.
        CHECK(MaxError(out, ref, 0, n) < 1e-8 * scale);
      }
    }
  }
}

TEST_CASE("Savitzky-Golay interior weights equal the classical closed forms", "[signal][savgol]") {
  for (int m : {2, 5, 10, 25}) {
    for (int order : {2, 3}) {
      const Eigen::MatrixXd w0 = internal::SavitzkyGolayWeights(2 * m + 1, order, 0);
      const Eigen::MatrixXd w1 = internal::SavitzkyGolayWeights(2 * m + 1, order, 1);
      const Eigen::MatrixXd w2 = internal::SavitzkyGolayWeights(2 * m + 1, order, 2);
      for (int s = -m; s <= m; ++s) {
        // QR solve versus rational closed form: rounding only.
        CHECK(w0(m, s + m) == Approx(SmoothWeight(m, s)).margin(1e-13));
        CHECK(w1(m, s + m) == Approx(SlopeWeight(m, s, order)).margin(1e-13));
        CHECK(w2(m, s + m) == Approx(CurvatureWeight(m, s)).margin(1e-13));
      }
    }
  }
}

TEST_CASE("Savitzky-Golay on a quantised sine meets Taylor plus rounding bounds",
          "[signal][savgol]") {
  const double amp = 5e-3, w = 2 * kPi * 2.0, dt = 1e-3, q = 1e-6;
  const Eigen::Index n = 3000;
  const int m = 15, window = 2 * m + 1, order = 3;
  const auto x_true = Sample([&](double t) { return amp * std::sin(w * t); }, n, dt);
  std::vector<double> s(window), c0(window), c1(window), c2(window);
  for (int i = 0; i < window; ++i) {
    s[i] = i - m;
    c0[i] = SmoothWeight(m, i - m);
    c1[i] = SlopeWeight(m, i - m, order);
    c2[i] = CurvatureWeight(m, i - m);
  }
  auto l1 = [](const std::vector<double>& c) {
    double sum = 0;
    for (double v : c) sum += std::abs(v);
    return sum;
  };
  auto mk = [&](int k) { return amp * std::pow(w, k); };  // max |x^(k)|
  for (bool quantised : {false, true}) {
    const Eigen::VectorXd x = quantised ? Quantize(x_true, q) : x_true;
    const double e = quantised ? q / 2 : 0.0;
    const Derivatives d =
        Differentiate(x, dt, {DerivativeMethod::kSavitzkyGolay, 50.0, 4, window, order});
    const auto v_ref = Sample([&](double t) { return amp * w * std::cos(w * t); }, n, dt);
    const auto a_ref = Sample([&](double t) { return -amp * w * w * std::sin(w * t); }, n, dt);
    INFO((quantised ? "quantised" : "clean"));
    // Smoothing: even weights, exact to degree 3, Taylor remainder of degree 4.
    CHECK(MaxError(d.x_m, x_true, m, n - m) <= StencilBound(c0, s, 3, 0, dt, mk(4)) + e * l1(c0));
    // Slope: odd weights also cancel the degree-4 term, so the remainder is of degree 5.
    const double v_bound = StencilBound(c1, s, 4, 1, dt, mk(5)) + e * l1(c1) / dt;
    CHECK(MaxError(d.v_mps, v_ref, m, n - m) <= v_bound);
    // Curvature: exact to degree 3 (degree-5 term cancels by symmetry, degree 4 does not).
    const double a_bound = StencilBound(c2, s, 3, 2, dt, mk(4)) + e * l1(c2) / (dt * dt);
    CHECK(MaxError(d.a_mps2, a_ref, m, n - m) <= a_bound);
    if (quantised) {
      // The 31-sample cubic fit cuts the central difference's worst-case noise q/(2h) ~4x.
      CHECK(e * l1(c1) / dt < 0.3 * q / (2 * dt));
    }
  }
}

TEST_CASE("Savitzky-Golay agrees with Boost.Math discrete_lanczos_derivative", "[signal][savgol]") {
  const double dt = 1e-3;
  const Eigen::Index n = 200;
  // A non-polynomial signal so that interior and boundary stencils are all exercised.
  const auto y = Sample(
      [](double t) { return std::sin(40 * t) + 0.3 * std::cos(95 * t + 1) + 2 * t * t; }, n, dt);
  const std::vector<double> yv(y.data(), y.data() + n);
  for (int m : {3, 10, 18}) {
    for (int order : {3, 4, 6}) {
      if (order > 2 * m) continue;
      boost::math::differentiation::discrete_lanczos_derivative<double, 1> d1(dt, m, order);
      boost::math::differentiation::discrete_lanczos_derivative<double, 2> d2(dt, m, order);
      const Eigen::VectorXd v = SavitzkyGolay(y, dt, 2 * m + 1, order, 1);
      const Eigen::VectorXd a = SavitzkyGolay(y, dt, 2 * m + 1, order, 2);
      const double v_scale = v.cwiseAbs().maxCoeff(), a_scale = a.cwiseAbs().maxCoeff();
      for (Eigen::Index k = 0; k < n; ++k) {
        INFO("m " << m << " order " << order << " k " << k);
        // Two least-squares algorithms (QR vs. Gram polynomials in long double): rounding,
        // amplified at the window's edge where the extrapolated fit is least conditioned.
        CHECK(v[k] == Approx(d1(yv, static_cast<size_t>(k))).margin(1e-9 * v_scale));
        CHECK(a[k] == Approx(d2(yv, static_cast<size_t>(k))).margin(1e-8 * a_scale));
      }
    }
  }
}

TEST_CASE("Savitzky-Golay options are checked", "[signal][savgol]") {
  const Eigen::VectorXd y = Eigen::VectorXd::Zero(30);
  CHECK_THROWS_WITH(SavitzkyGolay(y, 1e-3, 20, 3, 1),
                    Catch::Contains("window = 20. Violated constraint: window odd and >= 3"));
  CHECK_THROWS_WITH(SavitzkyGolay(y, 1e-3, 5, 5, 1),
                    Catch::Contains("order = 5. Violated constraint: 0 <= order < window = 5"));
  CHECK_THROWS_AS(SavitzkyGolay(y, 1e-3, 5, 1, 2), OptionsError);
  CHECK_THROWS_WITH(SavitzkyGolay(y, 1e-3, 31, 3, 1),
                    Catch::Contains("has 30 samples") && Catch::Contains("at least 31"));
  DerivativeOptions o;
  o.method = DerivativeMethod::kSavitzkyGolay;
  o.savgol_order = 1;
  CHECK_THROWS_WITH(o.Validate(1e-3), Catch::Contains("savgol_order = 1. Violated constraint: "
                                                      "2 <= savgol_order < savgol_window = 21"));
}

TEST_CASE("Savitzky-Golay with a wide window: exact on its polynomials, weights as closed forms",
          "[signal][savgol]") {
  // Issue #29: the weights were a window x window matrix (6.3 GB at 20001); the filter now keeps
  // the window x (order + 1) factorisation. Checked at the widest window allowed against the
  // same independent references as above: polynomial exactness and the closed-form weights.
  const int window = kMaxSavitzkyGolayWindow, m = (window - 1) / 2, order = 3;
  const double dt = 1e-3;
  const Eigen::Index n = window + 2000;
  const double t_mid = 0.5 * dt * static_cast<double>(n);
  auto poly = [&](double t, int d) {  // (t - t_mid)^3 - 2 (t - t_mid)^2 + 0.5 and derivatives
    const double s = t - t_mid;
    if (d == 0) return s * s * s - 2 * s * s + 0.5;
    if (d == 1) return 3 * s * s - 4 * s;
    return 6 * s - 4;
  };
  const auto y = Sample([&](double t) { return poly(t, 0); }, n, dt);
  for (int d = 0; d <= 2; ++d) {
    const Eigen::VectorXd out = SavitzkyGolay(y, dt, window, order, d);
    const auto ref = Sample([&](double t) { return poly(t, d); }, n, dt);
    INFO("deriv " << d);
    // Exact in exact arithmetic; rounding of the ~1e4-term dot products of O(1) values, and for
    // d = 2 the division by dt^2 = 1e-6 of weights of size ~1/m^3: 1e-6 is far above both.
    CHECK(MaxError(out, ref, 0, n) < 1e-6);
  }
  const internal::SavitzkyGolayFit fit(window, order, 1);
  const Eigen::VectorXd w1 = fit.Weights(m);
  for (int s : {-m, -m / 3, -1, 0, 7, m}) {
    // Relative to the largest weight (~1.5/m^2): the QR solve's rounding on a 10001-row basis.
    CHECK(w1[s + m] == Approx(SlopeWeight(m, s, order)).margin(1e-12));
  }
}

TEST_CASE("Savitzky-Golay window and order limits are named", "[signal][savgol]") {
  const Eigen::VectorXd y = Eigen::VectorXd::LinSpaced(30000, 0, 1);
  CHECK_THROWS_WITH(SavitzkyGolay(y, 1e-3, kMaxSavitzkyGolayWindow + 2, 3, 1),
                    Catch::Contains("window <= 10001"));
  CHECK_THROWS_WITH(SavitzkyGolay(y, 1e-3, 101, kMaxSavitzkyGolayOrder + 1, 1),
                    Catch::Contains("order <= 20"));
}
