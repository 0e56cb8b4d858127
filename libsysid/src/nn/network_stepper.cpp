#include "sysid/nn_stepper.hpp"

namespace sysid {

NetworkStepper::NetworkStepper(const NeuralNetwork& network)
    : network_(network), x_(Eigen::VectorXd::Zero(network.input_count())) {
  network_.Validate();
}

}  // namespace sysid
