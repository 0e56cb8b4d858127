#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <numeric>
#include <random>
#include <vector>

#include "sysid/error.hpp"
#include "sysid/nn_irreducible.hpp"

namespace {

sysid::NeuralDataset Dataset(const Eigen::MatrixXd& x, const Eigen::VectorXd& y) {
  sysid::NeuralDataset d;
  for (Eigen::Index c = 0; c < x.cols(); ++c) d.input_names.push_back("x" + std::to_string(c));
  d.output_name = "y";
  d.inputs = x;
  d.targets = y;
  d.source = "data.csv";
  return d;
}

}  // namespace

TEST_CASE("irreducible error: a smooth function plus noise leaves the noise's variance",
          "[nn][irreducible]") {
  // y = sin(3 v) + 0.5 a^2 + e, e ~ N(0, 0.1^2): given (v, a) the floor is 0.01 (closed form);
  // given v alone it is 0.01 + Var(0.5 a^2) = 0.01 + 0.25 * 2/45 (a uniform on [-1, 1]:
  // Var(a^2) = E a^4 - (E a^2)^2 = 1/5 - 1/9).
  const int n = 40000;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> uni(-1, 1);
  std::normal_distribution<double> noise(0, 0.1);
  Eigen::MatrixXd x(n, 2);
  Eigen::VectorXd y(n);
  for (int r = 0; r < n; ++r) {
    x(r, 0) = uni(rng);
    x(r, 1) = uni(rng);
    y[r] = std::sin(3 * x(r, 0)) + 0.5 * x(r, 1) * x(r, 1) + noise(rng);
  }
  const auto both = sysid::EstimateIrreducibleError(Dataset(x, y));
  CHECK(both.mse == Approx(0.01).epsilon(0.06));
  CHECK(both.rows == n);
  const auto v_only = sysid::EstimateIrreducibleError(Dataset(x.leftCols(1), y));
  CHECK(v_only.mse == Approx(0.01 + 0.25 * (1.0 / 5 - 1.0 / 9)).epsilon(0.05));
  CHECK(v_only.unexplained_share() > both.unexplained_share());
}

TEST_CASE("irreducible error: the k-d tree's neighbours equal a brute-force search's",
          "[nn][irreducible]") {
  // Second algorithm: every row's k nearest by a full sort of the distances, on the same
  // standardised, tie-broken points (no ties are left: the perturbation is continuous).
  const int n = 300, k = 7;
  std::mt19937_64 rng(3);
  std::normal_distribution<double> g(0, 1);
  Eigen::MatrixXd x(n, 2);
  Eigen::VectorXd y(n);
  for (int r = 0; r < n; ++r) {
    x(r, 0) = 0.02 * g(rng);  // very different scales: standardisation matters
    x(r, 1) = 50 * g(rng);
    y[r] = x(r, 0) * 30 + std::cos(x(r, 1) / 20) + 0.3 * g(rng);
  }
  sysid::IrreducibleErrorOptions o;
  o.neighbours = k;
  const double tree = sysid::EstimateIrreducibleError(Dataset(x, y), o).mse;

  Eigen::MatrixXd p = x;
  for (Eigen::Index c = 0; c < 2; ++c) {
    const double m = p.col(c).mean();
    const double sd = std::sqrt((p.col(c).array() - m).square().sum() / n);
    p.col(c) = (p.col(c).array() - m) / sd;
  }
  std::mt19937_64 tie_rng(o.seed);
  std::normal_distribution<double> tie(0.0, 1e-9);
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < 2; ++c) p(r, c) += tie(tie_rng);
  double sum = 0;
  for (int r = 0; r < n; ++r) {
    std::vector<int> order(n);
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](int a, int b) {
      return (p.row(a) - p.row(r)).squaredNorm() < (p.row(b) - p.row(r)).squaredNorm();
    });
    double mean = 0, ss = 0;
    for (int i = 0; i < k; ++i) mean += y[order[i]] / k;
    for (int i = 0; i < k; ++i) ss += std::pow(y[order[i]] - mean, 2);
    sum += ss / (k - 1);
  }
  CHECK(tree == Approx(sum / n).epsilon(1e-12));
}

TEST_CASE("irreducible error: quantised inputs in time order are not mistaken for information",
          "[nn][irreducible]") {
  // An encoder-like input with 5 levels, each held for a long run of rows, and an output that
  // drifts slowly in time and is independent of the level: the inputs explain nothing, so the
  // estimate is the output's variance (a search that took tied rows in time order would find
  // neighbours with nearly the same output and report almost 0).
  const int n = 5000;
  Eigen::MatrixXd x(n, 1);
  Eigen::VectorXd y(n);
  for (int r = 0; r < n; ++r) {
    x(r, 0) = 1e-7 * ((r / 50) % 5);
    y[r] = std::sin(2 * M_PI * r / 1700.0);
  }
  const auto e = sysid::EstimateIrreducibleError(Dataset(x, y));
  CHECK(e.unexplained_share() == Approx(1.0).epsilon(0.05));
}

TEST_CASE("irreducible error: bad data and options are refused by name", "[nn][irreducible]") {
  Eigen::MatrixXd x(5, 1);
  x << 1, 2, 3, 4, 5;
  Eigen::VectorXd y(5);
  y << 1, 2, 3, 4, 5;
  sysid::IrreducibleErrorOptions o;
  CHECK_THROWS_WITH(sysid::EstimateIrreducibleError(Dataset(x, y), o),
                    Catch::Contains("data.csv") && Catch::Contains("fewer than the 10"));
  o.neighbours = 1;
  CHECK_THROWS_AS(sysid::EstimateIrreducibleError(Dataset(x, y), o), sysid::OptionsError);
  o.neighbours = 2;
  x(3, 0) = std::nan("");
  CHECK_THROWS_WITH(sysid::EstimateIrreducibleError(Dataset(x, y), o),
                    Catch::Contains("row 4") && Catch::Contains("x0"));
  // Finite outputs whose squares overflow: an error, not inf and NaN in the table.
  x(3, 0) = 4;
  y << 1e308, -1e308, 1e308, -1e308, 1e308;
  CHECK_THROWS_AS(sysid::EstimateIrreducibleError(Dataset(x, y), o), sysid::NumericalError);
  y *= 1e-300;  // the same data, rescaled: finite
  CHECK(std::isfinite(sysid::EstimateIrreducibleError(Dataset(x, y), o).mse));
}

TEST_CASE(
    "irreducible error: the jackknife interval's width matches the estimate's spread over "
    "independent recordings",
    "[nn][irreducible]") {
  // Second method: the sampling spread of the estimate measured directly, over 40 independent
  // data sets of the same law; the jackknife sees one data set only. Its 95 % interval's
  // half-width over 1.96 must match that spread's standard deviation.
  const int n = 2000, sets = 40;
  std::mt19937_64 rng(21);
  std::uniform_real_distribution<double> uni(-1, 1);
  std::normal_distribution<double> noise(0, 0.1);
  std::vector<double> estimates, half_widths;
  for (int s = 0; s < sets; ++s) {
    Eigen::MatrixXd x(n, 1);
    Eigen::VectorXd y(n);
    for (int r = 0; r < n; ++r) {
      x(r, 0) = uni(rng);
      y[r] = std::sin(3 * x(r, 0)) + noise(rng);
    }
    sysid::IrreducibleErrorOptions o;
    o.jackknife_groups = 20;
    o.seed = static_cast<std::uint64_t>(s + 1);
    const auto e = sysid::EstimateIrreducibleError(Dataset(x, y), o);
    CHECK(e.mse_low < e.mse);
    CHECK(e.mse < e.mse_high);
    estimates.push_back(e.mse);
    half_widths.push_back((e.mse_high - e.mse_low) / 2);
  }
  const double mean = std::accumulate(estimates.begin(), estimates.end(), 0.0) / sets;
  double var = 0;
  for (const double e : estimates) var += (e - mean) * (e - mean) / (sets - 1);
  const double jackknife_sd =
      std::accumulate(half_widths.begin(), half_widths.end(), 0.0) / sets / 1.96;
  INFO("jackknife " << jackknife_sd << ", over data sets " << std::sqrt(var));
  CHECK(jackknife_sd == Approx(std::sqrt(var)).epsilon(0.35));

  sysid::IrreducibleErrorOptions none;
  none.jackknife_groups = 0;
  Eigen::MatrixXd x = Eigen::MatrixXd::Random(100, 1);
  const auto e = sysid::EstimateIrreducibleError(Dataset(x, x.col(0)), none);
  CHECK(e.mse_low == e.mse);
  CHECK(e.mse_high == e.mse);
  none.jackknife_groups = 4;
  CHECK_THROWS_AS(sysid::EstimateIrreducibleError(Dataset(x, x.col(0)), none), sysid::OptionsError);
}
