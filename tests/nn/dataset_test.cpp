// NeuralDataset helpers.
#include <catch2/catch.hpp>

#include "sysid/nn.hpp"

TEST_CASE("SubsampleRows keeps rows 0, s, 2s, ... with their targets", "[nn][dataset]") {
  sysid::NeuralDataset d;
  d.inputs.resize(7, 2);
  d.targets.resize(7);
  for (int k = 0; k < 7; ++k) {
    d.inputs(k, 0) = k;
    d.inputs(k, 1) = 10.0 * k;
    d.targets[k] = 100.0 * k;
  }
  const sysid::NeuralDataset s = sysid::SubsampleRows(d, 3);
  REQUIRE(s.size() == 3);  // rows 0, 3, 6: ceil(7 / 3)
  for (int k = 0; k < 3; ++k) {
    CHECK(s.inputs(k, 0) == 3.0 * k);
    CHECK(s.inputs(k, 1) == 30.0 * k);
    CHECK(s.targets[k] == 300.0 * k);
  }
  CHECK(sysid::SubsampleRows(d, 1).inputs == d.inputs);
  CHECK(sysid::SubsampleRows(d, 0).size() == 7);
  CHECK(sysid::SubsampleRows(d, 8).size() == 1);
}
