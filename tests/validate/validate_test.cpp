// Validation scores and residual tests against references they did not produce: a hand-computed
// fit, the alternating sequence's closed-form correlations, an FFT correlation (Eigen's
// kissfft), the binomial tail summed term by term, published normal quantiles, and the tests'
// behaviour over seeds on white and on wrong-model residuals.
#include "sysid/validate.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <complex>
#include <limits>
#include <nlohmann/json.hpp>
#include <unsupported/Eigen/FFT>
#include <string>
#include <vector>

#include "core/portable_random.hpp"
#include "support/known_pi.hpp"
#include "support/plot_index_check.hpp"
#include "support/test_support.hpp"
#include "sysid/compare_hysteresis.hpp"
#include "sysid/error.hpp"
#include "sysid/hysteresis.hpp"
#include "sysid/input.hpp"
#include "sysid/io_output.hpp"
#include "sysid/report.hpp"
#include "sysid/simulate.hpp"

namespace {

using sysid::internal::PortableRandom;
using sysid::test::RunCli;
using sysid::test::TempDir;

Eigen::VectorXd Gaussian(PortableRandom& rng, int n) {
  Eigen::VectorXd out(n);
  for (int i = 0; i < n; ++i) out[i] = rng.Normal();
  return out;
}

Eigen::VectorXd Ar1(const Eigen::VectorXd& w, double phi) {
  Eigen::VectorXd out(w.size());
  double prev = 0;
  for (Eigen::Index i = 0; i < w.size(); ++i) out[i] = prev = phi * prev + w[i];
  return out;
}

// sum_t a_t b_{t-k} for k = 0..max_lag by FFT: zero-padded to 2N, A(f) conj(B(f)).
Eigen::VectorXd FftLaggedProducts(const Eigen::VectorXd& a, const Eigen::VectorXd& b, int max_lag) {
  const auto n = static_cast<size_t>(a.size());
  std::vector<double> pa(2 * n, 0.0), pb(2 * n, 0.0);
  for (size_t i = 0; i < n; ++i) {
    pa[i] = a[static_cast<Eigen::Index>(i)];
    pb[i] = b[static_cast<Eigen::Index>(i)];
  }
  Eigen::FFT<double> fft;
  std::vector<std::complex<double>> fa, fb, prod(2 * n);
  fft.fwd(fa, pa);
  fft.fwd(fb, pb);
  for (size_t i = 0; i < 2 * n; ++i) prod[i] = fa[i] * std::conj(fb[i]);
  std::vector<double> c;
  fft.inv(c, prod);
  Eigen::VectorXd out(max_lag + 1);
  for (int k = 0; k <= max_lag; ++k) out[k] = c[static_cast<size_t>(k)];
  return out;
}

double BinomialTail(int n, double p, int k) {  // P(X > k), term by term with exact C(n, j)
  double cdf = 0;
  for (int j = 0; j <= k; ++j) {
    double c = 1;
    for (int i = 1; i <= j; ++i) c = c * (n - j + i) / i;
    cdf += c * std::pow(p, j) * std::pow(1 - p, n - j);
  }
  return 1 - cdf;
}

}  // namespace

TEST_CASE("fit % is MATLAB compare's formula on a hand-computed case", "[validate]") {
  // y = 1, 2, 3, 4; ŷ = 1, 2, 3, 5: ||y - ŷ|| = 1, ||y - mean y|| = sqrt(5), range 3.
  const Eigen::Vector4d y(1, 2, 3, 4), yhat(1, 2, 3, 5);
  const sysid::FitScores s = sysid::ScoreFit(y, yhat);
  CHECK(s.fit_percent == Approx(55.278640450004206).epsilon(1e-14));
  CHECK(s.rmse == Approx(0.5).epsilon(1e-15));
  CHECK(s.nrmse_std == Approx(0.44721359549995793).epsilon(1e-14));  // 0.5 / sqrt(5/4)
  CHECK(s.nrmse_range == Approx(1.0 / 6.0).epsilon(1e-15));
  // A perfect model scores 100 %, the mean as a model 0 %.
  CHECK(sysid::ScoreFit(y, y).fit_percent == 100.0);
  CHECK(sysid::ScoreFit(y, Eigen::Vector4d::Constant(2.5)).fit_percent == Approx(0).margin(1e-13));
  CHECK(std::isnan(sysid::ScoreFit(Eigen::Vector4d::Ones(), y).fit_percent));
  CHECK_THROWS_AS(sysid::ScoreFit(y, Eigen::Vector3d(1, 2, 3)), sysid::InputError);
}

TEST_CASE("correlations match the alternating sequence's closed form", "[validate]") {
  // e_t = (-1)^t, N even: mean 0, sum e_t e_{t-k} = (-1)^k (N - k), sum e^2 = N.
  const int n = 100;
  Eigen::VectorXd e(n);
  for (int t = 0; t < n; ++t) e[t] = t % 2 ? -1.0 : 1.0;
  const Eigen::VectorXd r = sysid::NormalisedAutocorrelation(e, 10);
  const Eigen::VectorXd c = sysid::NormalisedCrossCorrelation(e, -e, 10);
  for (int k = 0; k <= 10; ++k) {
    const double expected = (k % 2 ? -1.0 : 1.0) * (n - k) / n;
    CHECK(r[k] == Approx(expected).margin(1e-15));
    CHECK(c[k] == Approx(-expected).margin(1e-15));
  }
}

TEST_CASE("correlations match an FFT correlation on random sequences", "[validate]") {
  PortableRandom rng(7);
  const int n = 777, lags = 40;
  const Eigen::VectorXd e = Ar1(Gaussian(rng, n), 0.7).array() + 3.0;  // a mean to remove
  const Eigen::VectorXd u = Gaussian(rng, n).array() - 1.0;
  const Eigen::VectorXd ce = e.array() - e.mean(), cu = u.array() - u.mean();
  const Eigen::VectorXd ree = FftLaggedProducts(ce, ce, lags) / ce.squaredNorm();
  const Eigen::VectorXd reu =
      FftLaggedProducts(ce, cu, lags) / std::sqrt(ce.squaredNorm() * cu.squaredNorm());
  const Eigen::VectorXd r = sysid::NormalisedAutocorrelation(e, lags);
  const Eigen::VectorXd c = sysid::NormalisedCrossCorrelation(e, u, lags);
  for (int k = 0; k <= lags; ++k) {
    CHECK(r[k] == Approx(ree[k]).margin(1e-12));
    CHECK(c[k] == Approx(reu[k]).margin(1e-12));
  }
}

TEST_CASE("the bounds are 2.58/sqrt(N) and the verdict rules' constants", "[validate]") {
  PortableRandom rng(3);
  const int n = 1234;
  const Eigen::VectorXd e = Gaussian(rng, n), u = Gaussian(rng, n);
  sysid::ResidualTestOptions o;
  const sysid::CorrelationTest a = sysid::AutocorrelationTest(e, o);
  const sysid::CorrelationTest x = sysid::CrossCorrelationTest(e, u, o);
  CHECK(a.bound == Approx(2.58 / std::sqrt(n)).epsilon(1e-15));
  CHECK(x.bound == Approx(2.58 / std::sqrt(n)).epsilon(1e-15));
  REQUIRE(a.lags.size() == 25);
  CHECK(a.lags.front() == 1);
  REQUIRE(x.lags.size() == 26);
  CHECK(x.lags.front() == 0);
  CHECK(x.lags.back() == 25);
  // Published quantiles: z_0.995 = 2.5758293035489, z_0.975 = 1.9599639845401.
  CHECK(sysid::NormalQuantile(0.995) == Approx(2.5758293035489).epsilon(1e-11));
  CHECK(sysid::NormalQuantile(0.975) == Approx(1.9599639845401).epsilon(1e-11));
  CHECK(a.strong_bound == Approx(sysid::NormalQuantile(1 - 0.01 / 50) / std::sqrt(n)));
  CHECK(x.strong_bound == Approx(sysid::NormalQuantile(1 - 0.01 / 52) / std::sqrt(n)));
  // Rule (a): the smallest k with P(Binomial(L, 0.01) > k) <= 0.01, against the tail summed.
  for (int lags : {1, 5, 25, 26, 100, 1000}) {
    const int k = sysid::AllowedLagsOutside(lags, 0.01, 0.01);
    CHECK(BinomialTail(lags, 0.01, k) <= 0.01);
    if (k > 0) CHECK(BinomialTail(lags, 0.01, k - 1) > 0.01);
  }
  CHECK(sysid::AllowedLagsOutside(25, 0.01, 0.01) == 2);
  // The counts agree with the correlations.
  CHECK(a.outside == (a.r.array().abs() > a.bound).count());
  CHECK(a.max_abs_r == Approx(a.r.cwiseAbs().maxCoeff()));
}

TEST_CASE("white residuals pass in at least 95 % of 200 seeds, wrong models fail", "[validate]") {
  const int n = 1000, seeds = 200;
  const sysid::ResidualTestOptions o;
  int white_auto = 0, white_cross = 0, ar_fail = 0, gain_fail = 0, coloured_gain_fail = 0;
  for (int seed = 1; seed <= seeds; ++seed) {
    PortableRandom rng(static_cast<std::uint64_t>(seed));
    const Eigen::VectorXd w = Gaussian(rng, n), u = Gaussian(rng, n);
    white_auto += sysid::AutocorrelationTest(w, o).pass;
    white_cross += sysid::CrossCorrelationTest(w, u, o).pass;
    // The residual of a model that misses an AR(1) noise model (coefficient 0.5).
    ar_fail += !sysid::AutocorrelationTest(Ar1(w, 0.5), o).pass;
    // y = u + w modelled as 0.8 u: e = 0.2 u + w, correlated with u at lag 0 (white u) ...
    const Eigen::VectorXd e_gain = 0.2 * u + w;
    gain_fail += !sysid::CrossCorrelationTest(e_gain, u, o).pass;
    // ... and at many lags for a coloured u.
    const Eigen::VectorXd uc = Ar1(u, 0.9);
    coloured_gain_fail += !sysid::CrossCorrelationTest(0.1 * uc + w, uc, o).pass;
  }
  INFO("white " << white_auto << " " << white_cross << ", wrong " << ar_fail << " " << gain_fail
                << " " << coloured_gain_fail);
  CHECK(white_auto >= 190);
  CHECK(white_cross >= 190);
  CHECK(ar_fail == seeds);
  CHECK(gain_fail >= 198);
  CHECK(coloured_gain_fail >= 198);
}

TEST_CASE("residual test options are bounded and named", "[validate]") {
  sysid::ResidualTestOptions o;
  o.max_lag = 0;
  CHECK_THROWS_AS(o.Validate(), sysid::OptionsError);
  o.max_lag = 1001;
  try {
    o.Validate();
    FAIL("max_lag 1001 accepted");
  } catch (const sysid::OptionsError& e) {
    CHECK(e.field() == "max_lag");
  }
  o = {};
  o.max_lag = 300;  // 4 (L + 1) = 1204 > 1000 samples
  PortableRandom rng(1);
  CHECK_THROWS_WITH(sysid::AutocorrelationTest(Gaussian(rng, 1000), o),
                    Catch::Contains("expected at least"));
  CHECK_THROWS_AS(sysid::NormalisedAutocorrelation(Eigen::VectorXd::Ones(50), 5),
                  sysid::InputError);
}

namespace {

// A friction-model recording: the model's own simulation with white noise on v and x.
sysid::Recording FrictionRecording(const sysid::FrictionModel& model, std::uint64_t seed) {
  std::vector<double> t, u;
  const int n = 1500;
  const double dt = 1e-3;
  for (int i = 0; i < n; ++i) {
    t.push_back(i * dt);
    const double phase = std::fmod(i * dt, 0.5);
    u.push_back(phase < 0.1 ? 2.0 : (phase > 0.25 && phase < 0.35 ? -2.2 : 0.0));
  }
  sysid::SimulationOptions so;
  so.t0_s = 0;
  so.t_end_s = t.back();
  so.output_times_s = t;
  const sysid::SimulationResult r = sysid::Simulate(model, sysid::PiecewiseConstantInput(t, u), so);
  REQUIRE(r.summary.IsSolutionUsable());
  PortableRandom rng(seed);
  sysid::Recording rec = sysid::TrajectoryRecording(r.trajectory, "friction.csv");
  const double v_noise = 0.02 * r.trajectory.v_mps.cwiseAbs().maxCoeff();
  const double x_noise = 0.005 * r.trajectory.x_m.cwiseAbs().maxCoeff();
  rec.SetColumn("v", r.trajectory.v_mps + v_noise * Gaussian(rng, n));
  // An offset, so a simulation that ignored the measured start position would show.
  rec.SetColumn("x", (r.trajectory.x_m + x_noise * Gaussian(rng, n)).array() + 5e-3);
  return rec;
}

}  // namespace

TEST_CASE("a friction model validated on its own noisy simulation, and a wrong one", "[validate]") {
  const sysid::FrictionModel truth = sysid::FrictionModel::Paper();
  const sysid::Recording rec = FrictionRecording(truth, 11);
  const sysid::Validation good = sysid::ValidateFrictionModel(rec, truth);
  REQUIRE(good.outputs.size() == 2);
  CHECK(good.model_kind == "friction");
  CHECK(good.outputs[0].output == "v");
  CHECK(good.outputs[1].output == "x");
  for (const auto& o : good.outputs) {
    // The scores are ScoreFit's on the traces, and fit = 100 (1 - nrmse_std).
    const sysid::FitScores s = sysid::ScoreFit(o.measured, o.simulated);
    CHECK(o.scores.fit_percent == s.fit_percent);
    CHECK(o.scores.fit_percent == Approx(100 * (1 - o.scores.nrmse_std)).epsilon(1e-12));
    CHECK(o.scores.fit_percent > 90);
    CHECK(o.autocorrelation.pass);  // the residual is the white noise added
    CHECK(o.cross_correlation.pass);
  }
  sysid::FrictionModel wrong = truth;
  wrong.a3 *= 1.3;  // a gain error: the residual follows u
  const sysid::Validation bad = sysid::ValidateFrictionModel(rec, wrong);
  CHECK(bad.outputs[0].scores.fit_percent < good.outputs[0].scores.fit_percent - 5);
  CHECK_FALSE(bad.outputs[0].cross_correlation.pass);
  CHECK_FALSE(bad.outputs[0].autocorrelation.pass);
  CHECK_THROWS_AS(sysid::ValidateFrictionModel(rec, truth,
                                               [] {
                                                 sysid::ValidationOptions o;
                                                 o.residual.max_lag = 400;
                                                 return o;
                                               }()),
                  sysid::InputError);
}

TEST_CASE("a hysteresis model validated on its own recording with noise", "[validate]") {
  const sysid::PiParameters p = sysid::test::KnownPiParameters();
  sysid::test::KnownPiDrive drive;
  drive.noise_width_m = 0.2e-6;
  drive.source = "pi.csv";
  const sysid::Recording rec = sysid::test::KnownPiRecording(p, 2000, drive);
  const sysid::PrandtlIshlinskiiModel model(p);
  const sysid::Validation v = sysid::ValidateHysteresisModel(rec, model);
  REQUIRE(v.outputs.size() == 1);
  CHECK(v.outputs[0].output == "x");
  CHECK(v.model_kind == model.kind());
  CHECK(v.outputs[0].scores.fit_percent > 95);
  CHECK(v.outputs[0].autocorrelation.pass);  // the noise is uniform i.i.d.
  CHECK(v.outputs[0].cross_correlation.pass);
  sysid::PiParameters off = p;
  for (double& w : off.weights) w *= 0.8;
  const sysid::Validation bad =
      sysid::ValidateHysteresisModel(rec, sysid::PrandtlIshlinskiiModel(off));
  CHECK(bad.outputs[0].scores.fit_percent < v.outputs[0].scores.fit_percent);
  CHECK_FALSE(bad.outputs[0].cross_correlation.pass);
}

TEST_CASE("a perfect model's constant residual is reported untested, not refused", "[validate]") {
  PortableRandom rng(2);
  const Eigen::VectorXd u = Gaussian(rng, 200);
  const sysid::ResidualTestOptions o;
  const sysid::CorrelationTest a = sysid::AutocorrelationTest(Eigen::VectorXd::Zero(200), o);
  CHECK_FALSE(a.tested);
  CHECK(a.pass);
  CHECK(std::isnan(a.r[0]));
  CHECK(a.bound == Approx(2.58 / std::sqrt(200.0)));
  const sysid::CorrelationTest c =
      sysid::CrossCorrelationTest(u, Eigen::VectorXd::Constant(200, 1.5), o);
  CHECK_FALSE(c.tested);
  CHECK(c.verdict == "not tested: u is constant");
  CHECK(sysid::CrossCorrelationTest(u, u, o).tested);
}

TEST_CASE("the validation plots: measured over simulated, both correlations and one band",
          "[validate][report]") {
  const sysid::FrictionModel truth = sysid::FrictionModel::Paper();
  const sysid::Validation v = sysid::ValidateFrictionModel(FrictionRecording(truth, 5), truth);
  const auto plots = sysid::ValidationPlots(v, "rec");
  REQUIRE(plots.size() == 4);
  CHECK(plots[0].first == "rec_v.png");
  CHECK(plots[1].first == "rec_v_residual_tests.png");
  CHECK(plots[2].first == "rec_x.png");
  const sysid::PlotSpec& fit = plots[2].second;
  REQUIRE(fit.series.size() == 2);
  CHECK(fit.series[1].label == "measured");  // drawn last: on top
  CHECK(fit.series[0].label == "friction model");
  CHECK(fit.y_label == "x [mm]");
  CHECK(fit.series[1].y == 1e3 * v.outputs[1].measured);
  const sysid::PlotSpec& r = plots[3].second;
  REQUIRE(r.series.size() == 3);
  CHECK(r.series[0].y == v.outputs[1].autocorrelation.r);
  CHECK(r.series[1].y == v.outputs[1].cross_correlation.r);
  CHECK(r.series[2].label == "99 % band");
  CHECK(r.series[2].y[0] == v.outputs[1].autocorrelation.bound);
  CHECK(r.series[2].y[4] == -v.outputs[1].autocorrelation.bound);
}

TEST_CASE("sysid validate: the library's numbers, its flags' bounds and its refusals",
          "[validate][cli]") {
  TempDir dir;
  const sysid::FrictionModel truth = sysid::FrictionModel::Paper();
  const sysid::Recording rec = FrictionRecording(truth, 9);
  sysid::WriteRecording(dir / "rec.csv", rec);
  sysid::WriteModel(dir / "m.json", truth);
  auto r = RunCli({"validate", "--model", dir / "m.json", "--lags", "10", "--json", "--no-plots",
                   "-o", dir / "out", dir / "rec.csv"});
  REQUIRE(r.exit_code == 0);
  const auto j = nlohmann::json::parse(r.out);
  sysid::ValidationOptions o;
  o.residual.max_lag = 10;
  const sysid::Validation lib = sysid::ValidateFrictionModel(sysid::ReadRecording(dir / "rec.csv"),
                                                             sysid::ReadModel(dir / "m.json"), o);
  auto expected = nlohmann::json::parse(sysid::ToJson(lib));
  expected["source"] = dir / "rec.csv";
  CHECK(j["recordings"][0] == expected);
  CHECK(j["kind"] == "friction");
  CHECK(std::filesystem::exists(dir / "out/summary.json"));
  // With plots: v and x, each with its residual tests, listed in plots.json by the house rules.
  r = RunCli({"validate", "--model", dir / "m.json", "-o", dir / "plotted", dir / "rec.csv"});
  REQUIRE(r.exit_code == 0);
  CHECK(sysid::test::CheckPlotIndex(dir / "plotted") == 4);
  r = RunCli({"validate", "--model", dir / "m.json", dir / "rec.csv"});
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(r.out, Catch::Contains("nrmse_std") && Catch::Contains("nrmse_range") &&
                        Catch::Contains("fit [%]"));
  SECTION("--lags is bounded, by its name") {
    for (const char* lags : {"0", "1001"}) {
      r = RunCli({"validate", "--model", dir / "m.json", "--lags", lags, dir / "rec.csv"});
      CHECK(r.exit_code == 1);
      CHECK_THAT(r.err, Catch::Contains("--lags"));
    }
  }
  SECTION("exactly one model") {
    CHECK(RunCli({"validate", dir / "rec.csv"}).exit_code == 1);
    sysid::WriteFileAtomically(
        dir / "h.json", sysid::PrandtlIshlinskiiModel(sysid::test::KnownPiParameters()).ToJson());
    CHECK(RunCli({"validate", "--model", dir / "m.json", "--hysteresis", dir / "h.json",
                  dir / "rec.csv"})
              .exit_code == 1);
  }
  SECTION("a short recording: exit 2 naming it, nothing written") {
    sysid::WriteFileAtomically(dir / "short.csv", "t,u,x\n0,0,0\n0.001,1,0\n0.002,1,0\n");
    r = RunCli({"validate", "--model", dir / "m.json", "-o", dir / "bad", dir / "rec.csv",
                dir / "short.csv"});
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.err, Catch::Contains("short.csv") && Catch::Contains("samples"));
    CHECK_FALSE(std::filesystem::exists(dir / "bad"));
  }
}

TEST_CASE("sysid validate --hysteresis: the library's numbers on x, no motion note",
          "[validate][cli]") {
  TempDir dir;
  sysid::test::KnownPiDrive drive;
  drive.noise_width_m = 0.2e-6;
  drive.source = "pi.csv";
  sysid::WriteRecording(
      dir / "pi.csv", sysid::test::KnownPiRecording(sysid::test::KnownPiParameters(), 1500, drive));
  const sysid::PrandtlIshlinskiiModel model(sysid::test::KnownPiParameters());
  sysid::WriteFileAtomically(dir / "h.json", model.ToJson());
  const auto r = RunCli({"validate", "--hysteresis", dir / "h.json", "--json", dir / "pi.csv"});
  REQUIRE(r.exit_code == 0);
  CHECK(r.err.find("v, a:") == std::string::npos);  // x is scored; no velocity is derived
  const auto j = nlohmann::json::parse(r.out);
  CHECK(j["kind"] == "pi");
  const sysid::Validation lib = sysid::ValidateHysteresisModel(
      sysid::ReadRecording(dir / "pi.csv"), *sysid::ReadHysteresisModel(dir / "h.json"));
  auto expected = nlohmann::json::parse(sysid::ToJson(lib));
  expected["source"] = dir / "pi.csv";
  CHECK(j["recordings"][0] == expected);
  CHECK(j["recordings"][0]["outputs"].size() == 1);
}

TEST_CASE("a validation's JSON holds the keys validate.hpp documents, in that order",
          "[validate][json]") {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  sysid::Validation v;
  v.source = "held_out.csv";
  v.model_kind = "friction";
  v.t_s = Eigen::VectorXd::LinSpaced(7, 0.0, 0.6);
  sysid::OutputValidation o;
  o.output = "v";
  o.unit = "m/s";
  o.scores = {93.5, 1e-4, 0.065, nan};  // a constant y leaves nrmse_range undefined
  o.autocorrelation.name = "autocorrelation";
  o.autocorrelation.lags = {1, 2};
  o.autocorrelation.r = Eigen::Vector2d(0.25, nan);
  o.autocorrelation.bound = 0.5;
  o.autocorrelation.strong_bound = 0.75;
  o.autocorrelation.outside = 1;
  o.autocorrelation.allowed_outside = 2;
  o.autocorrelation.max_abs_r = 0.25;
  o.autocorrelation.pass = true;
  o.autocorrelation.verdict = "pass";
  o.cross_correlation = o.autocorrelation;
  o.cross_correlation.tested = false;
  v.outputs = {o};
  const auto j = nlohmann::ordered_json::parse(sysid::ToJson(v));
  auto keys = [](const nlohmann::ordered_json& object) {
    std::vector<std::string> k;
    for (auto it = object.begin(); it != object.end(); ++it) k.push_back(it.key());
    return k;
  };
  CHECK(keys(j) == std::vector<std::string>{"source", "model", "samples", "outputs"});
  CHECK(j["model"] == "friction");
  CHECK(j["samples"] == 7);
  const auto& out = j["outputs"][0];
  CHECK(keys(out) == std::vector<std::string>{"output", "unit", "fit_percent", "rmse",
                                              "nrmse_std", "nrmse_range", "autocorrelation",
                                              "cross_correlation"});
  CHECK(out["fit_percent"] == 93.5);
  CHECK(out["nrmse_range"].is_null());
  const auto& test = out["cross_correlation"];
  CHECK(keys(test) == std::vector<std::string>{"name", "lags", "r", "bound", "strong_bound",
                                               "outside", "allowed_outside", "max_abs_r",
                                               "tested", "pass", "verdict"});
  CHECK(test["lags"] == nlohmann::ordered_json::array({1, 2}));
  CHECK(test["r"] == nlohmann::ordered_json::array({0.25, nullptr}));
  CHECK(test["tested"] == false);
  CHECK(out["autocorrelation"]["tested"] == true);
}
