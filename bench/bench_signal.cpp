// Throughput of the derivative methods in samples/s beside a naive baseline (a plain loop of
// central differences over std::vector, v and a), in one process.
//
//   bench_signal [--samples N] [--repeats R]
// The signal is a quantised (1 um) 1 kHz position: 0.1 t + 5 mm sin(2 pi 2 t).
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <string>
#include <vector>

#include "sysid/signal.hpp"

namespace {

double BestSeconds(int repeats, const std::function<double()>& run, double& sink) {
  double best = 1e300;
  for (int r = 0; r < repeats; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    sink += run();
    best = std::min(best,
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  return best;
}

}  // namespace

int main(int argc, char** argv) {
  long samples = 2'000'000;
  int repeats = 5;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string arg = argv[i];
    if (arg == "--samples") samples = std::atol(argv[i + 1]);
    if (arg == "--repeats") repeats = std::atoi(argv[i + 1]);
  }
  const double dt = 1e-3, q = 1e-6, pi = std::acos(-1.0);
  Eigen::VectorXd x(samples);
  for (long k = 0; k < samples; ++k) {
    const double t = static_cast<double>(k) * dt;
    x[k] = q * std::round((0.1 * t + 5e-3 * std::sin(2 * pi * 2 * t)) / q);
  }
  const std::vector<double> xs(x.data(), x.data() + samples);
  double sink = 0;

  // Baseline: v and a by plain central-difference loops (interior only, no checks).
  const double base = BestSeconds(
      repeats,
      [&] {
        std::vector<double> v(xs.size()), a(xs.size());
        for (size_t k = 1; k + 1 < xs.size(); ++k) v[k] = (xs[k + 1] - xs[k - 1]) / (2 * dt);
        for (size_t k = 2; k + 2 < xs.size(); ++k) a[k] = (v[k + 1] - v[k - 1]) / (2 * dt);
        return v[samples / 2] + a[samples / 2];
      },
      sink);

  struct Case {
    std::string name;
    std::function<double()> run;
  };
  auto derive = [&](sysid::DerivativeOptions o) {
    return [&x, dt, o] {
      const sysid::Derivatives d = sysid::Differentiate(x, dt, o);
      return d.v_mps[d.v_mps.size() / 2] + d.a_mps2[d.a_mps2.size() / 2];
    };
  };
  sysid::DerivativeOptions central, butter, savgol, savgol51;
  butter.method = sysid::DerivativeMethod::kButterworthCentral;
  savgol.method = savgol51.method = sysid::DerivativeMethod::kSavitzkyGolay;
  savgol51.savgol_window = 51;
  const std::vector<Case> cases{
      {"Differentiate central (v, a)", derive(central)},
      {"Differentiate butterworth order 4 (x, v, a)", derive(butter)},
      {"Differentiate savgol 21/3 (x, v, a)", derive(savgol)},
      {"Differentiate savgol 51/3 (x, v, a)", derive(savgol51)},
      {"Decimate by 10 (order-8 filtfilt)", [&] { return sysid::Decimate(x, dt, 10)[7]; }},
  };
  fmt::print("{} samples, best of {} runs\n", samples, repeats);
  fmt::print("{:<46} {:>10} {:>14} {:>10}\n", "method", "time [s]", "samples/s", "vs base");
  fmt::print("{:<46} {:>10.4f} {:>14.3e} {:>10}\n", "baseline: plain central-difference loops",
             base, samples / base, "1.00");
  for (const auto& c : cases) {
    const double s = BestSeconds(repeats, c.run, sink);
    fmt::print("{:<46} {:>10.4f} {:>14.3e} {:>9.2f}x\n", c.name, s, samples / s, base / s);
  }
  return sink == 12345.678 ? 1 : 0;  // keeps the work observable
}
