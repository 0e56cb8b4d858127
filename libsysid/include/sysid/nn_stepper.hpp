// The tanh inverse network run one sample at a time (issue #39): a static map, so the stepper
// holds no history; it exists so that every inverse has the same streaming face (construct,
// Reset, Step) and so that the sample loop allocates nothing. Step is NeuralNetwork::Evaluate
// (std::tanh, inputs scaled by the stored mapminmax ranges, the output unscaled), bit for bit.
// EvaluateBatch sums in Eigen's order and may differ from it in the last bits.
#ifndef SYSID_NN_STEPPER_HPP_
#define SYSID_NN_STEPPER_HPP_

#include <Eigen/Core>

#include "sysid/nn.hpp"

namespace sysid {

class NetworkStepper {
 public:
  /// Throws OptionsError for an invalid network (NeuralNetwork::Validate: sizes, ranges,
  /// non-finite weights).
  explicit NetworkStepper(const NeuralNetwork& network);
  void Reset() {}
  /// u_k [output unit] from the inputs at sample k in the network's input order and units
  /// (inputs()[i].name, .unit): `inputs` points at input_count() values. No allocation and no
  /// exception.
  double Step(const double* inputs) {
    for (Eigen::Index i = 0; i < x_.size(); ++i) x_[i] = inputs[i];
    return network_.Evaluate(x_);
  }
  int input_count() const { return network_.input_count(); }
  const NeuralNetwork& network() const { return network_; }

 private:
  NeuralNetwork network_;
  Eigen::VectorXd x_;
};

}  // namespace sysid

#endif  // SYSID_NN_STEPPER_HPP_
