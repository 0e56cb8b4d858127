// Private interface of the two Levenberg–Marquardt trainers. Both work on normalised data
// (Z: n x N inputs in [-1, 1], y: N targets in [-1, 1]) and report MSE in physical units
// through `mse_scale` = ((output max - output min) / 2)^2.
#ifndef SYSID_SRC_NN_TRAINERS_HPP_
#define SYSID_SRC_NN_TRAINERS_HPP_

#include <Eigen/Core>
#include <string>
#include <vector>

#include "sysid/nn.hpp"

namespace sysid::internal::nn {

struct NormalizedData {
  Eigen::MatrixXd Z;  ///< n x N
  Eigen::VectorXd y;  ///< N
};

struct TrainerRun {
  Eigen::VectorXd theta;  ///< best finite parameters (by validation MSE if any, else training)
  TrainingStop stop = TrainingStop::kMaxEpochs;
  std::string message;
  int epochs = 0;
  double train_mse = 0;       ///< [output unit^2] at theta
  double validation_mse = 0;  ///< [output unit^2] at theta, NaN without validation
  std::vector<EpochRecord> history;
};

/// The paper's rule with trainlm's mu schedule (lm_trainer.cpp).
TrainerRun RunLevenbergMarquardt(const NormalizedData& train, const NormalizedData* validation,
                                 int H, const Eigen::VectorXd& theta0, double mse_scale,
                                 const NeuralTrainingOptions& options);

/// Ceres' Levenberg–Marquardt on the same residuals (ceres_trainer.cpp).
TrainerRun RunCeres(const NormalizedData& train, const NormalizedData* validation, int H,
                    const Eigen::VectorXd& theta0, double mse_scale,
                    const NeuralTrainingOptions& options);

}  // namespace sysid::internal::nn

#endif  // SYSID_SRC_NN_TRAINERS_HPP_
