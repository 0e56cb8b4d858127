#include "sysid/hysteresis.hpp"
#include "sysid/nn_stepper.hpp"

namespace sysid {

NetworkStepper::NetworkStepper(const NeuralNetwork& network)
    : network_(network), x_(Eigen::VectorXd::Zero(network.input_count())) {
  network_.Validate();
}

OperatorNetworkInverseStepper::OperatorNetworkInverseStepper(const OperatorNetworkModel& model)
    : side_(model.inverse()),
      z_(side_.thresholds.size(), side_.initial_input),
      features_(Eigen::VectorXd::Zero(static_cast<Eigen::Index>(side_.thresholds.size()) + 1)) {
  side_.network.Validate();
  const ScaledVariable& range = side_.network.inputs()[0];
  const double half = 0.5 * (range.max - range.min);
  lo_ = range.min - half;
  hi_ = range.max + half;
}

void OperatorNetworkInverseStepper::Reset() {
  for (double& z : z_) z = side_.initial_input;
  saturated_ = false;
}

double OperatorNetworkInverseStepper::Step(double x_ref_m) {
  saturated_ = !(x_ref_m >= lo_ && x_ref_m <= hi_);
  const double x = saturated_ ? (x_ref_m > hi_ ? hi_ : lo_) : x_ref_m;
  features_[0] = x;
  for (size_t i = 0; i < z_.size(); ++i)
    features_[static_cast<Eigen::Index>(i) + 1] = z_[i] = PlayStep(x, side_.thresholds[i], z_[i]);
  return side_.network.Evaluate(features_);
}

}  // namespace sysid
