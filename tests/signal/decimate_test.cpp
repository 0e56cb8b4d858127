// Decimation against the closed-form anti-alias response: a pass-band sine keeps |H|^2 of its
// amplitude, a sine above the new Nyquist frequency (which would alias) is cut to |H|^2.
#include <catch2/catch.hpp>

#include "signal_test_util.hpp"
#include "sysid/error.hpp"
#include "sysid/signal.hpp"

using namespace sysid;
using namespace sysid::test;

TEST_CASE("decimate keeps pass-band sines and suppresses aliases by |H|^2", "[signal][decimate]") {
  const double dt = 1e-3;
  const int factor = 4;  // 1 kHz -> 250 Hz, anti-alias cut-off 0.8 x 125 Hz = 100 Hz
  const Eigen::Index n = 4001;
  const double fc_over_fs = kDecimateCutoffFraction * 0.5 / factor;
  for (double f : {5.0, 60.0, 200.0, 310.0}) {
    const double w = 2 * kPi * f;
    const auto y = Sample([&](double t) { return std::sin(w * t + 0.2); }, n, dt);
    const Eigen::VectorXd out = Decimate(y, dt, factor);
    REQUIRE(out.size() == (n + factor - 1) / factor);
    const double g = ButterworthGain2(w * dt, fc_over_fs, kDecimateButterworthOrder);
    // Sampling the zero-phase steady state g sin(w t + 0.2) at t = i factor dt (for 200 and
    // 310 Hz this is the aliased sine, attenuated by g ~ 3e-6 and ~1e-11).
    const auto ref =
        Sample([&](double t) { return g * std::sin(w * t + 0.2); }, out.size(), factor * dt);
    INFO("f = " << f << " Hz, |H|^2 = " << g);
    // Interior only: transients decay as the largest pole radius (0.93 at fc/fs = 0.1)^k,
    // below 1e-13 after 600 input samples = 150 output samples.
    CHECK(MaxError(out, ref, 150, out.size() - 150) < 1e-12);
  }
  // The pass band is flat: 5 Hz keeps its amplitude to 1e-12, and 200 Hz is attenuated > 100 dB.
  CHECK(ButterworthGain2(2 * kPi * 5.0 * dt, fc_over_fs, kDecimateButterworthOrder) > 1 - 1e-12);
  CHECK(ButterworthGain2(2 * kPi * 200.0 * dt, fc_over_fs, kDecimateButterworthOrder) < 1e-5);
}

TEST_CASE("decimate keeps the first sample, factor 1 is the identity", "[signal][decimate]") {
  const Eigen::VectorXd y = Eigen::VectorXd::Constant(103, 2.5);
  const Eigen::VectorXd out = Decimate(y, 1e-3, 10);
  CHECK(out.size() == 11);
  // A constant passes the steady-state-initialised filter without any transient; what is
  // left is rounding in 2 x 4 resonant sections.
  CHECK((out.array() - 2.5).abs().maxCoeff() < 1e-12);
  const Eigen::VectorXd ramp = Eigen::VectorXd::LinSpaced(50, 0, 1);
  CHECK(Decimate(ramp, 1e-3, 1) == ramp);
  CHECK_THROWS_WITH(Decimate(ramp, 1e-3, 0),
                    Catch::Contains("factor = 0. Violated constraint: factor >= 1"));
  CHECK_THROWS_AS(Decimate(ramp.head(20), 1e-3, 2), InputError);  // order 8 pads 3 x 9 = 27
}
