// Butterworth design and zero-phase filtering against the closed-form |H|^2 of the bilinear
// Butterworth, a steady-state sine (gain |H|^2, zero phase), and SciPy's published values.
#include <catch2/catch.hpp>
#include <complex>

#include "signal/filters.hpp"
#include "signal_test_util.hpp"
#include "sysid/error.hpp"
#include "sysid/signal.hpp"

using namespace sysid;
using namespace sysid::test;

namespace {

// Coefficients of the product of the sections' numerators and denominators (highest power of
// z^-1 last), to compare with a transfer-function design.
std::pair<std::vector<double>, std::vector<double>> Polynomials(
    const std::vector<internal::Biquad>& sections) {
  std::vector<double> b{1.0}, a{1.0};
  auto multiply = [](const std::vector<double>& p, std::vector<double> q) {
    while (!q.empty() && q.back() == 0.0) q.pop_back();
    std::vector<double> r(p.size() + q.size() - 1, 0.0);
    for (size_t i = 0; i < p.size(); ++i)
      for (size_t j = 0; j < q.size(); ++j) r[i + j] += p[i] * q[j];
    return r;
  };
  for (const auto& s : sections) {
    b = multiply(b, {s.b0, s.b1, s.b2});
    a = multiply(a, {1.0, s.a1, s.a2});
  }
  return {b, a};
}

}  // namespace

TEST_CASE("Butterworth sections have the closed-form magnitude response", "[signal][butter]") {
  for (int order = 1; order <= 10; ++order) {
    for (double fc : {0.01, 0.05, 0.2, 0.45}) {
      const auto sections = internal::DesignButterworthLowPass(order, fc);
      CHECK(static_cast<int>(sections.size()) == (order + 1) / 2);
      for (double omega : {0.0, 0.3 * kPi * fc, 2 * kPi * fc, 1.7 * kPi * fc, 0.9 * kPi}) {
        const double h2 = std::norm(internal::FrequencyResponse(sections, omega));
        // Same quantity through two formulas: relative rounding of a product of <= 10 factors.
        CHECK(h2 == Approx(ButterworthGain2(omega, fc, order)).epsilon(1e-9).margin(1e-300));
      }
      // Half power at the cut-off for every order (the Butterworth definition).
      CHECK(std::norm(internal::FrequencyResponse(sections, 2 * kPi * fc)) ==
            Approx(0.5).epsilon(1e-10));
      for (const auto& s : sections) {  // stable: poles inside the unit circle
        const std::complex<double> disc = std::sqrt(std::complex<double>(s.a1 * s.a1 - 4 * s.a2));
        CHECK(std::abs((-s.a1 + disc) / 2.0) < 1.0);
        CHECK(std::abs((-s.a1 - disc) / 2.0) < 1.0);
      }
    }
  }
}

TEST_CASE("Butterworth design matches scipy.signal.butter", "[signal][butter]") {
  // Provenance: SciPy 1.10.1, scipy.signal.butter(N, Wn) with Wn relative to Nyquist, i.e.
  // fc/fs = Wn/2; printed with repr().
  struct Case {
    int order;
    double wn;
    std::vector<double> b, a;
  };
  const std::vector<Case> cases{
      {4,
       0.2,
       {0.004824343357716228, 0.019297373430864913, 0.02894606014629737, 0.019297373430864913,
        0.004824343357716228},
       {1.0, -2.369513007182038, 2.3139884144158804, -1.054665405878568, 0.18737949236818502}},
      {5,
       0.3,
       {0.006933196130142604, 0.034665980650713024, 0.06933196130142605, 0.06933196130142605,
        0.034665980650713024, 0.006933196130142604},
       {1.0, -1.9759016164414662, 2.0134730260003075, -1.1026179777777698, 0.3276183340001567,
        -0.04070948961666521}}};
  for (const auto& c : cases) {
    const auto [b, a] = Polynomials(internal::DesignButterworthLowPass(c.order, c.wn / 2));
    REQUIRE(b.size() == c.b.size());
    REQUIRE(a.size() == c.a.size());
    for (size_t i = 0; i < b.size(); ++i) {
      // Different factorisations (sections vs. zpk) of the same polynomials: a few ulps.
      CHECK(b[i] == Approx(c.b[i]).epsilon(1e-12));
      CHECK(a[i] == Approx(c.a[i]).epsilon(1e-12));
    }
  }
}

TEST_CASE("filtfilt passes a sine with gain |H|^2 and zero phase", "[signal][butter]") {
  const double dt = 1e-3, fc = 50.0;
  const int order = 4;
  const Eigen::Index n = 4000;
  for (double f : {5.0, 40.0, 50.0, 80.0}) {
    const double w = 2 * kPi * f;
    const auto y = Sample([&](double t) { return std::sin(w * t + 0.3); }, n, dt);
    const Eigen::VectorXd out = ButterworthFiltFilt(y, dt, fc, order);
    const double g = ButterworthGain2(w * dt, fc * dt, order);
    // Away from the ends the start-up transients have decayed (pole radius <= 0.93 here, so
    // 0.93^500 ~ 1e-16): only the steady state g sin(wt + 0.3) remains, with no phase shift.
    CHECK(MaxError(out, g * y, 500, n - 500) < 1e-12);
  }
}

TEST_CASE("filtfilt keeps constants and ramps exactly in the interior", "[signal][butter]") {
  const double dt = 1e-3;
  const Eigen::Index n = 1000;
  // Steady-state initial conditions: a constant produces no transient at all.
  const Eigen::VectorXd c = Eigen::VectorXd::Constant(n, 0.0123);
  CHECK(MaxError(ButterworthFiltFilt(c, dt, 20.0, 6), c, 0, n) < 1e-15);
  // Zero phase means |H|^2 is flat to second order at DC, so a ramp passes unchanged once the
  // start-up transient (the initial state assumes a constant, not a ramp) has decayed:
  // largest pole radius 0.968 at fc/fs = 0.02, and 0.968^1000 ~ 1e-14 of a ~1e-3 transient.
  const Eigen::Index m = 3000;
  const auto ramp = Sample([](double t) { return 0.002 + 0.05 * t; }, m, dt);
  CHECK(MaxError(ButterworthFiltFilt(ramp, dt, 20.0, 6), ramp, 1000, m - 1000) < 1e-13);
}

TEST_CASE("filtfilt matches scipy.signal.sosfiltfilt including the padded ends",
          "[signal][butter]") {
  // Provenance: SciPy 1.10.1, y_k = sin(0.3 k) + 0.1 k, k = 0..39,
  // scipy.signal.sosfiltfilt(scipy.signal.butter(3, 0.25, output='sos'), y) (odd padding,
  // padlen 3 x (2 x 2 + 1 - 1) = 12, sosfilt_zi initial conditions).
  const auto y = Sample([](double k) { return std::sin(0.3 * k) + 0.1 * k; }, 40, 1.0);
  const Eigen::VectorXd out = ButterworthFiltFilt(y, 1.0, 0.125, 3);
  const std::vector<std::pair<int, double>> expected{
      {0, 0.0007938024222916701}, {1, 0.3953400125624193}, {5, 1.495018179263969},
      {20, 1.7213043197312947},   {38, 2.914535928299137}, {39, 3.1389895801210104}};
  for (const auto& [k, value] : expected)
    CHECK(out[k] == Approx(value).margin(1e-12));  // same LTI filter, different factorisation
}

TEST_CASE("Butterworth then central difference: bias and noise as predicted", "[signal][butter]") {
  // A stage moving one way at 0.06..0.14 m/s with a 7 Hz ripple: the encoder (q = 1 um at
  // 1 kHz) advances 60..140 counts per sample, so its rounding error is close to white.
  const double dt = 1e-3, fc = 50.0, amp = 0.001, w = 2 * kPi * 7.0, q = 1e-6;
  const int order = 4;
  const Eigen::Index n = 20000;
  const auto x = Sample([&](double t) { return amp * std::sin(w * t) + 0.1 * t; }, n, dt);
  const auto v_ref = Sample([&](double t) { return amp * w * std::cos(w * t) + 0.1; }, n, dt);
  DerivativeOptions opt;
  opt.method = DerivativeMethod::kButterworthCentral;
  opt.cutoff_hz = fc;
  opt.butterworth_order = order;
  const Derivatives clean = Differentiate(x, dt, opt);
  // Clean: the sine loses (1 - |H|^2) of its amplitude, then the difference adds h^2/6 y'''.
  const double g = ButterworthGain2(w * dt, fc * dt, order);
  const double bias = (1 - g) * amp * w + dt * dt / 6 * amp * std::pow(w, 3);
  CHECK(MaxError(clean.v_mps, v_ref, 500, n - 500) <= bias * 1.001 + 1e-15);

  // Quantised: the difference of the two outputs is the rounding error e (|e| <= q/2) through
  // the linear map g = D o filtfilt, so |difference| <= (q/2) sum_k |g_k|. g from the closed
  // form: g_k = -(1/(pi h)) int_0^pi |H(w)|^2 sin(w) sin(k w) dw (D has response j sin(w)/h).
  const Derivatives noisy = Differentiate(Quantize(x, q), dt, opt);
  const Eigen::VectorXd diff = (noisy.v_mps - clean.v_mps).segment(500, n - 1000);
  double g_l1 = 0;
  const int steps = 8000;
  for (int k = 1; k <= 400; ++k) {  // |g_k| ~ pole radius^k: beyond 400 it is below 1e-8 of g_1
    double integral = 0;
    for (int i = 0; i < steps; ++i) {  // midpoint rule: smooth periodic integrand, converges fast
      const double om = kPi * (i + 0.5) / steps;
      integral += ButterworthGain2(om, fc * dt, order) * std::sin(om) * std::sin(k * om);
    }
    g_l1 += 2 * std::abs(integral / steps / dt);  // g is odd: g_-k = -g_k, g_0 = 0
  }
  const double noise_bound = q / 2 * g_l1;
  const double worst = diff.cwiseAbs().maxCoeff();
  CHECK(worst <= noise_bound);
  CHECK(worst > 0.1 * noise_bound);  // the bound is not vacuous for real rounding noise
  // Far below the raw central difference's worst case q/(2h) (the reason to filter).
  CHECK(worst < 0.1 * q / (2 * dt));
}

TEST_CASE("Butterworth options are checked", "[signal][butter]") {
  const Eigen::VectorXd y = Eigen::VectorXd::Zero(100);
  CHECK_THROWS_WITH(ButterworthFiltFilt(y, 1e-3, 500.0, 4),
                    Catch::Contains("cutoff_hz = 500 Hz. Violated constraint: 0 < cutoff_hz < "
                                    "Nyquist frequency 0.5/dt_s = 500 Hz"));
  CHECK_THROWS_AS(ButterworthFiltFilt(y, 1e-3, 50.0, 0), OptionsError);
  CHECK_THROWS_AS(ButterworthFiltFilt(y, 1e-3, 50.0, kMaxButterworthOrder + 1), OptionsError);
  // Order 4: 2 sections, padding 3 x 5 = 15, so 15 samples are too few and 16 enough.
  CHECK_THROWS_WITH(ButterworthFiltFilt(y.head(15), 1e-3, 50.0, 4),
                    Catch::Contains("has 15 samples") && Catch::Contains("at least 16"));
  CHECK_NOTHROW(ButterworthFiltFilt(y.head(16), 1e-3, 50.0, 4));
  // A cut-off 2e-13 of Nyquist: the sections round to a NaN output, reported with the cure.
  const Eigen::VectorXd ramp = Eigen::VectorXd::LinSpaced(100, 0.0, 1e-3);
  CHECK_THROWS_WITH(ButterworthFiltFilt(ramp, 1e-3, 1e-10, 4),
                    Catch::Contains("numerically unstable") &&
                        Catch::Contains("raise the cut-off"));
  CHECK(ButterworthFiltFilt(ramp, 1e-3, 1.0, 4).allFinite());
}
