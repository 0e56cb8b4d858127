// Pulse-table least squares against the paper's printed numbers and closed forms.
#include <catch2/catch.hpp>
#include <cmath>
#include <string>
#include <vector>

#include "support/test_support.hpp"
#include "sysid/error.hpp"
#include "sysid/identify.hpp"

using sysid::test::SourcePath;

namespace {
double Round4(double x) { return std::round(x * 1e4) / 1e4; }
}  // namespace

TEST_CASE("the paper's pulse table gives the paper's parameters to every printed digit",
          "[identify][pulse][paper]") {
  const auto points = sysid::ReadPulseTable(SourcePath("datasets/paper/pulse_table.csv"));
  REQUIRE(points.size() == 10);
  const auto r = sysid::FitPulseTable(points, {6.0});
  // The paper prints four decimals: rounding must reproduce them exactly.
  CHECK(Round4(r.model.a1p) == 104.0154);
  CHECK(Round4(r.model.a1n) == 117.1441);
  CHECK(Round4(r.model.a2p) == 3.1023);
  CHECK(Round4(r.model.a2n) == 6.8216);
  CHECK(r.model.a3 == 6.0);
  CHECK(r.fit.rank == 4);
  CHECK(r.fit.dof == 6);
  CHECK(r.fit.residuals.size() == 10);
  CHECK(r.fit.r_diagonal.size() == 4);
}

TEST_CASE("pulse least squares matches the 2x2 normal equations and the textbook covariance",
          "[identify][pulse]") {
  // Independent reference: per direction, simple linear regression y = a1 v + a2 in closed
  // form, s^2 = RSS/(n-2), var(a1) = s^2 / Sxx, var(a2) = s^2 (1/n + vbar^2/Sxx).
  const std::vector<double> v{0.02, 0.031, 0.045, 0.052, 0.07, 0.081};
  const std::vector<double> u{0.9, 1.1, 1.45, 1.62, 1.95, 2.2};
  std::vector<sysid::PulsePoint> pts;
  for (size_t i = 0; i < v.size(); ++i) {
    pts.push_back({u[i], v[i], "p"});
    pts.push_back({-u[i] * 1.1, -v[i] * 0.9 - 0.001 * (i % 2), "n"});
  }
  const double a3 = 4.5;
  const auto r = sysid::FitPulseTable(pts, {a3});
  const double n = 6;
  double sv = 0, sy = 0, svv = 0, svy = 0;
  for (size_t i = 0; i < v.size(); ++i) {
    sv += v[i];
    sy += a3 * u[i];
    svv += v[i] * v[i];
    svy += v[i] * a3 * u[i];
  }
  const double sxx = svv - sv * sv / n;
  const double a1 = (svy - sv * sy / n) / sxx;
  const double a2 = (sy - a1 * sv) / n;
  // Both are exact solutions of the same small problem: agreement to rounding (1e-12 rel).
  CHECK(r.model.a1p == Approx(a1).epsilon(1e-12));
  CHECK(r.model.a2p == Approx(a2).epsilon(1e-10));
  // The joint fit pools both directions' residuals into one variance estimate.
  const double rss_total = r.fit.residuals.squaredNorm();
  const double s2_joint = rss_total / (2 * n - 4);
  CHECK(r.fit.std_error[0] == Approx(std::sqrt(s2_joint / sxx)).epsilon(1e-9));
  CHECK(r.fit.std_error[1] ==
        Approx(std::sqrt(s2_joint * (1 / n + (sv / n) * (sv / n) / sxx))).epsilon(1e-9));
  CHECK(r.fit.covariance(0, 2) == Approx(0.0).margin(1e-15));  // directions are independent
}

TEST_CASE("one-sided or degenerate pulse sets name the unidentifiable parameters",
          "[identify][pulse][errors]") {
  std::vector<sysid::PulsePoint> pos{{1.3, 0.04465, "a"}, {1.6, 0.06222, "b"}};
  CHECK_THROWS_AS(sysid::FitPulseTable(pos, {6.0}), sysid::NumericalError);
  CHECK_THROWS_WITH(sysid::FitPulseTable(pos, {6.0}),
                    Catch::Contains("a1n, a2n: no negative pulses"));
  std::vector<sysid::PulsePoint> neg{{-1.3, -0.04465, "a"}, {-1.6, -0.06222, "b"}};
  CHECK_THROWS_WITH(sysid::FitPulseTable(neg, {6.0}),
                    Catch::Contains("a1p, a2p: no positive pulses"));
  auto single = pos;
  single.push_back({-2.0, -0.05, "c"});
  single.push_back({-2.0, -0.0501, "d"});  // noise: velocities differ, amplitudes do not
  CHECK_THROWS_WITH(sysid::FitPulseTable(single, {6.0}),
                    Catch::Contains("a1n, a2n: the negative pulses have a single amplitude (2 V)"));
  CHECK_THROWS_WITH(sysid::FitPulseTable({{1.0, -0.01, "t.csv row 3"}}, {6.0}),
                    Catch::Contains("t.csv row 3: u = 1 V and v = -0.01 m/s have opposite"));
  CHECK_THROWS_WITH(sysid::FitPulseTable(pos, {0.0}),
                    Catch::Contains("PulseFitOptions::a3 = 0. Violated constraint"));
}
