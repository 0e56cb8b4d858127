// FullReport of a training run: the brief paragraph plus every diagnostic.
#include <catch2/catch.hpp>

#include "sysid/nn.hpp"

using Catch::Contains;

TEST_CASE("training: FullReport adds the stopping rule, restarts and warnings", "[nn][report]") {
  sysid::NeuralTrainingResult r;
  r.epochs = 40;
  r.restart = 1;
  r.train_mse = 0.125;
  r.validation_mse = 0.25;
  r.warnings = {"stopped by the epoch budget"};
  r.history = {{39, 0, 1e-3, 0.5, 0.75, 2.0}, {40, 0, 1e-3, 0.375, 0.625, 1.5},
               {40, 1, 1e-4, 0.125, 0.25, 0.5}};
  const std::string full = r.FullReport();
  CHECK(full.rfind(r.BriefReport(), 0) == 0);
  CHECK_THAT(full, Contains("stopping rule: " + sysid::ToString(r.stop)));
  CHECK_THAT(full, Contains("kept restart 1 after 40 epochs"));
  CHECK_THAT(full, Contains("train MSE 0.125, validation MSE 0.25"));
  CHECK_THAT(full, Contains("warnings: 1"));
  CHECK_THAT(full, Contains("restarts: 2"));
  CHECK_THAT(full, Contains("restart 0 epoch 40: 0.375 0.625"));  // the last epoch, not the 39th
  CHECK_THAT(full, Contains("restart 1 epoch 40: 0.125 0.25 0.0001 0.5"));
}
