// AddDerivatives / DescribeDerivative / UniformSampleInterval / DerivedRecordingToJson: what
// `sysid derive` calls.
#include <catch2/catch.hpp>

#include <cmath>
#include <nlohmann/json.hpp>

#include "sysid/error.hpp"
#include "sysid/io.hpp"
#include "sysid/motion.hpp"

namespace {

// x = c t^2 sampled every dt: central differences are exact in the interior (v = 2 c t, a = 2 c).
sysid::Recording Quadratic(int n, double dt, double c) {
  sysid::Recording r;
  r.source = "quadratic";
  Eigen::VectorXd t = Eigen::VectorXd::LinSpaced(n, 0.0, (n - 1) * dt);
  r.SetColumn("t", t);
  r.SetColumn("u", Eigen::VectorXd::Zero(n));
  r.SetColumn("x", (c * t.array().square()).matrix());
  return r;
}

}  // namespace

TEST_CASE("AddDerivatives: central differences of a quadratic are exact", "[motion]") {
  sysid::Recording r = Quadratic(50, 0.001, 3.0);
  const double dt = sysid::AddDerivatives(r, 0.001, {});
  CHECK(dt == 0.001);
  REQUIRE(r.has("v"));
  REQUIRE(r.has("a"));
  for (int k = 1; k < 49; ++k) {
    CHECK(r.column("v")[k] == Approx(6.0 * r.column("t")[k]).margin(1e-12));
    CHECK(r.column("a")[k] == Approx(6.0).epsilon(1e-6));
  }
}

TEST_CASE("AddDerivatives decimates first and returns the new interval", "[motion]") {
  sysid::Recording r = Quadratic(400, 0.001, 1.0);
  const double dt = sysid::AddDerivatives(r, 0.001, {}, 4);
  CHECK(dt == Approx(0.004));
  CHECK(r.rows() == 100);  // ceil(400 / 4)
  CHECK(r.column("t")[1] == Approx(0.004));
  try {
    sysid::Recording again = Quadratic(10, 0.001, 1.0);
    sysid::AddDerivatives(again, 0.001, {}, 0);
    FAIL("decimate = 0 accepted");
  } catch (const sysid::OptionsError& e) {
    CHECK(e.field() == "decimate");
  }
  sysid::DerivativeOptions bad;
  bad.method = sysid::DerivativeMethod::kButterworthCentral;
  bad.cutoff_hz = 400;  // above the decimated Nyquist 125 Hz
  try {
    sysid::Recording again = Quadratic(400, 0.001, 1.0);
    sysid::AddDerivatives(again, 0.001, bad, 4);
    FAIL("a cut-off above the decimated Nyquist frequency was accepted");
  } catch (const sysid::OptionsError& e) {
    CHECK(e.field() == "cutoff_hz");
  }
}

TEST_CASE("DescribeDerivative names the method's own settings", "[motion]") {
  sysid::DerivativeOptions d;
  CHECK(sysid::DescribeDerivative(d) == "method=central");
  d.method = sysid::DerivativeMethod::kButterworthCentral;
  d.cutoff_hz = 20;
  d.butterworth_order = 2;
  CHECK(sysid::DescribeDerivative(d, 5) == "method=butterworth cutoff_hz=20 order=2 decimate=5");
  d.method = sysid::DerivativeMethod::kSavitzkyGolay;
  d.savgol_window = 11;
  d.savgol_order = 3;
  CHECK(sysid::DescribeDerivative(d, 1) == "method=savgol window=11 order=3");
}

TEST_CASE("UniformSampleInterval returns the median interval or names the worst row",
          "[motion]") {
  sysid::Recording r = Quadratic(20, 0.002, 1.0);
  CHECK(sysid::UniformSampleInterval(r, 0.01) == Approx(0.002));
  Eigen::VectorXd t = r.column("t");
  t[7] += 0.0005;  // t[7] - t[6] is 25 % long (and t[8] - t[7] 25 % short)
  r.SetColumn("t", t);
  try {
    sysid::UniformSampleInterval(r, 0.01);
    FAIL("irregular sampling accepted");
  } catch (const sysid::InputError& e) {
    CHECK_THAT(e.what(), Catch::StartsWith("quadratic:"));
    CHECK_THAT(e.what(), Catch::Contains("irregular sampling"));
  }
  CHECK(sysid::UniformSampleInterval(r, 0.3) == Approx(0.002));
}

TEST_CASE("DerivedRecordingToJson summarises v and a of the extended recording", "[motion][json]") {
  // x = c t^2 with c = 0.5: v = t (ramp 0..(n-1) dt), a = 1 everywhere (central differences
  // and their one-sided ends are exact on a quadratic).
  const int n = 101;
  const double dt = 0.01;
  sysid::Recording r = Quadratic(n, dt, 0.5);
  r.metadata.emplace_back("derive", "method=central resample_hz=100");
  sysid::AddDerivatives(r, dt, {});
  const auto j = nlohmann::json::parse(sysid::DerivedRecordingToJson(r, dt, {}));
  CHECK(j["method"] == "central");
  CHECK(j["settings"] == "method=central resample_hz=100");  // the recording's own note
  CHECK(j["rows"] == n);
  CHECK(j["columns"].back() == "a");
  CHECK(j["sample_rate_hz"].get<double>() == Approx(100));
  CHECK(j["v_mps"]["min"].get<double>() == Approx(0).margin(1e-12));
  CHECK(j["v_mps"]["max"].get<double>() == Approx(1.0));
  // rms of the ramp 0..1 sampled at n points: sqrt(sum k^2 / n) / (n - 1).
  CHECK(j["v_mps"]["rms"].get<double>() ==
        Approx(std::sqrt((n - 1) * (2.0 * n - 1) / 6.0) / (n - 1)).epsilon(1e-12));
  CHECK(j["a_mps2"]["min"].get<double>() == Approx(1.0));
  CHECK(j["a_mps2"]["rms"].get<double>() == Approx(1.0));
  sysid::Recording bare = Quadratic(5, dt, 1.0);
  CHECK_THROWS_AS(sysid::DerivedRecordingToJson(bare, dt, {}), sysid::InputError);
}
