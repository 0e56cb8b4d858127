#include <catch2/catch.hpp>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>

#include "support/test_support.hpp"
#include "sysid/compare.hpp"
#include "sysid/error.hpp"

namespace {
constexpr double kPi = 3.14159265358979323846;
}

TEST_CASE("prediction errors match hand computation", "[compare]") {
  Eigen::VectorXd u(4), p(4);
  u << 0, 1, 2, 3;
  p << 0, 1, 2, 5;  // one error of 2 V
  const auto e = sysid::ComputePredictionErrors(u, p);
  CHECK(e.rmse_v == Approx(1.0));  // sqrt(4 / 4)
  CHECK(e.peak_error_v == 2.0);
  CHECK(e.nrmse_range == Approx(1.0 / 3.0));
  CHECK(e.r2 == Approx(1.0 - 4.0 / 5.0));  // SST = 2.25+0.25+0.25+2.25
}

TEST_CASE("analytic inverse matches the closed form on a sinusoid", "[compare]") {
  // v = V sin(w t), a = V w cos(w t): the inverse evaluated at the exact delayed time is the
  // reference; linear interpolation of v errs by at most dt^2/8 max|v''| = dt^2/8 V w^2.
  const auto m = sysid::FrictionModel::Paper();
  const double dt = 1e-3, V = 0.05, w = 2 * kPi * 0.7;
  const int n = 3000;
  Eigen::VectorXd v(n), a(n);
  for (int k = 0; k < n; ++k) {
    v[k] = V * std::sin(w * k * dt);
    a[k] = V * w * std::cos(w * k * dt);
  }
  const Eigen::VectorXd u = sysid::AnalyticInverse(m, dt, v, a);
  const double bound = dt * dt / 8 * V * w * w * std::max(m.a1p, m.a1n) / m.a3;
  int checked = 0;
  for (int k = 10; k < n; ++k) {
    const double vd = V * std::sin(w * (k * dt - m.tau_s));
    const double vk = v[k];
    // Skip the few samples where v(t - tau) changes sign between grid points: a1 switches.
    if ((vd > 0) != (sysid::DelaySignal(v, dt, m.tau_s)[k] > 0)) continue;
    const double ref = m.InverseVoltage(a[k], vd, vk);
    REQUIRE(std::abs(u[k] - ref) <= bound * 1.0001);
    ++checked;
  }
  CHECK(checked > n - 20);
}

TEST_CASE("the inverses refuse v and a of different lengths (issue 29)", "[compare]") {
  // Before: lengths 10 / 5 gave 0.857 V where 1.857 V is right (a read past its end), and
  // 2e6 / 1 crashed. Each sample needs its own v and a, so a mismatch is the caller's data error.
  const auto m = sysid::FrictionModel::Paper();
  const sysid::NeuralNetwork net({{"v", "m/s", -0.1, 0.1}, {"a", "m/s^2", -1, 1}},
                                 {"u", "V", 0.0, 1.0}, 4);
  for (const auto& [nv, na] : {std::pair<int, int>{10, 5}, {2000000, 1}, {0, 3}}) {
    const Eigen::VectorXd v = Eigen::VectorXd::Constant(nv, 0.01);
    const Eigen::VectorXd a = Eigen::VectorXd::Zero(na);
    const std::string lengths = "v_mps has " + std::to_string(nv) + " values, a_mps2 has " +
                                std::to_string(na);
    CHECK_THROWS_AS(sysid::AnalyticInverse(m, 1e-3, v, a), sysid::InputError);
    CHECK_THROWS_WITH(sysid::AnalyticInverse(m, 1e-3, v, a),
                      Catch::Matchers::Contains("AnalyticInverse: " + lengths));
    CHECK_THROWS_AS(sysid::NetworkInverse(net, v, a), sysid::InputError);
    CHECK_THROWS_WITH(sysid::NetworkInverse(net, v, a),
                      Catch::Matchers::Contains("NetworkInverse: " + lengths));
  }
  const Eigen::VectorXd v = Eigen::VectorXd::Constant(10, 0.01), a = Eigen::VectorXd::Zero(10);
  for (const double dt : {0.0, -1e-3, std::nan("")}) {
    CHECK_THROWS_AS(sysid::AnalyticInverse(m, dt, v, a), sysid::OptionsError);
    CHECK_THROWS_WITH(sysid::AnalyticInverse(m, dt, v, a),
                      Catch::Matchers::Contains("Violated constraint: 0 < dt_s"));
  }
  // An invalid model is refused as by every other consumer (was u = inf for a3 = 0, NaN for a
  // NaN field).
  sysid::FrictionModel bad = m;
  bad.a3 = 0;
  CHECK_THROWS_WITH(sysid::AnalyticInverse(bad, 1e-3, v, a),
                    Catch::Matchers::Contains("a3 = 0. Violated constraint: a3 > 0"));
  bad = m;
  bad.a1p = std::nan("");
  CHECK_THROWS_WITH(sysid::AnalyticInverse(bad, 1e-3, v, a),
                    Catch::Matchers::Contains("a1p = nan. Violated constraint: finite"));
  // Finite, valid parameters that overflow (a3 = 1e-308 divides) are a numerical error, not
  // an inf that a comparison would score.
  bad = m;
  bad.a3 = 1e-308;
  CHECK_THROWS_AS(sysid::AnalyticInverse(bad, 1e-3, v, a), sysid::NumericalError);
  CHECK_THROWS_WITH(sysid::AnalyticInverse(bad, 1e-3, v, a),
                    Catch::Matchers::Contains("at sample 0") &&
                        Catch::Matchers::Contains("overflows"));
  sysid::NeuralNetwork huge({{"v", "m/s", -0.1, 0.1}}, {"u", "V", -2.0, 2.0}, 2);
  Eigen::VectorXd theta = Eigen::VectorXd::Constant(huge.parameter_count(), 1e308);
  huge.set_parameters(theta);
  CHECK_THROWS_WITH(sysid::NetworkInverse(huge, v, a),
                    Catch::Matchers::Contains("NetworkInverse: u = ") &&
                        Catch::Matchers::Contains("overflows"));
  // Equal lengths still work, and a steady slide needs u = (a1 v + a2) / a3 (a = 0, v const).
  const Eigen::VectorXd u = sysid::AnalyticInverse(m, 1e-3, v, a);
  CHECK(u[9] == Approx((m.a1p * 0.01 + m.a2p) / m.a3).epsilon(1e-12));  // closed form
}

TEST_CASE("comparison on data made by the analytic inverse scores it near zero", "[compare]") {
  const auto m = sysid::FrictionModel::Paper();
  const double dt = 1e-3, V = 0.04, w = 2 * kPi * 0.5;
  const int n = 2000;
  Eigen::VectorXd t(n), v(n), a(n);
  for (int k = 0; k < n; ++k) {
    t[k] = k * dt;
    v[k] = V * std::sin(w * t[k]);
    a[k] = V * w * std::cos(w * t[k]);
  }
  sysid::Recording rec;
  rec.source = "synthetic";
  rec.SetColumn("t", t);
  rec.SetColumn("u", sysid::AnalyticInverse(m, dt, v, a));
  rec.SetColumn("v", v);
  rec.SetColumn("a", a);
  // A network that outputs the constant 0.5 V: zero weights, b2 = 0 on the range [0, 1] V.
  sysid::NeuralNetwork net({{"v", "m/s", -0.1, 0.1}}, {"u", "V", 0.0, 1.0}, 4);
  const auto c = sysid::CompareInverseModels(rec, m, &net);
  CHECK(c.analytic.rmse_v < 1e-12);  // same formula, same samples
  REQUIRE(c.has_nn);
  const Eigen::VectorXd um = c.u_measured_v;
  const double rmse_const = std::sqrt((um.array() - 0.5).square().mean());
  CHECK(c.nn.rmse_v == Approx(rmse_const).epsilon(1e-12));
  CHECK(c.t_s.size() == n - 10);  // 5 samples trimmed at each end
}

TEST_CASE("sysid compare reports per-recording errors and writes its folder", "[compare][cli]") {
  sysid::test::TempDir dir;
  const auto m = sysid::FrictionModel::Paper();
  sysid::WriteModel(dir / "m.json", m);
  const double dt = 1e-3;
  const int n = 500;
  Eigen::VectorXd t(n), x(n), u(n);
  for (int k = 0; k < n; ++k) {
    t[k] = k * dt;
    x[k] = 0.01 * std::sin(2.0 * t[k]);
    u[k] = 1.0;
  }
  sysid::Recording rec;
  rec.SetColumn("t", t);
  rec.SetColumn("u", u);
  rec.SetColumn("x", x);
  sysid::WriteRecording(dir / "run.csv", rec);
  const auto r = sysid::test::RunCli({"compare", "--model", dir / "m.json", "--json", "-o",
                                      dir / "out", "--no-plots", dir / "run.csv"});
  REQUIRE(r.exit_code == 0);
  const auto j = nlohmann::json::parse(r.out);
  CHECK(j["recordings"][0]["samples"] == n - 10);
  CHECK(j["recordings"][0]["analytic"]["rmse_v"].get<double>() > 0);
  CHECK(sysid::test::ReadText(dir / "out/summary.csv").find("run,analytic,") != std::string::npos);
  {
    // summary.csv is the library's table of the same comparison.
    const auto c = sysid::CompareInverseModels(sysid::ReadRecording(dir / "run.csv"),
                                               sysid::ReadModel(dir / "m.json"), nullptr);
    CHECK(sysid::test::ReadText(dir / "out/summary.csv") == sysid::ComparisonTableCsv({c}));
    const std::string csv = sysid::ComparisonTableCsv({c});
    CHECK(csv.rfind("recording,model,rmse_v,peak_error_v,nrmse_range,r2\nrun,analytic,", 0) == 0);
    CHECK(csv.find(",nn,") == std::string::npos);  // no network: no nn row
  }
  // A bad recording: exit 2, nothing written.
  sysid::test::WriteText(dir / "bad.csv", "t,u,x\n0,1,0\n0.001,x,1\n");
  const auto bad = sysid::test::RunCli(
      {"compare", "--model", dir / "m.json", "-o", dir / "out2", dir / "run.csv", dir / "bad.csv"});
  CHECK(bad.exit_code == 2);
  CHECK_THAT(bad.err, Catch::Contains("bad.csv:3:7:"));
  CHECK_FALSE(std::filesystem::exists(dir / "out2"));
}
