// The networks' experiment: the training and test sets (P-controlled sinusoids), the dominant
// v -> u network, the typical (v, a) -> u one, their MSEs and the sets' coverage.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "paper/experiments.hpp"
#include "sysid/nn_irreducible.hpp"

namespace sysid::paper {
namespace {

// The rows of `data` whose first input (v [m/s]) is at least kRestSpeedMps in magnitude.
NeuralDataset MovingRows(const NeuralDataset& data) {
  NeuralDataset out = data;
  Eigen::Index n = 0;
  for (Eigen::Index k = 0; k < data.size(); ++k) {
    if (std::abs(data.inputs(k, 0)) < kRestSpeedMps) continue;
    out.inputs.row(n) = data.inputs.row(k);
    out.targets[n++] = data.targets[k];
  }
  out.inputs.conservativeResize(n, Eigen::NoChange);
  out.targets.conservativeResize(n);
  return out;
}

// The MSE of `net` on the moving rows of `data` [V^2]; NaN (null in JSON) when the stage never
// moved (a collection gain too weak to move it: --collect-kp 1 failed with "no data rows").
double MovingMse(const NeuralNetwork& net, const NeuralDataset& data) {
  const NeuralDataset moving = MovingRows(data);
  return moving.size() > 0 ? MeanSquaredError(net, moving) : std::nan("");
}

SetCoverage Coverage(const Recording& training, const Recording& test) {
  SetCoverage c;
  const Eigen::VectorXd tv = training.column("v"), ta = training.column("a");
  const Eigen::VectorXd sv = test.column("v"), sa = test.column("a");
  c.training_max_abs_v_mps = tv.cwiseAbs().maxCoeff();
  c.training_max_abs_a_mps2 = ta.cwiseAbs().maxCoeff();
  c.test_max_abs_v_mps = sv.cwiseAbs().maxCoeff();
  c.test_max_abs_a_mps2 = sa.cwiseAbs().maxCoeff();
  // Test rows outside the training set's (v, a) bounding box: where a network extrapolates.
  long outside = 0;
  for (Eigen::Index k = 0; k < sv.size(); ++k)
    outside += sv[k] < tv.minCoeff() || sv[k] > tv.maxCoeff() || sa[k] < ta.minCoeff() ||
               sa[k] > ta.maxCoeff();
  c.test_rows_outside_training_box_fraction =
      static_cast<double>(outside) / static_cast<double>(sv.size());
  const Eigen::Index n = ta.size(), w = 10;
  double noise = 0;
  for (Eigen::Index k = w; k + w < n; ++k)
    noise += std::pow(ta[k] - ta.segment(k - w, 2 * w + 1).mean(), 2);
  c.training_a_noise_rms_mps2 =
      std::sqrt(noise / static_cast<double>(std::max<Eigen::Index>(n - 2 * w, 1)));
  c.training_a_rms_mps2 = std::sqrt(ta.squaredNorm() / static_cast<double>(n));
  // At rest v and a are ~0 whatever u is in the dead zone, so these rows hold most of any
  // network's MSE on this stage.
  const Eigen::VectorXd tu = training.column("u");
  double rest = 0, sum = 0, sum2 = 0;
  for (Eigen::Index k = 0; k < n; ++k) {
    if (std::abs(tv[k]) >= kRestSpeedMps) continue;
    rest += 1;
    sum += tu[k];
    sum2 += tu[k] * tu[k];
  }
  const double mean = rest > 0 ? sum / rest : 0.0;
  c.training_rest_fraction = rest / static_cast<double>(n);
  c.training_u_variance_at_rest_v2 = rest > 0 ? std::max(sum2 / rest - mean * mean, 0.0) : 0.0;
  return c;
}

}  // namespace

const NetworkExperiment& Experiments::Networks() {
  if (network_) return *network_;
  Step("training and test sets (P-controlled sinusoids)");
  TrackingProcedure tp;
  tp.kp_v_per_m = o_.collection_kp_v_per_m;
  const Recording training =
      RunTrackingSet(stage_, TrainingGrid(), tp, DeriveSeed(o_.seed, 1), "training");
  const Recording test = RunTrackingSet(stage_, TestGrid(), tp, DeriveSeed(o_.seed, 2), "test");
  NetworkExperiment& e = network_.emplace();
  e.coverage = Coverage(training, test);
  e.train_v = MakeNeuralDataset(training, {"v"}, "u");
  const NeuralDataset test_v = MakeNeuralDataset(test, {"v"}, "u");
  Step(fmt::format("dominant network (v, {} units)", o_.training.hidden));
  e.dominant = TrainNeuralNetwork(e.train_v, nullptr, DominantTraining(0)).network;
  e.dominant_mse = {MeanSquaredError(e.dominant, e.train_v), MeanSquaredError(e.dominant, test_v)};
  e.dominant_moving_mse = {MovingMse(e.dominant, e.train_v), MovingMse(e.dominant, test_v)};
  if (typical_network_) TrainTypical(training, test);
  return *network_;
}

void Experiments::TrainTypical(const Recording& training, const Recording& test) {
  NetworkExperiment& e = *network_;
  Step(fmt::format("typical network (v, a, {} units)", o_.typical_hidden));
  const NeuralDataset test_v = MakeNeuralDataset(test, {"v"}, "u");
  const NeuralDataset train_va = MakeNeuralDataset(training, {"v", "a"}, "u");
  const NeuralDataset test_va = MakeNeuralDataset(test, {"v", "a"}, "u");
  NeuralTrainingOptions t = DominantTraining(0);
  t.hidden = o_.typical_hidden;
  t.max_epochs = o_.typical_max_epochs;
  const NeuralNetwork typical =
      TrainNeuralNetwork(SubsampleRows(train_va, o_.typical_stride), nullptr, t).network;
  e.typical_trained = true;
  e.typical_mse = {MeanSquaredError(typical, train_va), MeanSquaredError(typical, test_va)};
  e.typical_moving_mse = {MovingMse(typical, train_va), MovingMse(typical, test_va)};
  // What no network on these inputs could do better than, from the data alone: tells the
  // networks' training apart from what v (or v and a) determine on each set.
  e.irreducible_v = {EstimateIrreducibleError(e.train_v).mse, EstimateIrreducibleError(test_v).mse};
  e.irreducible_va = {EstimateIrreducibleError(train_va).mse,
                      EstimateIrreducibleError(test_va).mse};
}

}  // namespace sysid::paper
