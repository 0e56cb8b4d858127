#include "sysid/nn_irreducible.hpp"

#include <fmt/format.h>

#include <cmath>
#include <nanoflann.hpp>
#include <random>

#include "sysid/error.hpp"

namespace sysid {

void IrreducibleErrorOptions::Validate() const {
  if (neighbours < 2 || neighbours > 1000)
    throw OptionsError(fmt::format(
        "IrreducibleErrorOptions::neighbours is {}. Violated constraint: 2 <= neighbours <= 1000",
        neighbours));
}

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

  using Tree = nanoflann::KDTreeEigenMatrixAdaptor<Eigen::MatrixXd>;
  const Tree tree(static_cast<Tree::Dimension>(dims), std::cref(points), 10);
  std::vector<Eigen::Index> index(static_cast<size_t>(k));
  std::vector<double> distance(static_cast<size_t>(k));
  std::vector<double> query(static_cast<size_t>(dims));
  double sum = 0;
  for (Eigen::Index r = 0; r < n; ++r) {
    for (Eigen::Index c = 0; c < dims; ++c) query[static_cast<size_t>(c)] = points(r, c);
    tree.query(query.data(), static_cast<size_t>(k), index.data(), distance.data());
    double mean = 0;
    for (const Eigen::Index i : index) mean += data.targets[i];
    mean /= k;
    double ss = 0;
    for (const Eigen::Index i : index) ss += std::pow(data.targets[i] - mean, 2);
    sum += ss / (k - 1);
  }

  IrreducibleError e;
  e.input_names = data.input_names;
  e.output_name = data.output_name;
  e.rows = static_cast<long>(n);
  e.neighbours = k;
  e.mse = sum / static_cast<double>(n);
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
