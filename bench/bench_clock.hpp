// What the benchmarks share: CPU time of a clock, the best wall time of repeats, and the
// machine's load average, which every benchmark prints beside its ratios (the machine is
// shared; docs/benchmarks.md).
#ifndef SYSID_BENCH_BENCH_CLOCK_HPP_
#define SYSID_BENCH_BENCH_CLOCK_HPP_

#include <fmt/format.h>
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>

namespace sysid::bench {

/// [s] CPU time of `clock` (CLOCK_THREAD_CPUTIME_ID: this thread; CLOCK_PROCESS_CPUTIME_ID).
inline double CpuSeconds(clockid_t clock = CLOCK_THREAD_CPUTIME_ID) {
  timespec ts{};
  clock_gettime(clock, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

/// [s] The shortest wall time of `repeats` calls of fn().
template <class F>
double BestWallSeconds(int repeats, F&& fn) {
  double best = 1e300;
  for (int r = 0; r < repeats; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    fn();
    best = std::min(best,
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  return best;
}

/// The first three fields of /proc/loadavg ("?" where there is none).
inline std::string LoadAverage() {
  std::FILE* f = std::fopen("/proc/loadavg", "r");
  if (!f) return "?";
  double l1 = 0, l5 = 0, l15 = 0;
  const int n = std::fscanf(f, "%lf %lf %lf", &l1, &l5, &l15);
  std::fclose(f);
  return n == 3 ? fmt::format("{:.2f} {:.2f} {:.2f}", l1, l5, l15) : "?";
}

}  // namespace sysid::bench

#endif  // SYSID_BENCH_BENCH_CLOCK_HPP_
