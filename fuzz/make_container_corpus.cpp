// Writes the MAT and HDF5 seed files of the fuzz corpus (fuzz/corpus/) with the same fixtures
// the tests use (tests/io/container_fixtures.hpp):
//   fuzz_make_container_corpus fuzz/corpus
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include "io/container_fixtures.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: fuzz_make_container_corpus DIR\n";
    return 1;
  }
  using namespace sysid::test;
  const std::string dir = argv[1];
  std::vector<double> t(16), u(16), x(16);
  for (size_t i = 0; i < t.size(); ++i) {
    t[i] = 0.01 * static_cast<double>(i);
    u[i] = std::sin(static_cast<double>(i));
    x[i] = 1e-3 * std::cos(static_cast<double>(i));
  }
  const std::vector<MatArray> arrays{{"t", 16, 1, t}, {"u", 1, 16, u}, {"x", 1, 16, x}};
  WriteMat(dir + "/small_v5.mat", MatVersion::kV5, arrays);
  WriteMat(dir + "/small_v5z.mat", MatVersion::kV5Compressed, arrays);
  WriteMat(dir + "/small_v73.mat", MatVersion::kV73, arrays);
  WriteControlDesk(dir + "/controldesk.mat", MatVersion::kV5, "capture", t, {"u", "x"}, {u, x});
  WriteH5(dir + "/small.h5", {{"/t", {16}, t}, {"/rec/u", {16, 1}, u}, {"/rec/x", {16}, x}});
  // Structure-aware seeds: the layouts the container policy refuses or bounds
  // (libsysid/src/io/container_policy.hpp), small enough to mutate quickly.
  WriteH5Virtual(dir + "/virtual.h5", "virtual.h5", "u");
  WriteH5External(dir + "/external.h5", "/etc/passwd");
  WriteH5HardLinks(dir + "/links.h5", 100, 20);
  WriteH5DeepGroups(dir + "/deep.h5", 40);
  WriteH5Null(dir + "/null.h5");
  WriteMat73Hostile(dir + "/selfref_v73.mat", Mat73Hostile::kSelfReference);
  WriteMatNestedStructs(dir + "/deep_v73.mat", MatVersion::kV73, 40);
  WriteMatNestedStructs(dir + "/deep_v5.mat", MatVersion::kV5, 40);
  WriteMatEmptyCells(dir + "/cells_v5z.mat", 200000);
  return 0;
}
