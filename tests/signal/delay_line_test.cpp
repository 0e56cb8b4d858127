// The streaming delay line against a hand-worked table and against DelaySignal's rule written
// out independently (linear interpolation, the first sample held before the record).
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "sysid/error.hpp"
#include "sysid/signal.hpp"

TEST_CASE("DelayLine: a hand-worked table at 2.5 samples", "[signal][delay][stream]") {
  // dt = 0.5 s, tau = 1.25 s: w = 2, f = 0.5, both exact in binary.
  sysid::DelayLine line(0.5, 1.25);
  CHECK(line.whole_samples() == 2);
  CHECK(line.fraction() == 0.5);
  const double y[] = {1, 2, 4, 8, 16, 32};
  // y(t_k - tau) = (y[k-2] + y[k-3]) / 2 with y[j < 0] = y[0] = 1.
  const double expected[] = {1, 1, 1, 1.5, 3, 6};
  for (int k = 0; k < 6; ++k) CHECK(line.Push(y[k]) == expected[k]);
  line.Reset();  // the history is gone: the next sample is the first one again
  CHECK(line.Push(10) == 10);
  CHECK(line.Push(20) == 10);
}

TEST_CASE("DelayLine follows the interpolation rule and DelaySignal at any delay", "[signal][delay][stream]") {
  const double dt = 1e-3;
  std::vector<double> y(300);
  for (size_t k = 0; k < y.size(); ++k) y[k] = std::sin(0.05 * static_cast<double>(k)) + 0.01 * k;
  for (double tau : {0.0, 0.4e-3, 1e-3, 3.5e-3, 37.25e-3, 0.5}) {
    sysid::DelayLine line(dt, tau);
    Eigen::VectorXd signal(static_cast<Eigen::Index>(y.size()));
    for (size_t k = 0; k < y.size(); ++k) signal[static_cast<Eigen::Index>(k)] = y[k];
    const Eigen::VectorXd batch = sysid::DelaySignal(signal, dt, tau);
    const double shift = tau / dt;
    const auto w = static_cast<long long>(std::floor(shift));
    const double f = shift - static_cast<double>(w);
    auto at = [&](long long j) { return y[static_cast<size_t>(j < 0 ? 0 : j)]; };
    for (long long k = 0; k < static_cast<long long>(y.size()); ++k) {
      INFO("tau = " << tau << ", k = " << k);
      // Same expression as the rule: bit-identical.
      const double pushed = line.Push(y[static_cast<size_t>(k)]);
      CHECK(pushed == (1 - f) * at(k - w) + f * at(k - w - 1));
      CHECK(pushed == batch[static_cast<Eigen::Index>(k)]);  // the batch form, bit for bit
    }
  }
}

TEST_CASE("DelayLine refuses what it cannot hold", "[signal][delay][stream]") {
  CHECK_THROWS_AS(sysid::DelayLine(0.0, 1e-3), sysid::OptionsError);
  CHECK_THROWS_AS(sysid::DelayLine(1e-3, -1e-3), sysid::OptionsError);
  CHECK_THROWS_AS(sysid::DelayLine(1e-9, 10.0), sysid::OptionsError);  // 1e10 samples
  // A batch of 5 samples needs no more than 5 of them, whatever the delay.
  sysid::DelayLine batch(1e-9, 10.0, 5);
  CHECK(batch.Push(3) == 3);
  CHECK(batch.Push(4) == 3);
}
