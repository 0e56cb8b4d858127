// Trainers: near-noise-floor fits of known functions, the library LM against Ceres, seeds,
// early stopping, failure reporting and option checks.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "sysid/error.hpp"
#include "sysid/nn.hpp"

using Catch::Matchers::Contains;

namespace {

constexpr double kSigma = 0.05;  // [V] noise of the synthetic targets

double Smooth(double v) { return 2.0 * std::sin(25.0 * v) + 8.0 * v; }  // [V] of v [m/s]

sysid::NeuralDataset MakeSet(int N, unsigned seed, double sigma, double (*f)(double)) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> U(-0.1, 0.1);
  std::normal_distribution<double> noise(0.0, 1.0);
  sysid::NeuralDataset d;
  d.input_names = {"v"};
  d.output_name = "u";
  d.source = "synthetic";
  d.inputs.resize(N, 1);
  d.targets.resize(N);
  for (int k = 0; k < N; ++k) {
    d.inputs(k, 0) = U(gen);
    d.targets[k] = f(d.inputs(k, 0)) + sigma * noise(gen);
  }
  return d;
}

}  // namespace

TEST_CASE("1-24-1 LM (paper rule) fits a smooth function to its noise floor", "[nn][train]") {
  const auto train = MakeSet(1500, 1u, kSigma, &Smooth);
  const auto clean = MakeSet(1000, 2u, 0.0, &Smooth);
  sysid::NeuralTrainingOptions o;
  o.hidden = 24;
  o.max_epochs = 150;
  o.seed = 3;
  const auto r = sysid::TrainNeuralNetwork(train, nullptr, o);
  INFO(r.BriefReport());
  // A fit at the noise floor leaves MSE ~ sigma^2 (1 - P/N = 0.95 of it); 1.1 sigma^2 allows
  // the last few percent of convergence.
  CHECK(r.train_mse < 1.1 * kSigma * kSigma);
  CHECK(r.train_mse > 0.85 * kSigma * kSigma);  // below this it would be fitting the noise
  // Against the noise-free function the error is a small fraction of the noise.
  CHECK(sysid::MeanSquaredError(r.network, clean) < 0.15 * kSigma * kSigma);
  CHECK(r.epochs == static_cast<int>(r.history.size()));
  for (size_t k = 1; k < r.history.size(); ++k)  // LM accepts only error-lowering steps
    CHECK(r.history[k].train_mse <= r.history[k - 1].train_mse);
}

TEST_CASE("the library LM reaches Ceres' MSE from the same start", "[nn][train][ceres]") {
  const auto train = MakeSet(800, 4u, kSigma, &Smooth);
  sysid::NeuralTrainingOptions o;
  o.hidden = 6;
  o.seed = 5;
  o.max_epochs = 400;
  const auto lm = sysid::TrainNeuralNetwork(train, nullptr, o);
  o.trainer = sysid::NeuralTrainer::kCeres;
  const auto ceres = sysid::TrainNeuralNetwork(train, nullptr, o);
  INFO("lm: " << lm.BriefReport() << "\nceres: " << ceres.BriefReport());
  // Same residuals, same start, both converged: the minima agree within 3 %.
  CHECK(lm.train_mse == Approx(ceres.train_mse).epsilon(0.03));
  CHECK(!ceres.history.empty());
  o.trainer = sysid::NeuralTrainer::kLevenbergMarquardt;
  o.solve_output_layer = true;
  const auto hybrid = sysid::TrainNeuralNetwork(train, nullptr, o);
  CHECK(hybrid.train_mse == Approx(ceres.train_mse).epsilon(0.03));
}

TEST_CASE("training is deterministic per seed, restarts keep the best", "[nn][train]") {
  const auto train = MakeSet(300, 6u, kSigma, &Smooth);
  sysid::NeuralTrainingOptions o;
  o.hidden = 5;
  o.max_epochs = 30;
  o.seed = 11;
  const auto a = sysid::TrainNeuralNetwork(train, nullptr, o);
  const auto b = sysid::TrainNeuralNetwork(train, nullptr, o);
  CHECK(a.network.parameters() == b.network.parameters());
  o.seed = 12;
  const auto c = sysid::TrainNeuralNetwork(train, nullptr, o);
  CHECK(c.network.parameters() != a.network.parameters());
  o.seed = 11;
  o.restarts = 2;  // restarts use seeds 11 and 12
  const auto best = sysid::TrainNeuralNetwork(train, nullptr, o);
  CHECK(best.train_mse == std::min(a.train_mse, c.train_mse));
  CHECK(best.restart == (c.train_mse < a.train_mse ? 1 : 0));
}

TEST_CASE("training on 1, 2 or a varying number of threads gives byte-identical networks",
          "[nn][train][threads]") {
  const auto train = MakeSet(3000, 21u, kSigma, &Smooth);
  const auto validation = MakeSet(500, 22u, kSigma, &Smooth);
  for (bool solve_output_layer : {false, true}) {
    sysid::NeuralTrainingOptions o;
    o.solve_output_layer = solve_output_layer;
    o.hidden = 8;
    o.max_epochs = 15;
    o.threads = 1;
    const auto one = sysid::TrainNeuralNetwork(train, &validation, o);
    o.threads = 2;
    const auto two = sysid::TrainNeuralNetwork(train, &validation, o);
    CHECK(one.network.parameters() == two.network.parameters());
    CHECK(one.epochs == two.epochs);
    CHECK(one.train_mse == two.train_mse);
    CHECK(one.validation_mse == two.validation_mse);
    // A share that changes from one pass to the next (a pool's tasks finishing): 1, 2, 3, ...
    int calls = 0;
    o.threads = 1;
    o.threads_now = [&calls] { return 1 + calls++ % 3; };
    const auto varying = sysid::TrainNeuralNetwork(train, &validation, o);
    CHECK(calls > 3 * varying.epochs);  // asked before every pass, not once
    CHECK(one.network.parameters() == varying.network.parameters());
    CHECK(one.epochs == varying.epochs);
    CHECK(one.validation_mse == varying.validation_mse);
  }
}

TEST_CASE("momentum keeps LM monotone and converging", "[nn][train]") {
  const auto train = MakeSet(600, 7u, kSigma, &Smooth);
  sysid::NeuralTrainingOptions o;
  o.hidden = 10;
  o.max_epochs = 120;
  o.momentum = 0.5;
  const auto r = sysid::TrainNeuralNetwork(train, nullptr, o);
  INFO(r.BriefReport());
  // 10 units fit this function closely; 1.3 sigma^2 is well inside reach with momentum.
  CHECK(r.train_mse < 1.3 * kSigma * kSigma);
}

TEST_CASE("validation failures stop training and keep the best validation weights", "[nn][train]") {
  // Overfitting set-up: few noisy samples, many units, validation from the clean function.
  const auto train = MakeSet(60, 8u, 0.3, &Smooth);
  const auto val = MakeSet(200, 9u, 0.0, &Smooth);
  sysid::NeuralTrainingOptions o;
  o.hidden = 30;
  o.max_epochs = 500;
  const auto r = sysid::TrainNeuralNetwork(train, &val, o);
  INFO(r.BriefReport());
  REQUIRE(r.stop == sysid::TrainingStop::kValidationFailures);
  double best = INFINITY;
  for (const auto& e : r.history) best = std::min(best, e.validation_mse);
  CHECK(r.validation_mse == best);
  CHECK(sysid::MeanSquaredError(r.network, val) == Approx(best).epsilon(1e-9));
  CHECK(r.history.back().epoch == r.epochs);
  CHECK(r.epochs < 500);
}

TEST_CASE("non-finite errors are a stop reason, not a crash", "[nn][train]") {
  const auto train = MakeSet(50, 10u, kSigma, &Smooth);
  sysid::NeuralTrainingOptions o;
  o.hidden = 2;
  o.initial_parameters = Eigen::VectorXd::Constant(7, 1e308);  // output overflows to inf
  const auto r = sysid::TrainNeuralNetwork(train, nullptr, o);
  CHECK(r.stop == sysid::TrainingStop::kNumericalFailure);
  CHECK(r.termination == sysid::Termination::kFailure);
  CHECK_THAT(r.message, Contains("non-finite"));
}

TEST_CASE("options and data are checked", "[nn][train]") {
  const auto train = MakeSet(50, 12u, kSigma, &Smooth);
  sysid::NeuralTrainingOptions o;
  o.momentum = 1.0;
  CHECK_THROWS_WITH(sysid::TrainNeuralNetwork(train, nullptr, o),
                    Contains("momentum = 1") && Contains("0 <= momentum < 1"));
  o = {};
  o.input_ranges = {{0.1, -0.1}};
  CHECK_THROWS_AS(sysid::TrainNeuralNetwork(train, nullptr, o), sysid::OptionsError);
  o = {};
  // The output-layer step exists in the library's LM trainer only: under Ceres it is an error,
  // not silently ignored.
  o.trainer = sysid::NeuralTrainer::kCeres;
  o.solve_output_layer = true;
  CHECK_THROWS_WITH(sysid::TrainNeuralNetwork(train, nullptr, o),
                    Contains("solve_output_layer needs trainer = lm"));
  o = {};
  auto constant = train;
  constant.inputs.setConstant(0.05);
  CHECK_THROWS_WITH(sysid::TrainNeuralNetwork(constant, nullptr, o),
                    Contains("column 'v' is constant"));
  auto nan = train;
  nan.targets[3] = NAN;
  CHECK_THROWS_AS(sysid::TrainNeuralNetwork(nan, nullptr, o), sysid::InputError);
}

TEST_CASE("hidden-size sweep: parallel equals sequential, picks min test MSE", "[nn][sweep]") {
  const auto train = MakeSet(400, 13u, kSigma, &Smooth);
  const auto test = MakeSet(300, 14u, kSigma, &Smooth);
  sysid::HiddenSweepOptions so;
  so.hidden_sizes = sysid::ParseHiddenSizes("2:8:2");
  REQUIRE(so.hidden_sizes == std::vector<int>{2, 4, 6, 8});
  so.training.max_epochs = 40;
  so.threads = 2;
  const auto par = sysid::SweepHiddenSize(train, nullptr, &test, so);
  so.threads = 1;
  const auto seq = sysid::SweepHiddenSize(train, nullptr, &test, so);
  REQUIRE(par.rows.size() == 4);
  for (size_t k = 0; k < 4; ++k) {
    CHECK(par.rows[k].hidden == so.hidden_sizes[k]);
    CHECK(par.rows[k].train_mse == seq.rows[k].train_mse);
    CHECK(par.rows[k].test_mse ==
          Approx(sysid::MeanSquaredError(par.runs[k].network, test)).epsilon(1e-12));
  }
  CHECK(par.rule == "min test MSE");
  for (const auto& row : par.rows) CHECK(par.rows[par.chosen].test_mse <= row.test_mse);
  CHECK(sysid::ParseHiddenSizes("16,24") == std::vector<int>{16, 24});
  CHECK_THROWS_WITH(sysid::ParseHiddenSizes("16:x"), Contains("'x' is not an integer"));
  CHECK_THROWS_AS(sysid::ParseHiddenSizes("32:16:2"), sysid::OptionsError);
}

TEST_CASE("LM follows trainlm's mu schedule: times mu_dec per accepted step, mu_inc per failed "
          "trial",
          "[nn][train]") {
  // MATLAB trainlm: an accepted step multiplies mu by mu_dec, each rejected trial before it by
  // mu_inc. So mu_k / mu_(k-1) = mu_dec mu_inc^j with j >= 0 rejected trials in epoch k. Factors
  // with no common power (0.3 and 7) make any other update rule visible in the ratios.
  const auto train = MakeSet(400, 9u, kSigma, &Smooth);
  sysid::NeuralTrainingOptions o;
  o.hidden = 8;
  o.max_epochs = 40;
  o.seed = 2;
  o.mu_decrease = 0.3;
  o.mu_increase = 7.0;
  const auto r = sysid::TrainNeuralNetwork(train, nullptr, o);
  INFO(r.BriefReport());
  REQUIRE(r.history.size() >= 10);
  int immediate = 0;
  double previous = o.mu_initial;
  for (const auto& e : r.history) {
    if (e.epoch == 1) previous = o.mu_initial;  // each restart starts again from mu_initial
    const double j = std::log(e.mu / previous / o.mu_decrease) / std::log(o.mu_increase);
    INFO("epoch " << e.epoch << ": mu " << previous << " -> " << e.mu << ", j = " << j);
    CHECK(j > -1e-9);                                // never more than one decrease per epoch
    CHECK(std::abs(j - std::round(j)) < 1e-9);       // whole numbers of failed trials
    immediate += std::abs(j) < 1e-9;
    previous = e.mu;
  }
  CHECK(immediate > 0);  // most epochs of a smooth fit accept their first trial
}
