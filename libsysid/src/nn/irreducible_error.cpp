#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <nanoflann.hpp>
#include <random>
#include <vector>

#include "core/option_rule.hpp"
#include "sysid/error.hpp"
#include "sysid/nn_irreducible.hpp"

namespace sysid {

void IrreducibleErrorOptions::Validate() const {
  if (neighbours < 2 || neighbours > 1000)
    internal::FailOption("IrreducibleErrorOptions", "neighbours", neighbours,
                         "2 <= neighbours <= 1000");
  if (jackknife_groups != 0 && (jackknife_groups < 5 || jackknife_groups > 100))
    internal::FailOption("IrreducibleErrorOptions", "jackknife_groups", jackknife_groups,
                         "0 or 5 <= jackknife_groups <= 100");
}

namespace {

// The mean over the rows of the output's variance among each row's k nearest neighbours
// (itself included) in `points`, which are standardised and tie-broken.
double MeanNeighbourhoodVariance(const Eigen::MatrixXd& points, const Eigen::VectorXd& targets,
                                 int k) {
  using Tree = nanoflann::KDTreeEigenMatrixAdaptor<Eigen::MatrixXd>;
  const Eigen::Index n = points.rows(), dims = points.cols();
  const Tree tree(static_cast<Tree::Dimension>(dims), std::cref(points), 10);
  std::vector<Eigen::Index> index(static_cast<size_t>(k));
  std::vector<double> distance(static_cast<size_t>(k));
  std::vector<double> query(static_cast<size_t>(dims));
  double sum = 0;
  for (Eigen::Index r = 0; r < n; ++r) {
    for (Eigen::Index c = 0; c < dims; ++c) query[static_cast<size_t>(c)] = points(r, c);
    tree.query(query.data(), static_cast<size_t>(k), index.data(), distance.data());
    double mean = 0;
    for (const Eigen::Index i : index) mean += targets[i];
    mean /= k;
    double ss = 0;
    for (const Eigen::Index i : index) ss += std::pow(targets[i] - mean, 2);
    sum += ss / (k - 1);
  }
  return sum / static_cast<double>(n);
}

// The delete-a-group jackknife's standard error of MeanNeighbourhoodVariance: the estimate
// again without each of `groups` contiguous blocks of rows. A row's noise enters its
// neighbours' terms too, so the terms are not independent and resampling them (a bootstrap)
// misses most of the spread; deleting rows lets every neighbourhood re-form. Contiguous blocks
// keep time-adjacent rows, which share their noise, together.
double JackknifeStandardError(const Eigen::MatrixXd& points, const Eigen::VectorXd& targets, int k,
                              int groups) {
  const Eigen::Index n = points.rows();
  std::vector<double> estimates;
  for (int g = 0; g < groups; ++g) {
    const Eigen::Index begin = n * g / groups, end = n * (g + 1) / groups;
    const Eigen::Index kept = n - (end - begin);
    Eigen::MatrixXd p(kept, points.cols());
    Eigen::VectorXd y(kept);
    p << points.topRows(begin), points.bottomRows(n - end);
    y << targets.head(begin), targets.tail(n - end);
    estimates.push_back(MeanNeighbourhoodVariance(p, y, k));
  }
  double mean = 0;
  for (const double e : estimates) mean += e / groups;
  double ss = 0;
  for (const double e : estimates) ss += (e - mean) * (e - mean);
  return std::sqrt(ss * (groups - 1) / groups);
}

}  // namespace

IrreducibleError EstimateIrreducibleError(const NeuralDataset& data,
                                          const IrreducibleErrorOptions& options) {
  options.Validate();
  const Eigen::Index n = data.size(), dims = data.inputs.cols();
  const int k = options.neighbours;
  if (dims == 0 || data.inputs.rows() != n)
    throw InputError(data.source + ": the data set has no inputs or unequal input and output rows");
  if (n < k)
    throw InputError(fmt::format("{}: {} rows, fewer than the {} neighbours asked for", data.source,
                                 n, k));
  for (Eigen::Index r = 0; r < n; ++r) {
    if (!std::isfinite(data.targets[r]))
      throw InputError(fmt::format("{}: row {}, column {}: expected a finite number", data.source,
                                   r + 1, data.output_name));
    for (Eigen::Index c = 0; c < dims; ++c)
      if (!std::isfinite(data.inputs(r, c)))
        throw InputError(fmt::format("{}: row {}, column {}: expected a finite number",
                                     data.source, r + 1, data.input_names[c]));
  }

  Eigen::MatrixXd points = data.inputs;
  for (Eigen::Index c = 0; c < dims; ++c) {
    // Divided by max|x| first: the mean and the squares of values near the largest double
    // stay finite, so an input gives one answer at every scale (+-1.7e308 as +-1).
    const double scale = points.col(c).cwiseAbs().maxCoeff();
    if (scale > 0) points.col(c) /= scale;
    const double mean = points.col(c).mean();
    const double sd = std::sqrt((points.col(c).array() - mean).square().sum() /
                                static_cast<double>(n));
    points.col(c) = (points.col(c).array() - mean) / (sd > 0 ? sd : 1.0);
  }
  std::mt19937_64 rng(options.seed);
  std::normal_distribution<double> tie(0.0, 1e-9);
  for (Eigen::Index r = 0; r < n; ++r)
    for (Eigen::Index c = 0; c < dims; ++c) points(r, c) += tie(rng);

  IrreducibleError e;
  e.input_names = data.input_names;
  e.output_name = data.output_name;
  e.rows = static_cast<long>(n);
  e.neighbours = k;
  e.mse = MeanNeighbourhoodVariance(points, data.targets, k);
  e.mse_low = e.mse_high = e.mse;
  const int groups = options.jackknife_groups;
  // Each group deleted must leave k rows to form a neighbourhood from.
  if (groups > 0 && n - (n + groups - 1) / groups >= k) {
    const double half = 1.96 * JackknifeStandardError(points, data.targets, k, groups);
    e.mse_low = std::max(0.0, e.mse - half);
    e.mse_high = e.mse + half;
  }
  const double mean = data.targets.mean();
  e.output_variance = (data.targets.array() - mean).square().sum() / static_cast<double>(n);
  // Finite outputs near the largest double square to inf: said, not printed as inf and NaN.
  if (!std::isfinite(e.mse) || !std::isfinite(e.output_variance))
    throw NumericalError(fmt::format(
        "irreducible error of '{}': the variance overflows (mse {}, output variance {}); the "
        "output's values reach {:g}: rescale it",
        data.output_name, e.mse, e.output_variance, data.targets.cwiseAbs().maxCoeff()));
  return e;
}

}  // namespace sysid
