// The C++ side of the Python binding-overhead ratio (bench/run_python.sh): dominance analysis of
// recordings already in memory, one after another on one thread, best of R passes.
//
//   bench_dominance MODEL.json REC.csv... [--repeats R]
// Prints one line "cpp_seconds_per_pass S recordings N" for bench/bench_python.py to read.
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <string>
#include <vector>

#include "sysid/dominance.hpp"
#include "sysid/io.hpp"
#include "sysid/model.hpp"

int main(int argc, char** argv) {
  int repeats = 20;
  std::vector<std::string> files;
  std::string model_path;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--repeats" && i + 1 < argc) {
      repeats = std::max(1, std::atoi(argv[++i]));
    } else if (model_path.empty()) {
      model_path = arg;
    } else {
      files.push_back(arg);
    }
  }
  if (model_path.empty() || files.empty()) {
    fmt::print(stderr, "usage: bench_dominance MODEL.json REC.csv... [--repeats R]\n");
    return 1;
  }
  const sysid::FrictionModel model = sysid::ReadModel(model_path);
  std::vector<sysid::Recording> recs;
  for (const auto& f : files) recs.push_back(sysid::ReadRecording(f));
  sysid::DominanceOptions options;
  options.threads = 1;
  double best = 1e300, sink = 0;
  for (int r = 0; r < repeats; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    for (const auto& rec : recs) sink += sysid::AnalyzeDominance(model, rec, options).margin;
    best = std::min(best,
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  fmt::print("cpp_seconds_per_pass {:.9g} recordings {} (checksum {:.6g})\n", best, recs.size(),
             sink);
  return 0;
}
