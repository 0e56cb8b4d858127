#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "core/option_rule.hpp"
#include "nn/mlp_kernels.hpp"
#include "sysid/error.hpp"
#include "sysid/nn.hpp"

namespace sysid {
namespace {

void CheckRange(const std::string& what, double min, double max) {
  // max - min finite too: the scaling divides by it (-1e308..1e308 made every value 0 or NaN).
  if (!std::isfinite(min) || !std::isfinite(max) || !(min < max) || !std::isfinite(max - min))
    internal::FailOption("NeuralNetwork", what, fmt::format("[{:.17g}, {:.17g}]", min, max),
                         "finite min < max, max - min finite");
}

}  // namespace

std::string DefaultUnit(std::string_view symbol) {
  if (symbol == "t") return "s";
  if (symbol == "u") return "V";
  if (symbol == "x") return "m";
  if (symbol == "v") return "m/s";
  if (symbol == "a") return "m/s^2";
  return "";
}

NeuralNetwork::NeuralNetwork(std::vector<ScaledVariable> inputs, ScaledVariable output, int hidden)
    : inputs_(std::move(inputs)), output_(std::move(output)) {
  if (inputs_.empty())
    internal::FailOption("NeuralNetwork", "inputs", "empty", "at least one input");
  // Checked before the weights are allocated (H x n, 2 H): hidden = 10^9 is a typo, not a
  // request for gigabytes.
  if (hidden < 1 || hidden > kMaxHiddenUnits)
    internal::FailOption(
        "NeuralNetwork", "hidden", hidden,
        fmt::format("1 <= hidden <= {} (sysid::kMaxHiddenUnits)", kMaxHiddenUnits));
  for (const auto& in : inputs_) CheckRange("input '" + in.name + "' range", in.min, in.max);
  CheckRange("output '" + output_.name + "' range", output_.min, output_.max);
  W1_ = Eigen::MatrixXd::Zero(hidden, input_count());
  b1_ = Eigen::VectorXd::Zero(hidden);
  w2_ = Eigen::VectorXd::Zero(hidden);
}

std::vector<std::string> NeuralNetwork::input_names() const {
  std::vector<std::string> names;
  for (const auto& in : inputs_) names.push_back(in.name);
  return names;
}

Eigen::VectorXd NeuralNetwork::parameters() const {
  return internal::nn::PackParameters(W1_, b1_, w2_, b2_);
}

void NeuralNetwork::set_parameters(const Eigen::VectorXd& theta) {
  const int H = hidden_size(), n = input_count();
  if (theta.size() != parameter_count())
    internal::FailOption("NeuralNetwork::set_parameters", "theta",
                         fmt::format("{} entries", theta.size()),
                         fmt::format("size = H n + 2 H + 1 = {}", parameter_count()));
  const internal::nn::Weights w(theta, n, H);
  W1_ = w.W1;
  b1_ = w.b1;
  w2_ = w.w2;
  b2_ = w.b2;
}

void NeuralNetwork::set_input_range(int i, double min, double max) {
  SYSID_CHECK(i >= 0 && i < input_count(), "input index " + std::to_string(i));
  CheckRange("input '" + inputs_[i].name + "' range", min, max);
  inputs_[i].min = min;
  inputs_[i].max = max;
}

void NeuralNetwork::set_output_range(double min, double max) {
  CheckRange("output '" + output_.name + "' range", min, max);
  output_.min = min;
  output_.max = max;
}

double NeuralNetwork::Evaluate(const Eigen::Ref<const Eigen::VectorXd>& x) const {
  SYSID_CHECK(x.size() == input_count(), "Evaluate: got " + std::to_string(x.size()) +
                                             " inputs, network has " +
                                             std::to_string(input_count()));
  const int H = hidden_size(), n = input_count();
  double y = b2_;
  for (int h = 0; h < H; ++h) {
    double s = b1_[h];
    for (int i = 0; i < n; ++i) s += W1_(h, i) * inputs_[i].Normalize(x[i]);
    y += w2_[h] * std::tanh(s);
  }
  return output_.Denormalize(y);
}

Eigen::VectorXd NeuralNetwork::EvaluateBatch(const Eigen::MatrixXd& X) const {
  if (X.cols() != input_count())
    internal::FailOption("NeuralNetwork::EvaluateBatch", "X", fmt::format("{} columns", X.cols()),
                         fmt::format("columns = inputs = {}", input_count()));
  const Eigen::Index N = X.rows();
  Eigen::VectorXd out(N);
  constexpr Eigen::Index kBlock = 512;
  Eigen::MatrixXd Z, A;
  for (Eigen::Index first = 0; first < N; first += kBlock) {
    const Eigen::Index count = std::min(kBlock, N - first);
    Z.resize(input_count(), count);
    for (int i = 0; i < input_count(); ++i) {
      const double c = 2.0 / (inputs_[i].max - inputs_[i].min);
      Z.row(i) = ((X.col(i).segment(first, count).array() - inputs_[i].min) * c - 1.0).transpose();
    }
    A.noalias() = W1_ * Z;
    A.colwise() += b1_;
    A = A.array().tanh();
    Eigen::VectorXd y = A.transpose() * w2_;
    out.segment(first, count) =
        output_.min + 0.5 * (y.array() + b2_ + 1.0) * (output_.max - output_.min);
  }
  return out;
}

void NeuralNetwork::Validate() const {
  if (inputs_.empty() || hidden_size() < 1)
    internal::FailOption("NeuralNetwork", inputs_.empty() ? "inputs" : "hidden",
                         inputs_.empty() ? "empty" : "0 units", "inputs >= 1, hidden >= 1");
  for (const auto& in : inputs_) CheckRange("input '" + in.name + "' range", in.min, in.max);
  CheckRange("output '" + output_.name + "' range", output_.min, output_.max);
  if (!parameters().allFinite())
    internal::FailOption("NeuralNetwork", "parameters", "a NaN or infinite weight",
                         "finite weights");
}

}  // namespace sysid
