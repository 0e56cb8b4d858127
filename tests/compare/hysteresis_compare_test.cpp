// Hysteresis models as inverse models in the comparison (`sysid compare --hysteresis`): the
// scored voltage is the model's own Invert, and a PI fitted to a known PI's data gives the
// recording's u back.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "support/known_pi.hpp"
#include "support/plot_index_check.hpp"
#include "support/test_support.hpp"
#include "sysid/compare.hpp"
#include "sysid/compare_hysteresis.hpp"
#include "sysid/error.hpp"
#include "sysid/hysteresis.hpp"
#include "sysid/io.hpp"

namespace {

using sysid::test::RunCli;
using sysid::test::TempDir;

constexpr double kDt = 5e-3;  // [s] 200 Hz, as the piezo recording

sysid::PiParameters TruthParameters() { return sysid::test::KnownPiParameters(); }

// t, u, x of the known PI driven by decaying loops (every operator reverses).
sysid::Recording TruthRecording(int n, const std::string& source = "run.csv") {
  sysid::test::KnownPiDrive drive;
  drive.sample_time_s = kDt;
  drive.source = source;
  return sysid::test::KnownPiRecording(TruthParameters(), n, drive);
}

}  // namespace

TEST_CASE("compare scores a hysteresis model's own inverse on the recording's x",
          "[compare][hysteresis]") {
  const sysid::Recording rec = TruthRecording(1500);
  const sysid::PrandtlIshlinskiiModel truth(TruthParameters());
  sysid::CompareOptions o;
  o.trim_samples = 7;
  const auto c = sysid::CompareInverseModels(rec, nullptr, nullptr, {{"pi:truth", &truth}}, o);
  CHECK_FALSE(c.has_analytic);
  CHECK_FALSE(c.has_nn);
  REQUIRE(c.hysteresis.size() == 1);
  const auto& h = c.hysteresis[0];
  CHECK(h.label == "pi:truth");
  CHECK(h.kind == "pi");
  // The scored voltage is PrandtlIshlinskiiModel::Invert on the whole x, trimmed: bit for bit.
  const Eigen::VectorXd direct = truth.Invert(rec.column("x"), kDt);
  REQUIRE(h.u_v.size() == rec.rows() - 14);
  CHECK(h.u_v == direct.segment(7, rec.rows() - 14));
  // The closed-form inverse of the model that made x gives the recording's u back.
  CHECK(h.errors.rmse_v < 1e-12);
  CHECK(h.errors.peak_error_v < 1e-11);
  // Errors as ComputePredictionErrors defines them, against a hand computation.
  const Eigen::VectorXd um = rec.column("u").segment(7, rec.rows() - 14);
  const Eigen::VectorXd off = h.u_v.array() + 0.01;
  const auto e = sysid::ComputePredictionErrors(um, off);
  CHECK(e.rmse_v == Approx(0.01).epsilon(1e-6));
  CHECK(e.nrmse_range == Approx(0.01 / (um.maxCoeff() - um.minCoeff())).epsilon(1e-6));
  // The traces carry the model's column under a MATLAB-safe name.
  const sysid::Recording traces = c.AsRecording();
  CHECK(traces.has("u_pi_truth"));
  CHECK_FALSE(traces.has("u_analytic"));
  const std::string csv = sysid::ComparisonTableCsv({c});
  CHECK(csv.rfind("recording,model,rmse_v,peak_error_v,nrmse_range,r2\nrun,pi:truth,", 0) == 0);
  const auto j = nlohmann::json::parse(sysid::ToJson(c));
  CHECK_FALSE(j.contains("analytic"));
  CHECK(j["hysteresis"][0]["label"] == "pi:truth");
  CHECK(j["hysteresis"][0]["rmse_v"].get<double>() == h.errors.rmse_v);
}

TEST_CASE("a PI fitted to a known PI's recording inverts it back in compare",
          "[compare][hysteresis]") {
  const sysid::Recording rec = TruthRecording(2000);
  sysid::PiFitOptions fo;
  fo.thresholds = TruthParameters().thresholds;  // the truth's structure: exact recovery
  const auto fitted = sysid::FitPrandtlIshlinskii({rec}, fo);
  const auto c = sysid::CompareInverseModels(rec, nullptr, nullptr, {{"pi:fit", fitted.get()}});
  REQUIRE(c.hysteresis.size() == 1);
  // u spans 3.4 V; the noise-free fit is exact to rounding of the least squares.
  CHECK(c.hysteresis[0].errors.rmse_v < 1e-8);
  CHECK(c.hysteresis[0].errors.r2 > 1 - 1e-12);
  // Beside the analytic inverse of a friction model: both scored on the same samples.
  const sysid::FrictionModel paper = sysid::FrictionModel::Paper();
  const auto both = sysid::CompareInverseModels(rec, &paper, nullptr,
                                                {{"pi:fit", fitted.get()}});
  CHECK(both.has_analytic);
  CHECK(both.hysteresis[0].u_v == c.hysteresis[0].u_v);
  CHECK(both.u_analytic_v.size() == both.hysteresis[0].u_v.size());
  CHECK_THROWS_AS(sysid::CompareInverseModels(rec, nullptr, nullptr, {}), sysid::OptionsError);
}

TEST_CASE("sysid compare --hysteresis scores model files and refuses what cannot invert",
          "[compare][hysteresis][cli]") {
  TempDir dir;
  const sysid::PrandtlIshlinskiiModel truth(TruthParameters());
  sysid::WriteFileAtomically(dir / "truth.json", truth.ToJson());
  sysid::WriteRecording(dir / "run.csv", TruthRecording(1200));
  auto r = RunCli({"compare", "--hysteresis", dir / "truth.json", "--json", "--no-plots",
                   "--traces", "mat", "-o", dir / "out", dir / "run.csv"});
  REQUIRE(r.exit_code == 0);
  const auto j = nlohmann::json::parse(r.out);
  CHECK_FALSE(j.contains("model"));
  CHECK(j["hysteresis"][0]["label"] == "pi:truth");
  const auto& row = j["recordings"][0]["hysteresis"][0];
  CHECK(row["kind"] == "pi");
  CHECK(row["rmse_v"].get<double>() < 1e-12);
  {
    // summary.csv and the traces are the library's comparison of the same files.
    const auto model = sysid::ReadHysteresisModel(dir / "truth.json");
    const auto c = sysid::CompareInverseModels(sysid::ReadRecording(dir / "run.csv"), nullptr,
                                               nullptr, {{"pi:truth", model.get()}});
    CHECK(sysid::test::ReadText(dir / "out/summary.csv") == sysid::ComparisonTableCsv({c}));
    sysid::ReadOptions any;
    any.required_columns.clear();
    any.any_of_columns.clear();
    const sysid::Recording traces = sysid::ReadRecording(dir / "out/run_traces.mat", any);
    CHECK((Eigen::VectorXd(traces.column("u_pi_truth")) - c.hysteresis[0].u_v).cwiseAbs().maxCoeff() ==
          0.0);
  }
  SECTION("the plots: the inverse, its error, a zoom and the u-x loop, one colour per model") {
    const sysid::FrictionModel paper = sysid::FrictionModel::Paper();
    sysid::WriteModel(dir / "m.json", paper);
    r = RunCli({"compare", "--hysteresis", dir / "truth.json", "--model", dir / "m.json", "-o",
                dir / "plots", dir / "run.csv"});
    REQUIRE(r.exit_code == 0);
    // 1200 samples trimmed by 5 at each end: above kCompareZoomAbove, so a zoom is drawn.
    CHECK(sysid::test::CheckPlotIndex(dir / "plots") == 4);
    const auto p = nlohmann::json::parse(sysid::test::ReadText(dir / "plots/plots.json"));
    CHECK(p["run.png"]["series"].size() == 3);
    CHECK(p["run_error.png"]["series"].size() == 2);
    CHECK(p["run_error.png"]["y_label"] == "u_model - u [V]");
    CHECK(p["run_zoom.png"]["series"][0]["points"] == 119);
    CHECK(p["run_loop.png"]["x_label"] == "x [um]");
    CHECK(p["run_loop.png"]["series"][0]["label"] == "pi:truth inverse");
    CHECK(p["run_loop.png"]["series"].size() == 2);  // the friction model has no u-x loop
  }
  SECTION("no inverse model at all is a usage error") {
    r = RunCli({"compare", dir / "run.csv"});
    CHECK(r.exit_code == 1);
    CHECK_THAT(r.err, Catch::Contains("--hysteresis"));
  }
  SECTION("a non-invertible model: exit 2 naming the file and the parameter, nothing written") {
    auto flat = nlohmann::json::parse(truth.ToJson());
    flat["polynomial"][0] = 0.0;
    sysid::test::WriteText(dir / "flat.json", flat.dump(2));
    r = RunCli({"compare", "--hysteresis", dir / "truth.json", "--hysteresis", dir / "flat.json",
                "-o", dir / "out2", dir / "run.csv"});
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.err, Catch::Contains("flat.json") && Catch::Contains("p0") &&
                          Catch::Contains("not invertible"));
    CHECK_FALSE(std::filesystem::exists(dir / "out2"));
  }
  SECTION(
      "an rdpi whose inverse diverges at the recording's step: exit 2, the recording named "
      "once") {
    // Error gain (q_0 + ... + q_n) max|u| / (dt p0) far above 1 at any step this test uses.
    sysid::test::WriteText(
        dir / "fast.json",
        R"({"kind":"rdpi","thresholds":[0.5,1.0,1.5],"weights":[2e-6,1e-6,0.5e-6],)"
        R"("polynomial":[4e-6],"rate_weights":[1e-7,2e-7,0,1e-7],"offset_m":-2e-4,)"
        R"("input_min_v":-1,"input_max_v":5})");
    r = RunCli({"compare", "--hysteresis", dir / "fast.json", "--no-plots", dir / "run.csv"});
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.err, Catch::Contains("not invertible at dt"));
    // The library's message already starts with the recording: the CLI does not add it again.
    const std::string run = dir / "run.csv";
    REQUIRE(r.err.find(run) != std::string::npos);
    CHECK(r.err.find(run, r.err.find(run) + 1) == std::string::npos);
  }
  SECTION("a reference outside the model's range: exit 2 naming recording, model and sample") {
    sysid::Recording far = TruthRecording(300, "far.csv");
    far.data(200, 2) = 1.0;  // 1 m: no input in the model's range reaches it
    sysid::WriteRecording(dir / "far.csv", far);
    r = RunCli({"compare", "--hysteresis", dir / "truth.json", "-o", dir / "out3", dir / "run.csv",
                dir / "far.csv"});
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.err, Catch::Contains("far.csv") && Catch::Contains("pi:truth") &&
                          Catch::Contains("reference sample 200"));
    CHECK_FALSE(std::filesystem::exists(dir / "out3"));
  }
  SECTION("two files with one label are refused before any work") {
    std::filesystem::create_directories(dir / "b");
    std::filesystem::copy_file(dir / "truth.json", dir / "b/truth.json");
    r = RunCli({"compare", "--hysteresis", dir / "truth.json", "--hysteresis", dir / "b/truth.json",
                dir / "run.csv"});
    CHECK(r.exit_code == 1);
    CHECK_THAT(r.err, Catch::Contains("pi:truth"));
  }
}
