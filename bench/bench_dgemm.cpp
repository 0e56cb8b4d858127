// The machine's Eigen dgemm rate, the yardstick of bench_nn's kernel GFLOP/s: C = A B with
// 512 x 2048 x 512 operands, on 1 thread and on T threads (each its own product, as Eigen is
// built without OpenMP here), median of repeats. Compiled with -mavx2 -mfma on x86-64
// (bench/CMakeLists.txt), so it measures the best the CPU does; bench/run_nn.sh runs it only
// when /proc/cpuinfo lists avx2 and fma.
//   bench_dgemm [--threads T] [--repeats R]
#include <Eigen/Core>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

namespace {

double RateGflops(int threads, int repeats) {
  const int m = 512, k = 2048, n = 512;
  std::vector<Eigen::MatrixXd> A, B, C;
  for (int t = 0; t < threads; ++t) {
    A.push_back(Eigen::MatrixXd::Random(m, k));
    B.push_back(Eigen::MatrixXd::Random(k, n));
    C.push_back(Eigen::MatrixXd::Zero(m, n));
  }
  std::vector<double> times;
  for (int r = 0; r < repeats; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    std::vector<std::thread> pool;
    for (int t = 1; t < threads; ++t) pool.emplace_back([&, t] { C[t].noalias() = A[t] * B[t]; });
    C[0].noalias() = A[0] * B[0];
    for (auto& th : pool) th.join();
    times.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  std::sort(times.begin(), times.end());
  return 2.0 * m * k * n * threads / times[times.size() / 2] / 1e9;
}

}  // namespace

int main(int argc, char** argv) {
  int threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  int repeats = 7;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string key = argv[i];
    if (key == "--threads") threads = std::max(1, std::stoi(argv[i + 1]));
    if (key == "--repeats") repeats = std::max(1, std::stoi(argv[i + 1]));
  }
  const double one = RateGflops(1, repeats);
  const double all = RateGflops(threads, repeats);
  std::printf(
      "{\"what\":\"eigen_dgemm\",\"simd\":\"%s\",\"threads\":%d,\"gflops_1\":%.3f,"
      "\"gflops_all\":%.3f}\n",
#ifdef __AVX2__
      "avx2+fma",
#else
      "default",
#endif
      threads, one, all);
  return 0;
}
