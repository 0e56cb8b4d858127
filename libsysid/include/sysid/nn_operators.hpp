// The operator-input network (kind "nn-operators", docs/hysteresis.md "## Operator-input
// network"): the paper's tanh network (sysid/nn.hpp, LM-trained as the nn module does), whose
// inputs are the dominant variable plus play-operator outputs of it, the "expanded input space"
// the paper cites (e.g. Zhang & Tan's hysteretic operators as network inputs):
//   forward  y_k = N_f(u_k, F_r1[u]_k, ..., F_rm[u]_k)       [m]
//   inverse  u_k = N_i(y_k, F_s1[y]_k, ..., F_sm[y]_k)       [V]
// Both networks are trained on the same recordings; the inverse is identified directly, as the
// paper identifies its inverse model. With m = 0 operators the model is the paper's static
// network on the dominant variable alone. Thresholds are uniform over each network's input
// range (r_i = i R / (m + 1), R = half the range); each side's operators start at rest at its
// `initial_input` (u: 0 V; y: the first training sample's x).
#ifndef SYSID_NN_OPERATORS_HPP_
#define SYSID_NN_OPERATORS_HPP_

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "sysid/hysteresis_model.hpp"
#include "sysid/io.hpp"
#include "sysid/nn.hpp"

namespace sysid {

struct OperatorNetworkOptions {
  int operators = 4;         ///< m play operators per network (0..kMaxPlayOperators)
  int hidden = 10;           ///< H tanh units (1..200)
  int max_epochs = 300;      ///< LM epochs per network (1..100000)
  int restarts = 2;          ///< initialisations; the best is kept (1..100)
  std::uint64_t seed = 1;    ///< initialisation seed
  void Validate() const;     ///< OptionsError naming the field and the rule
};

/// One side of the model: the play operators on its input and the network.
struct OperatorNetworkSide {
  std::vector<double> thresholds;  ///< [input unit] 0 < r_1 < ... < r_m
  double initial_input = 0;        ///< [input unit] the operators' rest point before sample 0
  NeuralNetwork network;           ///< inputs: the variable, then F_r1 .. F_rm
  /// The network's output for the samples `input` (operators from initial_input).
  Eigen::VectorXd Evaluate(const Eigen::VectorXd& input) const;
  /// The network's input matrix (N x (1 + m)) for the samples.
  Eigen::MatrixXd Features(const Eigen::VectorXd& input) const;
};

class OperatorNetworkModel : public HysteresisModel {
 public:
  OperatorNetworkModel(OperatorNetworkSide forward, OperatorNetworkSide inverse);
  std::string kind() const override { return "nn-operators"; }
  Eigen::VectorXd Simulate(const Eigen::VectorXd& u, double dt_s) const override;
  bool invertible() const override { return true; }
  /// The inverse network's prediction; InputError naming the sample when y leaves the inverse
  /// network's training range widened by half its span (a tanh network extrapolates flat).
  Eigen::VectorXd Invert(const Eigen::VectorXd& y_desired, double dt_s) const override;
  /// An OperatorNetworkInverseStepper (sysid/nn_stepper.hpp; dt_s unused).
  std::unique_ptr<HysteresisInverseStepper> InverseStepper(double dt_s) const override;
  /// Every weight of both networks (forward first; standard errors NaN: not estimated).
  std::vector<HysteresisParameter> parameters() const override;
  std::string ToJson(int indent = 2) const override;
  const OperatorNetworkSide& forward() const { return forward_; }
  const OperatorNetworkSide& inverse() const { return inverse_; }

 private:
  OperatorNetworkSide forward_, inverse_;
};

/// Trains both networks on the recordings (columns t, u [V], x [m]). OptionsError, before
/// anything is allocated, when the fit's memory (features of N samples x (1 + operators), the
/// training's 16 P^2 + 8 N H bytes) passes kTrainingMemoryLimitBytes.
std::unique_ptr<OperatorNetworkModel> FitOperatorNetwork(const std::vector<Recording>& recordings,
                                                         const OperatorNetworkOptions& options = {},
                                                         HysteresisFitSummary* summary = nullptr);

/// Reads the model file's text; InputError "SOURCE:LINE:COL: ..." when invalid.
std::unique_ptr<OperatorNetworkModel> OperatorNetworkFromJson(std::string_view text,
                                                              const std::string& source);

}  // namespace sysid

#endif  // SYSID_NN_OPERATORS_HPP_
