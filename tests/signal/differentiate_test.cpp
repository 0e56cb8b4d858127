// Differentiate(): method names, option rules, and each method on a sine against the bound
// that follows from it (details of each bound in the per-method tests).
#include <catch2/catch.hpp>

#include "signal_test_util.hpp"
#include "sysid/error.hpp"
#include "sysid/signal.hpp"

using namespace sysid;
using namespace sysid::test;

TEST_CASE("derivative method names round-trip", "[signal][options]") {
  for (auto m : {DerivativeMethod::kCentral, DerivativeMethod::kButterworthCentral,
                 DerivativeMethod::kSavitzkyGolay})
    CHECK(ParseDerivativeMethod(ToString(m)) == m);
  CHECK_THROWS_WITH(ParseDerivativeMethod("lanczos"),
                    Catch::Contains("'lanczos' is unknown; expected one of: central, "
                                    "butterworth, savgol"));
}

TEST_CASE("DerivativeOptions::Validate checks only what the method uses", "[signal][options]") {
  DerivativeOptions o;
  o.cutoff_hz = 900;  // above Nyquist at 1 kHz, but central differences do not use it
  CHECK_NOTHROW(o.Validate(1e-3));
  o.method = DerivativeMethod::kButterworthCentral;
  CHECK_THROWS_WITH(o.Validate(1e-3), Catch::Contains("cutoff_hz = 900 Hz"));
  o.cutoff_hz = 50;
  o.butterworth_order = 0;
  CHECK_THROWS_WITH(o.Validate(1e-3),
                    Catch::Contains("butterworth_order = 0. Violated constraint: 1 <= "
                                    "butterworth_order <= 20"));
  o.method = DerivativeMethod::kSavitzkyGolay;
  o.savgol_window = 8;
  CHECK_THROWS_WITH(o.Validate(1e-3), Catch::Contains("savgol_window = 8"));
  CHECK_THROWS_WITH(DerivativeOptions{}.Validate(-1e-3), Catch::Contains("dt_s = -0.001 s"));
}

TEST_CASE("every method differentiates a sine within its bound", "[signal][differentiate]") {
  const double amp = 0.02, w = 2 * kPi * 1.5, dt = 1e-3;
  const Eigen::Index n = 3000, skip = 400;
  const auto x = Sample([&](double t) { return amp * std::sin(w * t); }, n, dt);
  const auto v_ref = Sample([&](double t) { return amp * w * std::cos(w * t); }, n, dt);
  const auto a_ref = Sample([&](double t) { return -amp * w * w * std::sin(w * t); }, n, dt);
  const double m3 = amp * std::pow(w, 3), m4 = amp * std::pow(w, 4);
  SECTION("central") {
    const Derivatives d = Differentiate(x, dt);
    CHECK(d.x_m == x);
    CHECK(MaxError(d.v_mps, v_ref, 1, n - 1) <= dt * dt / 6 * m3);
    CHECK(MaxError(d.a_mps2, a_ref, 2, n - 2) <= dt * dt / 3 * m4);
  }
  SECTION("butterworth") {
    DerivativeOptions o;
    o.method = DerivativeMethod::kButterworthCentral;
    o.cutoff_hz = 30;
    const Derivatives d = Differentiate(x, dt, o);
    const double g = ButterworthGain2(w * dt, o.cutoff_hz * dt, o.butterworth_order);
    // Steady state after the transients (pole radius ~0.96, skip 400): gain g, zero phase.
    CHECK(MaxError(d.x_m, g * x, skip, n - skip) < 1e-12);
    CHECK(MaxError(d.v_mps, v_ref, skip, n - skip) <= (1 - g) * amp * w + dt * dt / 6 * m3 + 1e-12);
    CHECK(MaxError(d.a_mps2, a_ref, skip, n - skip) <=
          (1 - g) * amp * w * w + dt * dt / 3 * m4 + 1e-9);
  }
  SECTION("savgol") {
    DerivativeOptions o;
    o.method = DerivativeMethod::kSavitzkyGolay;
    o.savgol_window = 51;
    o.savgol_order = 4;
    const Derivatives d = Differentiate(x, dt, o);
    // The accuracy of the fit is tested in savitzky_golay_test.cpp; here: the wiring.
    CHECK(d.x_m == SavitzkyGolay(x, dt, 51, 4, 0));
    CHECK(d.v_mps == SavitzkyGolay(x, dt, 51, 4, 1));
    CHECK(d.a_mps2 == SavitzkyGolay(x, dt, 51, 4, 2));
  }
}
