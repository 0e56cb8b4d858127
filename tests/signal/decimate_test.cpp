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

TEST_CASE("a decimated recording: t subsampled exactly, each other column as its closed form",
          "[signal][decimate]") {
  // Columns t [s], u = 2.5 V (a constant) and x = 1e-3 sin(2 pi 5 t + 0.2) [m] at 1 kHz;
  // factor 4. The independent references: t_i = 4 i dt exactly, u stays 2.5, and x is the
  // steady state |H|^2 x(t_i) of the zero-phase anti-alias filter (closed-form gain).
  const double dt = 1e-3;
  const int factor = 4;
  const Eigen::Index n = 2001;
  const double w = 2 * kPi * 5.0;
  Recording rec;
  rec.source = "closed-form.csv";
  rec.metadata = {{"units", "t [s], u [V], x [m]"}};
  rec.SetColumn("t", Sample([](double t) { return t; }, n, dt));
  rec.SetColumn("u", Eigen::VectorXd::Constant(n, 2.5));
  rec.SetColumn("x", Sample([&](double t) { return 1e-3 * std::sin(w * t + 0.2); }, n, dt));
  const Recording out = DecimateRecording(rec, dt, factor);
  const Eigen::Index m = (n + factor - 1) / factor;
  REQUIRE(out.rows() == m);
  CHECK(out.names == rec.names);
  CHECK(out.source == rec.source);
  CHECK(out.metadata == rec.metadata);
  for (Eigen::Index i = 0; i < m; ++i) CHECK(out.column("t")[i] == rec.column("t")[i * factor]);
  CHECK((out.column("u").array() - 2.5).abs().maxCoeff() < 1e-12);
  const double g = ButterworthGain2(w * dt, kDecimateCutoffFraction * 0.5 / factor,
                                    kDecimateButterworthOrder);
  const auto ref =
      Sample([&](double t) { return g * 1e-3 * std::sin(w * t + 0.2); }, m, factor * dt);
  CHECK(MaxError(out.column("x"), ref, 150, m - 150) < 1e-14);
  // Bad factors name the field (OptionsError::field), so callers need not parse messages.
  try {
    DecimateRecording(rec, dt, 0);
    FAIL("factor 0 accepted");
  } catch (const OptionsError& e) {
    CHECK(e.field() == "factor");
  }
}

TEST_CASE("derivative option errors name their field", "[signal][decimate]") {
  DerivativeOptions o;
  o.method = DerivativeMethod::kButterworthCentral;
  o.cutoff_hz = 600;  // above Nyquist at 1 kHz
  auto field = [](const DerivativeOptions& options) {
    try {
      options.Validate(1e-3);
    } catch (const OptionsError& e) {
      return e.field();
    }
    return std::string("none");
  };
  CHECK(field(o) == "cutoff_hz");
  o.cutoff_hz = 50;
  o.butterworth_order = 0;
  CHECK(field(o) == "butterworth_order");
  o.method = DerivativeMethod::kSavitzkyGolay;
  o.savgol_window = 4;
  CHECK(field(o) == "savgol_window");
  o.savgol_window = 21;
  o.savgol_order = 1;
  CHECK(field(o) == "savgol_order");
}
