// nn_json.cpp: the training and sweep options round-trip through JSON; bad keys, types and
// rules are positioned errors.
#include <catch2/catch.hpp>
#include <string>

#include "sysid/error.hpp"
#include "sysid/nn.hpp"

namespace {
sysid::NeuralTrainingOptions Changed() {
  sysid::NeuralTrainingOptions o;
  o.hidden = 7;
  o.trainer = sysid::NeuralTrainer::kCeres;
  o.init = sysid::NeuralInit::kUniform;
  o.momentum = 0.25;
  o.mu_initial = 0.01;
  o.mu_decrease = 0.2;
  o.mu_increase = 5;
  o.mu_max = 1e8;
  o.gradient_tolerance = 1e-6;
  o.max_epochs = 77;
  o.max_validation_failures = 4;
  o.goal_mse = 1e-5;
  o.seed = 18446744073709551615ULL;  // the largest uint64 survives
  o.restarts = 3;
  o.input_ranges = {{-0.1, 0.1}, {-2.0, 2.5}};
  o.output_range = std::make_pair(-10.0, 10.0);
  o.initial_parameters = Eigen::VectorXd::LinSpaced(29, -1.0, 1.0);
  o.ceres_block_size = 64;
  o.threads = 2;
  return o;
}
}  // namespace

TEST_CASE("training options round-trip through JSON", "[nn][json]") {
  const sysid::NeuralTrainingOptions o = Changed();
  const std::string text = sysid::ToJson(o);
  const auto back = sysid::NeuralTrainingOptionsFromJson(text, "t.json");
  CHECK(back.hidden == 7);
  CHECK(back.trainer == sysid::NeuralTrainer::kCeres);
  CHECK(back.init == sysid::NeuralInit::kUniform);
  CHECK(back.momentum == 0.25);
  CHECK(back.max_epochs == 77);
  CHECK(back.seed == 18446744073709551615ULL);
  CHECK(back.input_ranges == o.input_ranges);
  REQUIRE(back.output_range);
  CHECK(*back.output_range == *o.output_range);
  REQUIRE(back.initial_parameters);
  CHECK(back.initial_parameters->isApprox(*o.initial_parameters, 0.0));
  CHECK(back.ceres_block_size == 64);
  CHECK(sysid::ToJson(back) == text);
  // Unset optionals are null and read back unset.
  const auto plain = sysid::NeuralTrainingOptionsFromJson(sysid::ToJson(sysid::NeuralTrainingOptions{}), "p.json");
  CHECK_FALSE(plain.output_range);
  CHECK_FALSE(plain.initial_parameters);
}

TEST_CASE("sweep options round-trip through JSON", "[nn][json]") {
  sysid::HiddenSweepOptions o;
  o.hidden_sizes = {4, 9, 13};
  o.training = Changed();
  o.threads = 5;
  const std::string text = sysid::ToJson(o);
  const auto back = sysid::HiddenSweepOptionsFromJson(text, "s.json");
  CHECK(back.hidden_sizes == o.hidden_sizes);
  CHECK(back.training.restarts == 3);
  CHECK(back.threads == 5);
  CHECK(sysid::ToJson(back) == text);
}

TEST_CASE("training options JSON: bad input names the place", "[nn][json]") {
  using Catch::Contains;
  // The library's rule that the output-layer solve needs the LM trainer.
  CHECK_THROWS_WITH(sysid::NeuralTrainingOptionsFromJson(
                        "{\"trainer\": \"ceres\",\n \"solve_output_layer\": true}", "t.json"),
                    Contains("t.json:2:2: solve_output_layer: expected solve_output_layer needs "
                             "trainer = lm"));
  CHECK_THROWS_WITH(sysid::NeuralTrainingOptionsFromJson("{\"trainer\": \"adam\"}", "t.json"),
                    Contains("t.json:1:2: trainer: expected a trainer (lm or ceres)"));
  CHECK_THROWS_WITH(sysid::NeuralTrainingOptionsFromJson("{\"init\": \"zeros\"}", "t.json"),
                    Contains("init: expected \"nguyen-widrow\" or \"uniform\""));
  CHECK_THROWS_WITH(sysid::NeuralTrainingOptionsFromJson("{\"seed\": -1}", "t.json"),
                    Contains("seed: expected an integer in [0, 2^64 - 1], found -1"));
  CHECK_THROWS_WITH(sysid::NeuralTrainingOptionsFromJson("{\"output_range\": [1]}", "t.json"),
                    Contains("output_range: expected an array of 2 values"));
  CHECK_THROWS_WITH(sysid::NeuralTrainingOptionsFromJson("{\"output_range\": [1, -1]}", "t.json"),
                    Contains("t.json:1:2: output_range: expected finite min < max, max - min "
                             "finite, found -1"));
  CHECK_THROWS_WITH(sysid::HiddenSweepOptionsFromJson("{\"hidden_sizes\": [8, 0]}", "s.json"),
                    Contains("s.json:1:22: hidden_sizes[1]: expected every size >= 1, found 0"));
  CHECK_THROWS_WITH(sysid::HiddenSweepOptionsFromJson("{\"training\": {\"hiden\": 3}}", "s.json"),
                    Contains("unknown key 'hiden' in 'training'"));
}
