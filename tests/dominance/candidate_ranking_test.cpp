#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "sysid/dominance_candidates.hpp"
#include "sysid/error.hpp"
#include "sysid/hysteresis.hpp"

namespace {

sysid::Recording Make(const Eigen::VectorXd& u, const Eigen::VectorXd& x, double dt) {
  sysid::Recording rec;
  rec.source = "r.csv";
  rec.names = {"t", "u", "x"};
  rec.data.resize(u.size(), 3);
  for (Eigen::Index k = 0; k < u.size(); ++k) rec.data.row(k) << k * dt, u[k], x[k];
  return rec;
}

}  // namespace

TEST_CASE("candidate ranking: a velocity source ranks v, a stack ranks x", "[dominance]") {
  const int n = 4000;
  const double dt = 1e-3;
  std::mt19937_64 rng(3);
  std::normal_distribution<double> noise(0, 1e-3);
  // Velocity source: u = 20 V/(m/s) v + small noise, x = a sum of sines (v its derivative).
  Eigen::VectorXd x(n), u(n);
  for (int k = 0; k < n; ++k) {
    const double t = k * dt;
    x[k] = 0.01 * std::sin(2 * M_PI * 1.0 * t) + 0.004 * std::sin(2 * M_PI * 3.1 * t);
    const double v = 0.01 * 2 * M_PI * std::cos(2 * M_PI * t) + 0.004 * 2 * M_PI * 3.1 * std::cos(2 * M_PI * 3.1 * t);
    u[k] = 20 * v + noise(rng);
  }
  const auto stage = sysid::RankCandidates(Make(u, x, dt));
  CHECK(stage.dominant == "v");
  CHECK(stage.r2 > 0.99);  // central differences of smooth sines: the model holds
  // Stack: x = PI[u], slow: u is a hysteretic function of x.
  sysid::PiParameters p;
  p.thresholds = {0.3, 0.6, 0.9};
  p.weights = {2e-6, 1e-6, 1e-6};
  p.polynomial = {5e-6};
  p.input_min_v = 0;
  p.input_max_v = 4;
  const sysid::PrandtlIshlinskiiModel m(p);
  for (int k = 0; k < n; ++k) u[k] = 2 + 1.8 * std::sin(2 * M_PI * 0.5 * k * dt);
  const auto stack = sysid::RankCandidates(Make(u, m.Simulate(u, dt), dt));
  CHECK(stack.dominant == "x");
  CHECK(stack.margin > 10);  // a slow sine: v's and a's terms are an order smaller at least
}

TEST_CASE("candidate ranking refuses a recording without x", "[dominance]") {
  sysid::Recording rec;
  rec.source = "nox.csv";
  rec.names = {"t", "u", "v"};
  rec.data = Eigen::MatrixXd::Random(10, 3);
  CHECK_THROWS_WITH(sysid::RankCandidates(rec), Catch::Contains("nox.csv") && Catch::Contains("'x'"));
}

TEST_CASE("candidate ranking refuses data that cannot rank: constant u or x, overflow",
          "[dominance]") {
  // Before: a stage at rest gave "dominant x (margin inf); R^2 -nan", exit 0.
  const Eigen::Index n = 400;
  Eigen::VectorXd u(n), x(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    u[k] = std::sin(0.05 * static_cast<double>(k));
    x[k] = 1e-6 * u[k];
  }
  CHECK_NOTHROW(sysid::RankCandidates(Make(u, x, 1e-3)));
  CHECK_THROWS_WITH(sysid::RankCandidates(Make(u, Eigen::VectorXd::Zero(n), 1e-3)),
                    Catch::Contains("r.csv: column 'x' is constant (0 m)"));
  CHECK_THROWS_WITH(sysid::RankCandidates(Make(Eigen::VectorXd::Constant(n, 2), x, 1e-3)),
                    Catch::Contains("r.csv: column 'u' is constant (2 V)"));
  CHECK_THROWS_AS(sysid::RankCandidates(Make(1e300 * u, 1e296 * u, 1e-3)), sysid::NumericalError);
}
