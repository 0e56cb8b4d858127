// Bouc–Wen simulation against independent references: a fixed-step RK4 at a tiny step (the
// CVODE paths, the piezo form's closed-form step), the benchmark's published test output (the
// benchmark chain), analytic band-limited signals (upsampling, input interpolation).
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "hysteresis/bouc_wen_internal.hpp"
#include "support/test_support.hpp"
#include "sysid/error.hpp"
#include "sysid/hysteresis_bouc_wen.hpp"
#include "sysid/hysteresis_stepper.hpp"
#include "sysid/io.hpp"

namespace sysid {
namespace {

// A multisine of `lines` harmonics (1..lines) of the period n dt, seeded phases, `rms_n` rms.
Eigen::VectorXd Multisine(Eigen::Index n, double dt, int first, int last, double amplitude,
                          double t_shift = 0, Eigen::VectorXd* derivative = nullptr) {
  Eigen::VectorXd u = Eigen::VectorXd::Zero(n);
  if (derivative) *derivative = Eigen::VectorXd::Zero(n);
  const double w0 = 2 * M_PI / (static_cast<double>(n) * dt);
  for (int l = first; l <= last; ++l) {
    // Deterministic "random" phases (golden angle), reduced so cos keeps its last digits.
    const double phase = std::fmod(2.39996 * l * l, 2 * M_PI);
    for (Eigen::Index i = 0; i < n; ++i) {
      const double t = static_cast<double>(i) * dt + t_shift;
      u[i] += amplitude * std::cos(w0 * l * t + phase);
      if (derivative) (*derivative)[i] -= amplitude * w0 * l * std::sin(w0 * l * t + phase);
    }
  }
  return u;
}

// Classic RK4 on x' = f(t, x, interval) with `sub` steps per sample interval; returns the first
// state component (or `out(x)`) at every sample.
Eigen::VectorXd Rk4(
    int states, Eigen::Index n, double dt, int sub,
    const std::function<void(double, Eigen::Index, const Eigen::VectorXd&, Eigen::VectorXd*)>& f,
    const std::function<double(Eigen::Index, const Eigen::VectorXd&)>& out) {
  Eigen::VectorXd x = Eigen::VectorXd::Zero(states), k1(states), k2(states), k3(states), k4(states);
  Eigen::VectorXd y(n);
  y[0] = out(0, x);
  const double h = dt / sub;
  for (Eigen::Index k = 0; k + 1 < n; ++k) {
    for (int j = 0; j < sub; ++j) {
      const double t = static_cast<double>(k) * dt + j * h;
      f(t, k, x, &k1);
      f(t + h / 2, k, x + h / 2 * k1, &k2);
      f(t + h / 2, k, x + h / 2 * k2, &k3);
      f(t + h, k, x + h * k3, &k4);
      x += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
    }
    y[k + 1] = out(k + 1, x);
  }
  return y;
}

Eigen::VectorXd MechanicalRk4(const MechanicalBoucWenParameters& p, const Eigen::VectorXd& u,
                              double dt, InputInterpolation how, int sub) {
  const internal::SampledInput input(u, dt, how);
  return Rk4(
      3, u.size(), dt, sub,
      [&](double t, Eigen::Index k, const Eigen::VectorXd& x, Eigen::VectorXd* d) {
        double uu, du;
        input.Evaluate(t, k, &uu, &du);
        // The equations written out again, not through MechanicalRate.
        const double v = x[1], z = x[2];
        (*d)[0] = v;
        (*d)[1] = (uu - p.c_n_s_per_m * v - p.k_n_per_m * x[0] - z) / p.m_kg;
        (*d)[2] = p.alpha_n_per_m * v -
                  p.beta_per_m * (p.gamma * std::abs(v) * std::pow(std::abs(z), p.nu - 1) * z +
                                  p.delta * v * std::pow(std::abs(z), p.nu));
      },
      [](Eigen::Index, const Eigen::VectorXd& x) { return x[0]; });
}

// A stack of 0.2 um/V with a loop of about 15 % of its stroke (invertible).
PiezoBoucWenParameters PiezoExample() {
  PiezoBoucWenParameters p;
  p.d_m_per_v = 2e-7;
  p.alpha = 0.3;
  p.beta_per_v = 0.04;
  p.gamma_per_v = 0.015;
  return p;
}

double RelativeMax(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return (a - b).cwiseAbs().maxCoeff() / b.cwiseAbs().maxCoeff();
}

// The RK4 reference at `sub` steps per sample, after checking its own error: RK4's order drops to
// 2 at the kinks of |y'| (velocity reversals), so its error is estimated by halving the step
// (err(h) ~ |y(h) - y(2h)| / 3) and must be well below the bound the test checks.
Eigen::VectorXd CheckedMechanicalRk4(const MechanicalBoucWenParameters& p, const Eigen::VectorXd& u,
                                     double dt, InputInterpolation how, int sub) {
  const Eigen::VectorXd fine = MechanicalRk4(p, u, dt, how, sub);
  const Eigen::VectorXd coarse = MechanicalRk4(p, u, dt, how, sub / 2);
  REQUIRE(RelativeMax(coarse, fine) / 3 <= 2e-9);  // the reference is 5x tighter than 1e-8
  return fine;
}

TEST_CASE("bouc-wen: CVODE against a tiny-step RK4 for held, linear and band-limited input",
          "[hysteresis][bouc-wen]") {
  MechanicalBoucWenParameters p;  // the benchmark's system
  const double dt = 1.0 / 750;
  const Eigen::Index n = 300;  // 0.4 s, dozens of velocity reversals
  const Eigen::VectorXd u = Multisine(n, dt, 3, 40, 15.0);
  for (auto how :
       {InputInterpolation::kHold, InputInterpolation::kLinear, InputInterpolation::kBandLimited}) {
    BoucWenSimulationOptions o;
    o.input = how;
    o.rtol = 1e-12;
    const Eigen::VectorXd y = MechanicalBoucWen(p, o).Simulate(u, dt);
    const Eigen::VectorXd ref = CheckedMechanicalRk4(p, u, dt, how, 4000);  // h = 0.33 us
    INFO("input " << static_cast<int>(how));
    CHECK(RelativeMax(y, ref) <= 1e-8);  // the acceptance bound of issue 25
  }
}

TEST_CASE("bouc-wen: the fixed step's step-doubling choice is within its tolerance of RK4",
          "[hysteresis][bouc-wen]") {
  // The benchmark's system on 160 samples at 750 Hz (a dozen velocity reversals), linear and
  // band-limited input: the steps per sample chosen for a tolerance of 1e-4 of the output's RMS
  // (the fit's default), then the fixed step at that count against the tiny-step RK4 reference.
  const MechanicalBoucWenParameters p;
  const double dt = 1.0 / 750;
  const Eigen::VectorXd u = Multisine(160, dt, 2, 20, 20.0);
  for (auto how : {InputInterpolation::kLinear, InputInterpolation::kBandLimited}) {
    const Eigen::VectorXd ref = CheckedMechanicalRk4(p, u, dt, how, 4000);
    const double rms = std::sqrt((ref.array() - ref.mean()).square().mean());
    const double tolerance = 1e-4 * rms;
    double estimate = 0;
    const int m = internal::ChooseFixedSteps(p, {{&u}, {dt}}, how, tolerance, &estimate);
    const Eigen::VectorXd y =
        internal::FixedStepOutput(p, internal::FixedStepInput(u, how, m), dt, m);
    const double error = std::sqrt((y - ref).squaredNorm() / static_cast<double>(y.size()));
    INFO("input " << static_cast<int>(how) << ": m " << m << ", estimate " << estimate
                  << " m, error against RK4 " << error << " m, tolerance " << tolerance << " m");
    CHECK(estimate <= tolerance);
    CHECK(error <= tolerance);  // the rule's promise, against the independent reference
    // Richardson's estimate is the error's size, not just a bound (second order).
    CHECK(estimate == Approx(error).epsilon(0.3));
    // Half the steps would not do: the choice is the smallest power of two.
    if (m > 2) {
      const Eigen::VectorXd coarse =
          internal::FixedStepOutput(p, internal::FixedStepInput(u, how, m / 2), dt, m / 2);
      CHECK(std::sqrt((coarse - ref).squaredNorm() / static_cast<double>(y.size())) > tolerance);
    }
  }
}

TEST_CASE("bouc-wen: the band-limited input is recognised by its wrap and its spectrum",
          "[hysteresis][bouc-wen]") {
  const double dt = 1.0 / 750;
  double wrap = 0, high = 0;
  // Whole periods of a multisine with lines far below Nyquist: band-limited.
  const Eigen::VectorXd u = Multisine(512, dt, 3, 40, 15.0).replicate(2, 1);
  CHECK(internal::PeriodicBandLimited(u, &wrap, &high));
  CHECK(high <= 1e-20);
  // Cut mid-period: the wrap jumps.
  CHECK_FALSE(internal::PeriodicBandLimited(u.head(700), &wrap, &high));
  // A long slow sine cut mid-period: its jump's power above a quarter of the rate is below the
  // bound (spread over 2^17 lines), the wrap is what refuses it.
  Eigen::VectorXd slow(1 << 17);
  for (Eigen::Index i = 0; i < slow.size(); ++i)
    slow[i] =
        std::sin(2 * M_PI * 10.05 * static_cast<double>(i) / static_cast<double>(slow.size()));
  CHECK_FALSE(internal::PeriodicBandLimited(slow, &wrap, &high));
  CHECK(high <= internal::kBandLimitedPower);
  // A ramp wraps by its whole range; noise has power everywhere.
  CHECK_FALSE(internal::PeriodicBandLimited(Eigen::VectorXd::LinSpaced(512, 0, 1), &wrap, &high));
  Eigen::VectorXd noise(512);
  for (Eigen::Index i = 0; i < noise.size(); ++i) noise[i] = std::sin(1e3 * i * i);
  CHECK_FALSE(internal::PeriodicBandLimited(noise, &wrap, &high));
  CHECK(high > 0.1);
  // The same multisine with lines up to 0.4 of the sampling rate: not well below Nyquist.
  CHECK_FALSE(internal::PeriodicBandLimited(Multisine(512, dt, 3, 200, 15.0), &wrap, &high));
}

TEST_CASE("bouc-wen: nu > 1 and CVODE agree with RK4 too", "[hysteresis][bouc-wen]") {
  MechanicalBoucWenParameters p;
  p.nu = 2;
  p.beta_per_m = 1e3 / 20;  // |z| ~ 20 N here: keep beta |z|^nu comparable to the nu = 1 case
  const double dt = 1.0 / 750;
  const Eigen::VectorXd u = Multisine(60, dt, 1, 12, 25.0);
  BoucWenSimulationOptions o;
  o.rtol = 1e-12;
  const Eigen::VectorXd y = MechanicalBoucWen(p, o).Simulate(u, dt);
  const Eigen::VectorXd ref = CheckedMechanicalRk4(p, u, dt, InputInterpolation::kLinear, 16000);
  CHECK(RelativeMax(y, ref) <= 1e-8);  // as above
}

TEST_CASE("bouc-wen-piezo: the closed-form step, CVODE and RK4 agree", "[hysteresis][bouc-wen]") {
  PiezoBoucWenParameters p = PiezoExample();
  p.offset_m = 1e-6;
  const double dt = 1e-3;
  const Eigen::VectorXd u = Multisine(400, dt, 1, 6, 20.0);
  const Eigen::VectorXd closed = PiezoBoucWen(p).Simulate(u, dt);
  BoucWenSimulationOptions o;
  o.rtol = 1e-12;
  const Eigen::VectorXd cvode = PiezoBoucWen(p, o).SimulateCvode(u, dt);
  const internal::SampledInput input(u, dt, InputInterpolation::kLinear);
  const Eigen::VectorXd ref = Rk4(
      1, u.size(), dt, 2000,
      [&](double t, Eigen::Index k, const Eigen::VectorXd& x, Eigen::VectorXd* d) {
        double uu, du;
        input.Evaluate(t, k, &uu, &du);
        (*d)[0] = p.alpha * p.d_m_per_v * du - p.beta_per_v * std::abs(du) * x[0] -
                  p.gamma_per_v * du * std::abs(x[0]);
      },
      [&](Eigen::Index k, const Eigen::VectorXd& x) {
        return p.d_m_per_v * u[k] - x[0] + p.offset_m;
      });
  // RK4 at 2000 steps per sample: its order drops to 2 where h or u' changes sign (3e-10 at
  // 200 steps, so ~3e-12 here).
  CHECK(RelativeMax(closed, ref) <= 1e-10);
  CHECK(RelativeMax(cvode, ref) <= 1e-8);  // CVODE at rtol 1e-12, the acceptance bound
  // The loop is real: y is not a function of u (the same u meets two y's).
  CHECK((closed - p.d_m_per_v * u).cwiseAbs().maxCoeff() > 0.1 * p.d_m_per_v * 20);
}

TEST_CASE("bouc-wen-piezo: Invert undoes Simulate sample by sample", "[hysteresis][bouc-wen]") {
  const PiezoBoucWenParameters p = PiezoExample();
  const PiezoBoucWen model(p);
  REQUIRE(model.invertible());
  const double dt = 1e-3;
  const Eigen::VectorXd u = Multisine(500, dt, 1, 9, 12.0);
  const Eigen::VectorXd y = model.Simulate(u, dt);
  const Eigen::VectorXd u_back = model.Invert(y, dt);
  // Bisection to the last bit of u, through an exact step: rounding only.
  CHECK((u_back - u).cwiseAbs().maxCoeff() <= 1e-9 * u.cwiseAbs().maxCoeff());
  CHECK(RelativeMax(model.Simulate(u_back, dt), y) <= 1e-12);

  PiezoBoucWenParameters bad = p;
  bad.alpha = 1.2;  // y falls while u rises: no inverse
  CHECK_FALSE(PiezoBoucWen(bad).invertible());
  CHECK_THROWS_AS(PiezoBoucWen(bad).Invert(y, dt), NumericalError);
  CHECK_THROWS_AS(MechanicalBoucWen({}).Invert(y, dt), NumericalError);
}

TEST_CASE("bouc-wen: band-limited upsampling and input are the multisine itself",
          "[hysteresis][bouc-wen]") {
  const double dt = 1.0 / 750;
  const Eigen::Index n = 512;
  const Eigen::VectorXd coarse = Multisine(n, dt, 2, 60, 3.0);
  const Eigen::VectorXd fine = Multisine(n * 20, dt / 20, 2, 60, 3.0);
  // FFT round trip on a signal of rms ~ 16: rounding at 1e-14 of its size.
  const double upsample_error = (UpsampleBandLimited(coarse, 20) - fine).cwiseAbs().maxCoeff();
  INFO("upsampling error " << upsample_error);
  CHECK(upsample_error <= 1e-11);
  const internal::SampledInput input(coarse, dt, InputInterpolation::kBandLimited);
  Eigen::VectorXd du_exact;
  const Eigen::VectorXd shifted = Multisine(n, dt, 2, 60, 3.0, 0.37 * dt, &du_exact);
  double worst_u = 0, worst_du = 0;
  for (Eigen::Index i = 0; i < n; ++i) {
    double u, du;
    input.Evaluate((static_cast<double>(i) + 0.37) * dt, i, &u, &du);
    worst_u = std::max(worst_u, std::abs(u - shifted[i]));
    worst_du = std::max(worst_du, std::abs(du - du_exact[i]) / du_exact.cwiseAbs().maxCoeff());
  }
  CHECK(worst_u <= 1e-10);   // the recurrence e^(i w l t) over 60 lines: ~1e-14 per product
  CHECK(worst_du <= 1e-10);  // relative to max |u'|
}

TEST_CASE("bouc-wen: the tabulated band-limited input is within its stated bound of the lines' sum",
          "[hysteresis][bouc-wen]") {
  // Past kMaxBandLimitedWork the input is tabulated (max_line_work 0 forces it here): u and u'
  // against the analytic multisine and the summed lines, at points between the grid's, in
  // the first period and two periods on (the interpolant is periodic). A slow and a rough
  // input: the grid's refinement follows the top line.
  const double dt = 1.0 / 750;
  const Eigen::Index n = 512;
  for (int top : {60, 255}) {
    const double amplitude = 3.0;
    const Eigen::VectorXd coarse = Multisine(n, dt, 2, top, amplitude);
    const internal::SampledInput sum(coarse, dt, InputInterpolation::kBandLimited);
    const internal::SampledInput table(coarse, dt, InputInterpolation::kBandLimited, 0.0);
    REQUIRE(sum.fine() == 0);
    REQUIRE(table.fine() >= 2);
    // Hermite's remainder h^6 M6 / 46080 with M6 = sum a_l w_l^6 (each line's amplitude a_l
    // is `amplitude`), A = sum a_l; the grid is the smallest power of two within 1e-11 A.
    const double w0 = 2 * M_PI / (static_cast<double>(n) * dt), w_top = w0 * top;
    double m6 = 0;
    for (int l = 2; l <= top; ++l) m6 += amplitude * std::pow(w0 * l, 6);
    const double lines_sum = amplitude * (top - 1);
    auto hermite = [&](int points) { return std::pow(dt / points, 6) * m6 / 46080; };
    CHECK(hermite(table.fine()) <= internal::kBandLimitedGridTolerance * lines_sum);
    CHECK(hermite(table.fine() / 2) > internal::kBandLimitedGridTolerance * lines_sum);
    const double bound = table.grid_error_bound();
    CHECK(bound == Approx(hermite(table.fine())).epsilon(1e-9));
    double worst_u = 0, worst_du = 0, worst_vs_sum = 0;
    for (int periods : {0, 2}) {
      for (double frac : {0.13, 0.37, 0.5, 0.91}) {
        const double shift = (periods * static_cast<double>(n) + frac) * dt;
        Eigen::VectorXd du_exact;
        const Eigen::VectorXd exact = Multisine(n, dt, 2, top, amplitude, shift, &du_exact);
        for (Eigen::Index i = 0; i < n; ++i) {
          const double t = static_cast<double>(i) * dt + shift;
          double u = 0, du = 0, us = 0, dus = 0;
          table.Evaluate(t, i, &u, &du);
          sum.Evaluate(t, i, &us, &dus);
          worst_u = std::max(worst_u, std::abs(u - exact[i]));
          worst_vs_sum = std::max(worst_vs_sum, std::abs(u - us));
          worst_du = std::max(worst_du, std::abs(du - du_exact[i]));
        }
      }
    }
    INFO("top line " << top << ": " << table.fine() << " points a sample, bound " << bound
                     << ", worst u error " << worst_u << ", against the sum " << worst_vs_sum
                     << ", worst u' error " << worst_du);
    // The bound plus the FFT's and the multisine's rounding (~1e-14 of A).
    CHECK(worst_u <= bound + 1e-13 * lines_sum);
    CHECK(worst_vs_sum <= bound + 1e-13 * lines_sum);
    // u': Hermite's derivative remainder, below h^5 M6 / 1920 (3 max|(s(1-s))^2 (2s-1)| / 720
    // = 1 / 13400 of it, with room for the mean-value point's own motion).
    const double h = dt / table.fine();
    CHECK(worst_du <= std::pow(h, 5) * m6 / 1920 + 1e-13 * w_top * lines_sum);
  }
}

TEST_CASE("bouc-wen: the table's bound is checked without the table, on either side of it",
          "[hysteresis][bouc-wen]") {
  // SampledInput::GridPerSample (the fit's --input auto rule) against the constructor and
  // against L from Hermite's remainder written out here; the table's bound lowered to 3 n L
  // values (max_line_work 0 forces the table): 3 n L fit, 3 n L - 1 are refused, both ways.
  const double dt = 1.0 / 750;
  const Eigen::Index n = 256;
  const int top = 60;
  const double amplitude = 3.0;
  const Eigen::VectorXd u = Multisine(n, dt, 2, top, amplitude);
  const double w0 = 2 * M_PI / (static_cast<double>(n) * dt);
  double m6 = 0;
  for (int l = 2; l <= top; ++l) m6 += amplitude * std::pow(w0 * l, 6);
  const double lines_sum = amplitude * (top - 1);
  int L = 1;
  do {
    L *= 2;
  } while (std::pow(dt / L, 6) * m6 / 46080 > internal::kBandLimitedGridTolerance * lines_sum);
  REQUIRE(L < internal::kMaxGridPerSample);
  using internal::SampledInput;
  const auto band = InputInterpolation::kBandLimited;
  const double values = 3.0 * static_cast<double>(n) * L;
  CHECK(SampledInput::GridPerSample(u, dt, 0.0, values) == L);
  CHECK(SampledInput(u, dt, band, 0.0, values).fine() == L);
  CHECK_THROWS_AS(SampledInput::GridPerSample(u, dt, 0.0, values - 1), InputError);
  CHECK_THROWS_AS(SampledInput(u, dt, band, 0.0, values - 1), InputError);
  CHECK_THROWS_WITH(SampledInput::GridPerSample(u, dt, 0.0, values - 1),
                    Catch::Contains(std::to_string(L) + " points a sample"));
  // The default bounds: 59 lines x 256 samples are summed, no table to bound.
  CHECK(SampledInput::GridPerSample(u, dt) == 0);
  CHECK(SampledInput(u, dt, band).fine() == 0);
  CHECK(SampledInput::GridPerSample(u, dt, 1e300, 0.0) == 0);
}

TEST_CASE("bouc-wen: CVODE on an input built beforehand is the self-built simulation's",
          "[hysteresis][bouc-wen]") {
  // The fit builds each recording's SampledInput once and hands it to every simulation: the
  // outputs (and CVODES' sensitivities) are the standalone simulations' to the bit, the input's
  // own interpolation taken (not the options'). A table (forced: max_line_work 0) agrees with
  // the summed lines to CVODE's tolerance.
  MechanicalBoucWenParameters p;
  const double dt = 1.0 / 750;
  const Eigen::VectorXd u = Multisine(200, dt, 3, 40, 15.0);
  const std::vector<int> which = {0, 2, 5};
  Eigen::VectorXd y_band;
  for (auto how :
       {InputInterpolation::kHold, InputInterpolation::kLinear, InputInterpolation::kBandLimited}) {
    INFO("input " << static_cast<int>(how));
    BoucWenSimulationOptions o;
    o.input = how;
    Eigen::VectorXd y_own, y_shared, y_sens_own, y_sens_shared;
    Eigen::MatrixXd dy_own, dy_shared;
    const internal::SampledInput input(u, dt, how);
    internal::MechanicalCvode(p, u, dt, o, {}, &y_own, nullptr);
    internal::MechanicalCvode(p, input, o, {}, &y_shared, nullptr);
    CHECK(y_own == y_shared);
    CHECK(y_own == MechanicalBoucWen(p, o).Simulate(u, dt));
    internal::MechanicalCvode(p, u, dt, o, which, &y_sens_own, &dy_own);
    internal::MechanicalCvode(p, input, o, which, &y_sens_shared, &dy_shared);
    CHECK(y_sens_own == y_sens_shared);
    CHECK(dy_own == dy_shared);
    // The input's interpolation, whatever the options say.
    BoucWenSimulationOptions other = o;
    other.input = how == InputInterpolation::kLinear ? InputInterpolation::kHold
                                                     : InputInterpolation::kLinear;
    Eigen::VectorXd y_other;
    internal::MechanicalCvode(p, input, other, {}, &y_other, nullptr);
    CHECK(y_other == y_own);
    if (how == InputInterpolation::kBandLimited) y_band = y_own;
  }
  BoucWenSimulationOptions band;
  band.input = InputInterpolation::kBandLimited;
  const internal::SampledInput table(u, dt, InputInterpolation::kBandLimited, 0.0);
  REQUIRE(table.fine() > 0);
  Eigen::VectorXd y_table;
  internal::MechanicalCvode(p, table, band, {}, &y_table, nullptr);
  CHECK(RelativeMax(y_table, y_band) <= 1e-7);  // rtol 1e-9 twice; the table's 1e-11
  // The piezo form: SimulateCvode (a held input taken linear) against PiezoCvode.
  const PiezoBoucWenParameters pz = PiezoExample();
  for (auto how :
       {InputInterpolation::kHold, InputInterpolation::kLinear, InputInterpolation::kBandLimited}) {
    BoucWenSimulationOptions o;
    o.input = how;
    const auto taken = how == InputInterpolation::kHold ? InputInterpolation::kLinear : how;
    CHECK(PiezoBoucWen(pz, o).SimulateCvode(u, dt) ==
          internal::PiezoCvode(pz, internal::SampledInput(u, dt, taken), o.rtol));
  }
}

TEST_CASE("bouc-wen: MATLAB's decimate(x, r, 'fir') keeps a slow sine and its phase",
          "[hysteresis][bouc-wen]") {
  // fir1(30, 1/r) has unit DC gain and, delay-compensated, zero phase: a sine at 1/50 of the
  // output Nyquist comes out with its amplitude within the window's ripple and no delay.
  const int r = 5;
  const Eigen::Index n = 2000;
  Eigen::VectorXd x(n);
  const double f = 0.01 / r;  // cycles per input sample
  for (Eigen::Index i = 0; i < n; ++i) x[i] = std::sin(2 * M_PI * f * static_cast<double>(i));
  const Eigen::VectorXd y = DecimateFir(x, r);
  REQUIRE(y.size() == n / r);
  double worst = 0;
  for (Eigen::Index j = 10; j + 10 < y.size(); ++j)  // away from the zero-padded edges
    worst = std::max(worst, std::abs(y[j] - std::sin(2 * M_PI * f * static_cast<double>(j * r))));
  CHECK(worst <= 2e-3);  // Hamming pass-band ripple of a 31-tap filter at 2 % of its band
  // A constant is kept exactly (DC gain 1) except within 15 samples of the ends.
  const Eigen::VectorXd c = DecimateFir(Eigen::VectorXd::Constant(300, 2.5), 2);
  CHECK(std::abs(c[75] - 2.5) <= 1e-14);
  CHECK(std::abs(c[0] - 2.5) > 1e-3);  // the start sees the zero initial state
}

TEST_CASE("bouc-wen: the benchmark chain reproduces the benchmark's test output",
          "[hysteresis][bouc-wen][benchmark]") {
  const std::string path = test::SourcePath("datasets/boucwen/test_multisine.csv");
  REQUIRE(std::filesystem::exists(path));  // bundled (datasets/boucwen/README.md)
  const Recording test = ReadRecording(path);
  const Eigen::VectorXd u = test.column("u"), y = test.column("x");
  BoucWenSimulationOptions o;
  o.integrator = BoucWenIntegrator::kBenchmarkChain;
  const MechanicalBoucWen truth(MechanicalBoucWenParameters{}, o);  // Noël & Schoukens' values
  const Eigen::VectorXd ym = truth.SimulatePeriodic(u, 1.0 / 750);
  const double rms = std::sqrt((ym - y).squaredNorm() / static_cast<double>(y.size()));
  // The benchmark's own generator, re-run: equal to the rounding of the CSV's 17 digits.
  CHECK(rms <= 1e-12);
  // The same through Simulate on repeated periods (the steady middle period).
  const Eigen::VectorXd y4 = truth.Simulate(u.replicate(4, 1), 1.0 / 750);
  CHECK((y4.segment(2 * u.size(), u.size()) - y).cwiseAbs().maxCoeff() <= 1e-12);
}

TEST_CASE("bouc-wen: bad parameters and options name the field", "[hysteresis][bouc-wen]") {
  MechanicalBoucWenParameters p;
  p.m_kg = -1;
  CHECK_THROWS_WITH(MechanicalBoucWen(p), Catch::Contains("m_kg"));
  p = {};
  p.nu = 0.5;
  CHECK_THROWS_WITH(MechanicalBoucWen(p), Catch::Contains("nu"));
  BoucWenSimulationOptions o;
  o.upsampling = 0;
  CHECK_THROWS_WITH(MechanicalBoucWen({}, o), Catch::Contains("upsampling"));
  o = {};
  o.integrator = BoucWenIntegrator::kBenchmarkChain;
  CHECK_THROWS_AS(PiezoBoucWen({}, o), OptionsError);
  Eigen::VectorXd u = Eigen::VectorXd::Zero(5);
  u[3] = NAN;
  CHECK_THROWS_WITH(MechanicalBoucWen({}).Simulate(u, 1e-3), Catch::Contains("u[3]"));
  CHECK_THROWS_AS(MechanicalBoucWen({}).Simulate(Eigen::VectorXd::Zero(5), 0), OptionsError);
}

}  // namespace

TEST_CASE("bouc-wen-piezo: the inverse stepper gives the forward model's output back",
          "[hysteresis][bouc-wen][stream]") {
  const PiezoBoucWen model(PiezoExample());
  const double dt = 1e-3;
  const Eigen::VectorXd u = Multisine(500, dt, 1, 9, 12.0);
  const Eigen::VectorXd y = model.Simulate(u, dt);
  BoucWenInverseStepper stepper(model);
  Eigen::VectorXd u_back(y.size());
  for (Eigen::Index k = 0; k < y.size(); ++k) u_back[k] = stepper.Step(y[k]);
  CHECK_FALSE(stepper.out_of_reach());
  CHECK(u_back == model.Invert(y, dt));
  // The forward model (closed form, its own tests) on the stepper's inputs: rounding only.
  CHECK(RelativeMax(model.Simulate(u_back, dt), y) <= 1e-12);
  stepper.Reset();
  CHECK(stepper.Step(y[0]) == u_back[0]);
}

}  // namespace sysid
