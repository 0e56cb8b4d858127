// The tanh inverse network run one sample at a time: a static map, so the stepper
// holds no history; it exists so that every inverse has the same streaming face (construct,
// Reset, Step) and so that the sample loop allocates nothing. Step is NeuralNetwork::Evaluate
// (std::tanh, inputs scaled by the stored mapminmax ranges, the output unscaled), bit for bit.
// EvaluateBatch sums in Eigen's order and may differ from it in the last bits.
#ifndef SYSID_NN_STEPPER_HPP_
#define SYSID_NN_STEPPER_HPP_

#include <Eigen/Core>

#include <vector>

#include "sysid/nn.hpp"
#include "sysid/nn_operators.hpp"

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

/// The operator-input network's inverse (kind "nn-operators") one sample at a time: the
/// inverse side's play operators on x_ref (from its initial input), then its network on
/// [x_ref, F_r1, ..., F_rm] through NeuralNetwork::Evaluate. OperatorNetworkModel::Invert
/// evaluates the same features with EvaluateBatch (a few ulp apart; not a loop over this).
class OperatorNetworkInverseStepper final : public HysteresisInverseStepper {
 public:
  /// Throws OptionsError for an invalid network.
  explicit OperatorNetworkInverseStepper(const OperatorNetworkModel& model);
  void Reset() override;
  /// u_k [V] from x_ref,k [m]. No allocation and no exception: a reference outside the model's
  /// range (the inverse network's training range widened by half its span; Invert refuses
  /// it) is clamped to it, and saturated() says so.
  double Step(double x_ref_m) override;
  bool saturated() const { return saturated_; }
  bool out_of_range() const override { return saturated_; }
  double x_min_m() const { return lo_; }  ///< [m] lower end of the accepted range
  double x_max_m() const { return hi_; }  ///< [m] upper end

 private:
  OperatorNetworkSide side_;
  std::vector<double> z_;
  Eigen::VectorXd features_;
  double lo_ = 0, hi_ = 0;
  bool saturated_ = false;
};

}  // namespace sysid

#endif  // SYSID_NN_STEPPER_HPP_
