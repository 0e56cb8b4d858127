#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <string>
#include <utility>

#include "sysid/error.hpp"
#include "sysid/hysteresis.hpp"

namespace {

sysid::PiParameters Classical(std::vector<double> r, std::vector<double> w, double p0,
                              double c = 0) {
  sysid::PiParameters p;
  p.thresholds = std::move(r);
  p.weights = std::move(w);
  p.polynomial = {p0};
  p.offset_m = c;
  p.input_min_v = -10;
  p.input_max_v = 10;
  return p;
}

// A random walk with random reversals, within [-a, a] [V].
Eigen::VectorXd RandomInput(int n, double a, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> step(-0.4, 0.4);
  Eigen::VectorXd u(n);
  double x = 0;
  for (int k = 0; k < n; ++k) {
    x = std::clamp(x + step(rng), -a, a);
    u[k] = x;
  }
  return u;
}

sysid::Recording MakeRecording(const Eigen::VectorXd& u, const Eigen::VectorXd& x, double dt,
                               const std::string& name) {
  sysid::Recording rec;
  rec.source = name;
  rec.names = {"t", "u", "x"};
  rec.data.resize(u.size(), 3);
  for (Eigen::Index k = 0; k < u.size(); ++k) rec.data.row(k) << k * dt, u[k], x[k];
  return rec;
}

// A decaying-amplitude sine that sweeps the operators' thresholds (minor loops inside major).
Eigen::VectorXd Excitation(int n, double dt, double f_hz, double a) {
  Eigen::VectorXd u(n);
  for (int k = 0; k < n; ++k) {
    const double t = k * dt;
    u[k] = a * (0.55 + 0.45 * std::cos(2 * M_PI * t / (n * dt))) * std::sin(2 * M_PI * f_hz * t) + 0.3;
  }
  return u;
}

}  // namespace

TEST_CASE("classical PI inverse matches a hand-worked example", "[hysteresis]") {
  // y = u + F_1[u]. Inverse (Kuhnen 2003): r'_1 = w0 r1 = 1, w'_0 = 1, w'_1 = -1/(2*1) = -0.5.
  // Input 0, 2, 0: F_1 = 0, 1, 1, so y = 0, 3, 1. Inverse: F'_1[y] = 0, 2, 2, u = y - 0.5 F'.
  const sysid::PrandtlIshlinskiiModel m(Classical({1.0}, {1.0}, 1.0));
  const sysid::PiParameters inv = m.InverseParameters();
  CHECK(inv.thresholds[0] == 1.0);
  CHECK(inv.weights[0] == -0.5);
  CHECK(inv.polynomial[0] == 1.0);
  Eigen::VectorXd u(3), y(3);
  u << 0, 2, 0;
  y << 0, 3, 1;
  CHECK(m.Simulate(u, 1.0) == y);
  CHECK(m.Invert(y, 1.0) == u);
}

TEST_CASE("classical PI: Invert after Simulate is the identity to 1e-12", "[hysteresis]") {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> weight(0.0, 1.0);
  for (int trial = 0; trial < 5; ++trial) {
    const int n = 20;
    std::vector<double> r(n), w(n);
    for (int i = 0; i < n; ++i) r[i] = 0.2 * (i + 1), w[i] = weight(rng) * (i % 3 == 0 ? 0.0 : 1.0);
    sysid::PiParameters p = Classical(r, w, 0.3 + weight(rng), 1e-3 * trial);
    // A non-trivial initial state: where a random earlier input history left the operators.
    const Eigen::VectorXd history = RandomInput(500, 8.0, 1000 + trial);
    p.initial_input_v = history[history.size() - 1];
    p.initial_state.resize(n);
    for (int i = 0; i < n; ++i) p.initial_state[i] = sysid::PlayOperator(history, r[i])[history.size() - 1];
    const sysid::PrandtlIshlinskiiModel m(p);
    const Eigen::VectorXd u = RandomInput(3000, 8.0, 11 + trial);
    const Eigen::VectorXd y = m.Simulate(u, 1e-3);
    const Eigen::VectorXd back = m.Invert(y, 1e-3);
    // 1e-12 V: the inverse's sums of ~40 terms of size <= 10 lose a few ulps.
    CHECK((back - u).cwiseAbs().maxCoeff() <= 1e-12);
    // And the other way round: Simulate after Invert reproduces a reference.
    const Eigen::VectorXd ref = 0.2 * RandomInput(3000, 8.0, 99 + trial);
    CHECK((m.Simulate(m.Invert(ref, 1e-3), 1e-3) - ref).cwiseAbs().maxCoeff() <= 1e-12);
  }
}

TEST_CASE("gpi and rdpi invert by a monotone solve to the last bits", "[hysteresis]") {
  sysid::PiParameters g = Classical({0.5, 1.0, 1.5}, {0.2, 0.1, 0.05}, 0.5, 0.01);
  g.form = sysid::PiForm::kPolynomial;
  g.polynomial = {0.5, 0.02, 0.004};  // slope 0.5 + 0.04 u + 0.012 u^2 > 0 everywhere
  sysid::PiParameters rd = Classical({0.5, 1.0, 1.5}, {0.2, 0.1, 0.05}, 0.5, 0.01);
  rd.form = sysid::PiForm::kRateDependent;
  // Small enough for a stable inverse: gain sum q max|u| / (dt p0) = 4e-5 * 11 / 0.005 = 0.09.
  rd.rate_weights = {1e-5, 2e-5, 0.0, 1e-5};
  for (const auto& p : {g, rd}) {
    const sysid::PrandtlIshlinskiiModel m(p);
    REQUIRE(m.invertible());
    const Eigen::VectorXd u = RandomInput(2000, 8.0, 3);
    const Eigen::VectorXd back = m.Invert(m.Simulate(u, 0.01), 0.01);
    // Bisection to adjacent doubles of u: a few ulps of 10 V, plus the output's rounding
    // divided by the smallest slope (0.5 m/V).
    CHECK((back - u).cwiseAbs().maxCoeff() <= 1e-12);
  }
}

TEST_CASE("PI fit recovers known weights from noisy data within 3 standard errors",
          "[hysteresis]") {
  const double dt = 5e-3, sigma = 2e-7;  // [s], [m] noise
  const std::vector<double> r_true = {0.25, 0.5, 0.75, 1.0, 1.25};
  const std::vector<double> w_true = {2e-6, 1.5e-6, 1e-6, 0.0, 0.5e-6};  // one at the bound
  sysid::PiParameters truth = Classical(r_true, w_true, 4e-6, -1.2e-5);
  const sysid::PrandtlIshlinskiiModel m(truth);
  std::mt19937_64 rng(2024);
  std::normal_distribution<double> noise(0, sigma);
  const Eigen::VectorXd u = Excitation(6000, dt, 1.0, 3.0);
  Eigen::VectorXd x = m.Simulate(u, dt);
  for (Eigen::Index k = 0; k < x.size(); ++k) x[k] += noise(rng);
  sysid::PiFitOptions o;
  o.thresholds = r_true;
  sysid::HysteresisFitSummary s;
  sysid::PiFitReport rep;
  const auto fit = sysid::FitPrandtlIshlinskii({MakeRecording(u, x, dt, "sim.csv")}, o, &s, &rep);
  const auto params = fit->parameters();
  const auto true_params = m.parameters();
  REQUIRE(params.size() == true_params.size());
  for (size_t j = 0; j < params.size(); ++j) {
    INFO(params[j].name << " = " << params[j].value << " +- " << params[j].std_error);
    if (std::isnan(params[j].std_error)) {  // held at the bound: the truth must be there too
      CHECK(params[j].value == 0.0);
      CHECK(true_params[j].value == 0.0);
    } else {
      CHECK(std::abs(params[j].value - true_params[j].value) <= 3 * params[j].std_error);
    }
  }
  CHECK(s.training_rms == Approx(sigma).epsilon(0.05));  // the noise, within its sampling spread
  CHECK(rep.residual_std == Approx(sigma).epsilon(0.05));
  CHECK(fit->invertible());
}

TEST_CASE("GPI and RDPI fits recover known parameters within 3 standard errors",
          "[hysteresis]") {
  const double sigma = 1e-7;
  std::mt19937_64 rng(5);
  std::normal_distribution<double> noise(0, sigma);
  const std::vector<double> r = {0.4, 0.8, 1.2};
  SECTION("gpi on one recording") {
    sysid::PiParameters truth = Classical(r, {1e-6, 0.6e-6, 0.3e-6}, 3e-6, 2e-6);
    truth.form = sysid::PiForm::kPolynomial;
    truth.polynomial = {3e-6, 0.0, 4e-8};  // Gu et al.'s odd polynomial: a2 held at 0
    const sysid::PrandtlIshlinskiiModel m(truth);
    const double dt = 5e-3;
    const Eigen::VectorXd u = Excitation(5000, dt, 0.7, 2.5);
    Eigen::VectorXd x = m.Simulate(u, dt);
    for (Eigen::Index k = 0; k < x.size(); ++k) x[k] += noise(rng);
    sysid::PiFitOptions o;
    o.form = sysid::PiForm::kPolynomial;
    o.thresholds = r;
    const auto fit = sysid::FitPrandtlIshlinskii({MakeRecording(u, x, dt, "g.csv")}, o);
    const auto got = fit->parameters(), want = m.parameters();
    for (size_t j = 0; j < got.size(); ++j) {
      INFO(got[j].name);
      if (got[j].name == "a2") {
        CHECK(got[j].value == 0.0);
        CHECK(std::isnan(got[j].std_error));
      } else {
        CHECK(std::abs(got[j].value - want[j].value) <= 3 * got[j].std_error);
      }
    }
  }
  SECTION("rdpi on recordings at several rates") {
    sysid::PiParameters truth = Classical(r, {1e-6, 0.6e-6, 0.3e-6}, 3e-6, 2e-6);
    truth.form = sysid::PiForm::kRateDependent;
    // q [m s/V^2]: at 8 Hz the input moves at up to ~125 V/s, so q0 rho is a third of p0.
    truth.rate_weights = {8e-9, 4e-9, 2e-9, 1e-9};
    const sysid::PrandtlIshlinskiiModel m(truth);
    std::vector<sysid::Recording> recs;
    const double dt = 5e-3;
    for (double f : {0.5, 2.0, 8.0}) {
      const Eigen::VectorXd u = Excitation(4000, dt, f, 2.5);
      Eigen::VectorXd x = m.Simulate(u, dt);
      for (Eigen::Index k = 0; k < x.size(); ++k) x[k] += noise(rng);
      recs.push_back(MakeRecording(u, x, dt, "f.csv"));
    }
    sysid::PiFitOptions o;
    o.form = sysid::PiForm::kRateDependent;
    o.thresholds = r;
    sysid::HysteresisFitSummary s;
    const auto fit = sysid::FitPrandtlIshlinskii(recs, o, &s);
    INFO(s.message << " rms " << s.training_rms);
    const auto got = fit->parameters(), want = m.parameters();
    for (size_t j = 0; j < got.size(); ++j) {
      INFO(got[j].name << " = " << got[j].value << " +- " << got[j].std_error);
      CHECK(std::abs(got[j].value - want[j].value) <= 3 * got[j].std_error);
    }
  }
}

TEST_CASE("an rdpi inverse whose rate feedback would grow is refused", "[hysteresis]") {
  sysid::PiParameters rd = Classical({0.5}, {0.2}, 0.5);
  rd.form = sysid::PiForm::kRateDependent;
  rd.rate_weights = {1e-3, 1e-3};  // gain 2e-3 * 10.5 / (0.01 * 0.5) = 4.2
  const sysid::PrandtlIshlinskiiModel m(rd);
  const Eigen::VectorXd u = RandomInput(200, 8.0, 4);
  CHECK_THROWS_WITH(m.Invert(m.Simulate(u, 0.01), 0.01),
                    Catch::Contains("rate_weights") && Catch::Contains("gain"));
  // Slower sampling divides the gain: at dt = 0.1 s it is 0.42 and the inverse is exact.
  CHECK((m.Invert(m.Simulate(u, 0.1), 0.1) - u).cwiseAbs().maxCoeff() <= 1e-12);
}

TEST_CASE("an ill-conditioned inverse is detected and a non-invertible one refused",
          "[hysteresis]") {
  const sysid::PrandtlIshlinskiiModel tiny(Classical({1.0}, {1.0}, 1e-9));
  CHECK(tiny.invertible());
  CHECK(tiny.InverseGainRatio() == Approx(1e9 + 1));  // (p0 + w) / p0
  const sysid::PrandtlIshlinskiiModel none(Classical({1.0}, {1.0}, 0.0));
  CHECK_FALSE(none.invertible());
  CHECK_THAT(none.why_not_invertible(), Catch::Contains("p0"));
  CHECK_THROWS_AS(none.Invert(Eigen::VectorXd::Zero(3), 1.0), sysid::NumericalError);
  // gpi: P(u) = u - 0.1 u^3 has dP/du = 1 - 0.3 u^2 < 0 beyond |u| = 1.83 V, inside [-10, 10].
  sysid::PiParameters g = Classical({1.0}, {1.0}, 1.0);
  g.form = sysid::PiForm::kPolynomial;
  g.polynomial = {1.0, 0.0, -0.1};
  const sysid::PrandtlIshlinskiiModel bent(g);
  CHECK_FALSE(bent.invertible());
  CHECK_THAT(bent.why_not_invertible(), Catch::Contains("polynomial") && Catch::Contains("dP/du"));
  g.input_min_v = -1.5;  // on [-1.5, 1.5] V (+5 %) the slope stays >= 1 - 0.3 * 1.65^2 = 0.18
  g.input_max_v = 1.5;
  CHECK(sysid::PrandtlIshlinskiiModel(g).invertible());
  // A fit on data whose p0 is nearly zero says so in its message.
  const double dt = 5e-3;
  const Eigen::VectorXd u = Excitation(3000, dt, 1.0, 3.0);
  const sysid::PrandtlIshlinskiiModel near_zero(Classical({0.5, 1.0}, {1e-6, 1e-6}, 1e-14));
  sysid::PiFitOptions o;
  o.thresholds = {0.5, 1.0};
  o.offset = false;
  sysid::HysteresisFitSummary s;
  sysid::PiFitReport rep;
  sysid::FitPrandtlIshlinskii({MakeRecording(u, near_zero.Simulate(u, dt), dt, "z.csv")}, o, &s, &rep);
  CHECK(rep.ill_conditioned_inverse);
  CHECK_THAT(s.message, Catch::Contains("ill-conditioned inverse") || Catch::Contains("not invertible"));
}

TEST_CASE("a reference outside the model's range is refused naming the sample", "[hysteresis]") {
  sysid::PiParameters p = Classical({1.0}, {1.0}, 1.0);
  p.input_min_v = 0;
  p.input_max_v = 2;
  for (auto form : {sysid::PiForm::kClassical, sysid::PiForm::kRateDependent}) {
    p.form = form;
    if (form == sysid::PiForm::kRateDependent) p.rate_weights = {0.0, 0.0};
    const sysid::PrandtlIshlinskiiModel m(p);
    Eigen::VectorXd y(4);
    y << 0.0, 1.0, 50.0, 1.0;
    CHECK_THROWS_WITH(m.Invert(y, 0.1), Catch::Contains("reference sample 2") && Catch::Contains("range"));
  }
}

TEST_CASE("a reference so far out that the inverse overflows names the model's reach, not NaN",
          "[hysteresis]") {
  // y = 0.25 u + F_1[u] (r = 1 V, w = 1), inputs [0, 2] V widened by 5 %: [-0.1, 2.1] V. Its
  // inverse (Kuhnen) is u = 4 y - 3.2 F'_1[y]: at y = +-1e308 both terms overflow, inf - inf,
  // and the message printed "it needs u = -nan V". By hand, from rest after u_0 = 0 the model
  // reaches 0.25 * 2.1 + (2.1 - 1) = 1.625 m at 2.1 V and 0.25 * -0.1 + 0 = -0.025 m at -0.1 V.
  sysid::PiParameters p = Classical({1.0}, {1.0}, 0.25);
  p.input_min_v = 0;
  p.input_max_v = 2;
  const sysid::PrandtlIshlinskiiModel m(p);
  REQUIRE(m.InverseParameters().weights[0] == Approx(-3.2));
  for (const auto& [x, reach] : {std::pair{1e308, std::string("above the output 1.625 m at u = 2.1 V")},
                                 std::pair{-1e308, std::string("below the output -0.025 m at u = -0.1 V")}}) {
    Eigen::VectorXd y(3);
    y << 0.0, x, 0.0;
    try {
      m.Invert(y, 0.1);
      FAIL("expected an InputError");
    } catch (const sysid::InputError& e) {
      const std::string what = e.what();
      INFO(what);
      CHECK_THAT(what, Catch::Contains("reference sample 1 (t = 0.1 s)") &&
                           Catch::Contains(reach) && Catch::Contains("overflows"));
      CHECK(what.find("nan") == std::string::npos);
      CHECK(what.find("inf") == std::string::npos);
    }
  }
}

TEST_CASE("PI parameters' rules name the field", "[hysteresis]") {
  auto make = [](sysid::PiParameters p) { return sysid::PrandtlIshlinskiiModel(p); };
  CHECK_THROWS_WITH(make(Classical({-1.0}, {1.0}, 1.0)), Catch::Contains("thresholds[0]"));
  CHECK_THROWS_WITH(make(Classical({1.0, 0.5}, {1.0, 1.0}, 1.0)),
                    Catch::Contains("thresholds[1]") && Catch::Contains("increasing"));
  CHECK_THROWS_WITH(make(Classical({1.0}, {NAN}, 1.0)), Catch::Contains("weights[0]"));
  sysid::PiParameters unreachable = Classical({0.5, 1.0}, {1.0, 1.0}, 1.0);
  unreachable.initial_state = {0.5, -0.8};  // 1.3 apart, more than r_2 - r_1 = 0.5
  CHECK_THROWS_WITH(make(unreachable), Catch::Contains("initial_state[1]"));
  std::vector<double> many(sysid::kMaxPlayOperators + 1);
  for (size_t i = 0; i < many.size(); ++i) many[i] = 0.01 * (i + 1);
  CHECK_THROWS_WITH(make(Classical(many, many, 1.0)), Catch::Contains("at most 200"));
  sysid::PiFitOptions o;
  o.operators = 201;
  CHECK_THROWS_WITH(o.Validate(), Catch::Contains("operators"));
}

TEST_CASE("a PI model file round-trips and its errors are positioned", "[hysteresis]") {
  sysid::PiParameters p = Classical({0.5, 1.0}, {1e-6, 2e-6}, 3e-6, 1e-5);
  p.form = sysid::PiForm::kRateDependent;
  p.rate_weights = {1e-8, 0, 2e-8};
  const sysid::PrandtlIshlinskiiModel m(p, {1e-9, NAN, 1e-9, 2e-9, NAN, 3e-9, 1e-8});
  const std::string text = m.ToJson();
  const auto back = sysid::PrandtlIshlinskiiFromJson(text, "h.json");
  const Eigen::VectorXd u = RandomInput(500, 3.0, 1);
  CHECK(back->Simulate(u, 0.01) == m.Simulate(u, 0.01));  // 17 significant digits: exact
  CHECK(std::isnan(back->parameters()[1].std_error));
  CHECK(back->parameters()[0].std_error == 1e-9);
  std::string bad = text;
  bad.replace(bad.find("0.5"), 3, "-0.5");
  CHECK_THROWS_WITH(sysid::PrandtlIshlinskiiFromJson(bad, "h.json"),
                    Catch::Contains("h.json:") && Catch::Contains("thresholds[0]"));
}
