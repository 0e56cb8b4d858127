// The irreducible-error estimate (sysid irreducible): the k-d tree (nanoflann) against a
// brute-force neighbour search on the same standardised points, in the same process, one
// thread, best of R passes of CPU time; both give the same estimate (checked and printed).
//
//   bench_irreducible REC.csv [--inputs v,a] [--neighbours K] [--repeats R] [--rows N]
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "bench_clock.hpp"
#include "sysid/nn.hpp"
#include "sysid/nn_irreducible.hpp"

namespace {

// The baseline: every row's k nearest by a partial sort of all distances (the estimator's
// definition written out), on the points the library builds (standardised, tie-broken).
double BruteForce(const sysid::NeuralDataset& d, int k, std::uint64_t seed) {
  const Eigen::Index n = d.size(), dims = d.inputs.cols();
  Eigen::MatrixXd p = d.inputs;
  for (Eigen::Index c = 0; c < dims; ++c) {
    const double m = p.col(c).mean();
    const double sd = std::sqrt((p.col(c).array() - m).square().sum() / static_cast<double>(n));
    p.col(c) = (p.col(c).array() - m) / (sd > 0 ? sd : 1.0);
  }
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> tie(0.0, 1e-9);
  for (Eigen::Index r = 0; r < n; ++r)
    for (Eigen::Index c = 0; c < dims; ++c) p(r, c) += tie(rng);
  std::vector<double> dist(static_cast<size_t>(n));
  std::vector<Eigen::Index> order(static_cast<size_t>(n));
  double sum = 0;
  for (Eigen::Index r = 0; r < n; ++r) {
    for (Eigen::Index j = 0; j < n; ++j)
      dist[static_cast<size_t>(j)] = (p.row(j) - p.row(r)).squaredNorm();
    std::iota(order.begin(), order.end(), Eigen::Index{0});
    std::partial_sort(order.begin(), order.begin() + k, order.end(),
                      [&](Eigen::Index a, Eigen::Index b) {
                        return dist[static_cast<size_t>(a)] < dist[static_cast<size_t>(b)];
                      });
    double mean = 0, ss = 0;
    for (int i = 0; i < k; ++i) mean += d.targets[order[static_cast<size_t>(i)]] / k;
    for (int i = 0; i < k; ++i) ss += std::pow(d.targets[order[static_cast<size_t>(i)]] - mean, 2);
    sum += ss / (k - 1);
  }
  return sum / static_cast<double>(n);
}

}  // namespace

int main(int argc, char** argv) {
  std::string path, inputs = "v,a";
  int k = 10, repeats = 3;
  long rows = 0;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--inputs" && i + 1 < argc) inputs = argv[++i];
    else if (a == "--neighbours" && i + 1 < argc) k = std::max(2, std::atoi(argv[++i]));
    else if (a == "--repeats" && i + 1 < argc) repeats = std::max(1, std::atoi(argv[++i]));
    else if (a == "--rows" && i + 1 < argc) rows = std::max(0L, std::atol(argv[++i]));
    else path = a;
  }
  if (path.empty()) {
    fmt::print(stderr, "usage: bench_irreducible REC.csv [--inputs v,a] [--neighbours K] "
                       "[--repeats R] [--rows N]\n");
    return 1;
  }
  std::vector<std::string> names;
  for (size_t s = 0, c; s <= inputs.size(); s = c + 1) {
    c = std::min(inputs.find(',', s), inputs.size());
    names.push_back(inputs.substr(s, c - s));
  }
  sysid::NeuralDataset d = sysid::ReadNeuralDataset(path, names, "u");
  if (rows > 0 && rows < d.size()) {  // the first N rows: the brute force is O(N^2)
    d.inputs = d.inputs.topRows(rows).eval();
    d.targets = d.targets.head(rows).eval();
  }
  sysid::IrreducibleErrorOptions o;
  o.neighbours = k;
  double tree_s = 1e300, brute_s = 1e300, tree = 0, brute = 0;
  for (int r = 0; r < repeats; ++r) {  // alternated: both see the same load
    double t0 = sysid::bench::CpuSeconds();
    tree = sysid::EstimateIrreducibleError(d, o).mse;
    tree_s = std::min(tree_s, sysid::bench::CpuSeconds() - t0);
    t0 = sysid::bench::CpuSeconds();
    brute = BruteForce(d, k, o.seed);
    brute_s = std::min(brute_s, sysid::bench::CpuSeconds() - t0);
  }
  fmt::print("irreducible error of u on {} ({} rows, k = {}), load {}\n", inputs, d.size(), k,
             sysid::bench::LoadAverage());
  fmt::print("k-d tree    {:.6f} s CPU   estimate {:.9g}\n", tree_s, tree);
  fmt::print("brute force {:.6f} s CPU   estimate {:.9g}\n", brute_s, brute);
  fmt::print("ratio brute / tree: {:.1f}x; estimates differ by {:.2g} (relative)\n",
             brute_s / tree_s, std::abs(brute - tree) / std::abs(brute));
  return std::abs(brute - tree) <= 1e-12 * std::abs(brute) ? 0 : 2;
}
