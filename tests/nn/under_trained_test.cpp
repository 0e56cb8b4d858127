// The under-trained warning (issue 29) fires only when training stopped at max epochs while
// the training MSE was still falling, not when it stopped there on a plateau.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <vector>

#include "support/test_support.hpp"
#include "sysid/nn.hpp"

namespace {

std::vector<sysid::EpochRecord> History(const std::vector<double>& mse, int restart = 0) {
  std::vector<sysid::EpochRecord> h;
  for (size_t i = 0; i < mse.size(); ++i) {
    sysid::EpochRecord e;
    e.epoch = static_cast<int>(i) + 1;
    e.restart = restart;
    e.train_mse = mse[i];
    h.push_back(e);
  }
  return h;
}

}  // namespace

TEST_CASE("TrainingMseStillFalling: the last tenth (at least 5 epochs) fell by more than 1 %",
          "[nn]") {
  using sysid::TrainingMseStillFalling;
  // Hand-made histories whose answer is read off: halving each epoch falls; flat does not.
  std::vector<double> halving, plateau, slow, just_over;
  for (int k = 0; k < 100; ++k) {
    halving.push_back(std::pow(0.5, k));
    plateau.push_back(k < 20 ? std::pow(0.5, k) : std::pow(0.5, 20));
    slow.push_back(1.0 - 0.004 * k / 100.0);  // 0.4 % over the whole run: below 1 %
    just_over.push_back(k < 90 ? 1.0 : 1.0 - 0.0011 * (k - 89));  // 1.1 % over the last 10
  }
  CHECK(TrainingMseStillFalling(History(halving), 0));
  CHECK_FALSE(TrainingMseStillFalling(History(plateau), 0));
  CHECK_FALSE(TrainingMseStillFalling(History(slow), 0));
  CHECK(TrainingMseStillFalling(History(just_over), 0));
  // Four epochs: the window is all of them (fewer than 5).
  CHECK(TrainingMseStillFalling(History({1.0, 0.5, 0.3, 0.2}), 0));
  CHECK_FALSE(TrainingMseStillFalling(History({1.0, 1.0, 1.0, 1.0}), 0));
  // Only the asked restart counts; one epoch shows nothing settled.
  auto both = History(plateau, 0);
  for (const auto& e : History(halving, 1)) both.push_back(e);
  CHECK_FALSE(TrainingMseStillFalling(both, 0));
  CHECK(TrainingMseStillFalling(both, 1));
  CHECK(TrainingMseStillFalling(History({0.3}), 0));
}

TEST_CASE("a budget stop on a plateau gives no warning; one while falling does", "[nn]") {
  // u = 3 v + noise: a 2-unit network reaches the noise floor (about the noise variance) within
  // a few epochs of LM with the output layer re-solved, then only nibbles at it.
  std::mt19937_64 rng(7);
  std::normal_distribution<double> noise(0.0, 0.05);
  sysid::NeuralDataset data;
  data.input_names = {"v"};
  data.output_name = "u";
  data.source = "synthetic";
  const int n = 400;
  data.inputs.resize(n, 1);
  data.targets.resize(n);
  for (int k = 0; k < n; ++k) {
    const double v = -0.1 + 0.2 * k / (n - 1);
    data.inputs(k, 0) = v;
    data.targets[k] = 3 * v + noise(rng);
  }
  sysid::NeuralTrainingOptions o;
  o.hidden = 2;
  o.solve_output_layer = true;
  o.gradient_tolerance = 0;  // no convergence test may end it: only the budget
  o.mu_max = 1e300;
  o.max_epochs = 80;
  const auto plateau = sysid::TrainNeuralNetwork(data, nullptr, o);
  REQUIRE(plateau.stop == sysid::TrainingStop::kMaxEpochs);
  CHECK_FALSE(plateau.still_falling);
  CHECK(plateau.warnings.empty());
  CHECK(plateau.train_mse < 2 * 0.05 * 0.05);  // at the noise floor: the plateau is real

  o.solve_output_layer = false;
  o.max_epochs = 2;
  const auto early = sysid::TrainNeuralNetwork(data, nullptr, o);
  REQUIRE(early.stop == sysid::TrainingStop::kMaxEpochs);
  CHECK(early.still_falling);
  REQUIRE(early.warnings.size() == 1);
  CHECK(early.warnings[0].find("still falling") != std::string::npos);

  // The sweep repeats the rule per hidden size.
  sysid::HiddenSweepOptions so;
  so.hidden_sizes = {2};
  so.training = o;
  so.training.solve_output_layer = true;
  so.training.max_epochs = 80;
  const auto flat = sysid::SweepHiddenSize(data, nullptr, nullptr, so);
  CHECK(flat.warnings.empty());
  so.training.solve_output_layer = false;
  so.training.max_epochs = 2;
  const auto falling = sysid::SweepHiddenSize(data, nullptr, nullptr, so);
  REQUIRE(falling.warnings.size() == 1);
  CHECK(falling.warnings[0].find("H = 2 stopped at --max-epochs 2 while its training MSE") !=
        std::string::npos);
}
