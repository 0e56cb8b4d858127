// The C++ side of the Python binding-overhead ratio (bench/run_python.sh): dominance analysis of
// recordings already in memory, one after another on one thread, best of R passes.
//
//   bench_dominance MODEL.json REC.csv... [--repeats R]
// Prints one line "cpp_seconds_per_pass S recordings N" for bench/bench_python.py to read, then
// the buffer-reuse ratios, one thread, passes alternated so that both see the same load:
//  - in memory: AnalyzeDominance (fresh buffers per recording) vs one DominanceWorkspace;
//  - from the files: ReadRecording + AnalyzeDominance per file (before) vs one RecordingReader
//    and one DominanceWorkspace (what a sysid.batch chunk does), with and without glibc's
//    MALLOC_TRIM_THRESHOLD_ as a Dask nanny sets it (run it with the variable set to see it).
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

  auto time = [](auto&& pass) {
    const auto t0 = std::chrono::steady_clock::now();
    pass();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  double fresh = 1e300, reused = 1e300, files_fresh = 1e300, files_reused = 1e300;
  double sum_fresh = 0, sum_reused = 0;
  for (int r = 0; r < repeats; ++r) {
    fresh = std::min(fresh, time([&] {
                       for (const auto& rec : recs)
                         sum_fresh += sysid::AnalyzeDominance(model, rec, options).margin;
                     }));
    reused = std::min(reused, time([&] {
                        sysid::DominanceWorkspace workspace;
                        for (const auto& rec : recs)
                          sum_reused +=
                              sysid::AnalyzeDominance(model, rec, options, &workspace).margin;
                      }));
    files_fresh = std::min(
        files_fresh, time([&] {
          for (const auto& f : files)
            sum_fresh += sysid::AnalyzeDominance(model, sysid::ReadRecording(f), options).margin;
        }));
    files_reused =
        std::min(files_reused, time([&] {
                   sysid::RecordingReader reader;
                   sysid::DominanceWorkspace workspace;
                   for (const auto& f : files)
                     sum_reused +=
                         sysid::AnalyzeDominance(model, reader.Read(f), options, &workspace).margin;
                 }));
  }
  const char* trim = std::getenv("MALLOC_TRIM_THRESHOLD_");
  fmt::print("in memory: fresh buffers {:.6f} s, one workspace {:.6f} s: {:.3f}x\n", fresh, reused,
             fresh / reused);
  fmt::print(
      "from files: ReadRecording per file {:.6f} s, one reader + workspace {:.6f} s: {:.3f}x"
      " (MALLOC_TRIM_THRESHOLD_={}; same results: {})\n",
      files_fresh, files_reused, files_fresh / files_reused, trim ? trim : "unset",
      sum_fresh == sum_reused);
  return 0;
}
