#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <tuple>

#include "support/known_pi.hpp"
#include "support/test_support.hpp"
#include "sysid/hysteresis.hpp"
#include "sysid/hysteresis_bouc_wen.hpp"
#include "sysid/io.hpp"

namespace {

using sysid::test::RunCli;
using sysid::test::TempDir;

// A recording of the known PI model (t, u, x) at 200 Hz.
sysid::Recording PiRecording(int n) {
  return sysid::test::KnownPiRecording(sysid::test::KnownPiParameters(), n);
}

}  // namespace

TEST_CASE("sysid hysteresis fit, simulate and invert round-trip a PI recording", "[hysteresis]") {
  TempDir dir;
  const sysid::Recording rec = PiRecording(2000);
  sysid::WriteRecording(dir / "rec.csv", rec);
  auto fit = RunCli({"hysteresis", "fit", "--model", "pi", "--operators", "6", "--json",
                     dir / "rec.csv", "-o", dir / "h.json"});
  REQUIRE(fit.exit_code == 0);
  const auto summary = nlohmann::json::parse(fit.out);
  CHECK(summary["kind"] == "pi");
  CHECK(summary["parameters"].size() == 8);  // p0, w1..w6, c
  CHECK(summary["training_rms_m"].get<double>() < 1e-7);  // 6 uniform operators approximate 3
  auto sim = RunCli({"hysteresis", "simulate", "--model", dir / "h.json", dir / "rec.csv", "-o",
                     dir / "sim.csv"});
  REQUIRE(sim.exit_code == 0);
  const sysid::Recording s = sysid::ReadRecording(dir / "sim.csv", {{"t", "u", "x_model"}, {}});
  CHECK(s.rows() == rec.rows());
  // Invert the model's own output: the recording's u comes back (closed form, 1e-9 V: the CSV's
  // 17 digits and the model's weights).
  sysid::Recording ref;
  ref.names = {"t", "x"};
  ref.data.resize(rec.rows(), 2);
  ref.data.col(0) = rec.column("t");
  ref.data.col(1) = s.column("x_model");
  sysid::WriteRecording(dir / "ref.csv", ref);
  auto inv = RunCli({"hysteresis", "invert", "--model", dir / "h.json", dir / "ref.csv", "-o",
                     dir / "u.csv"});
  REQUIRE(inv.exit_code == 0);
  const sysid::Recording back = sysid::ReadRecording(dir / "u.csv", {{"t", "x", "u"}, {}});
  CHECK((back.column("u") - rec.column("u")).cwiseAbs().maxCoeff() < 1e-9);
}

TEST_CASE("sysid hysteresis refuses bad input naming the field, writing nothing",
          "[hysteresis]") {
  TempDir dir;
  sysid::WriteRecording(dir / "rec.csv", PiRecording(600));
  SECTION("operators above the bound: usage error") {
    auto r = RunCli({"hysteresis", "fit", "--model", "pi", "--operators", "201", dir / "rec.csv",
                     "-o", dir / "h.json"});
    CHECK(r.exit_code == 1);
    CHECK_THAT(r.err, Catch::Contains("--operators"));
    CHECK_FALSE(std::filesystem::exists(dir / "h.json"));
  }
  SECTION("nn-operators --operators or --hidden past its bound: usage error before reading") {
    // The recording does not exist: an exit-1 message naming the flag shows the option was
    // refused before any file was read (else: exit 2 naming the missing file).
    for (const auto& [flag, value, field] :
         {std::tuple{"--operators", "1000000000", "operators = 1000000000"},
          std::tuple{"--hidden", "1000000000", "hidden = 1000000000"},
          std::tuple{"--epochs", "0", "max_epochs = 0"}}) {
      INFO(flag);
      auto r = RunCli({"hysteresis", "fit", "--model", "nn-operators", flag, value,
                       dir / "missing.csv", "-o", dir / "h.json"});
      CHECK(r.exit_code == 1);
      CHECK_THAT(r.err, Catch::Contains(std::string(flag) + ": ") && Catch::Contains(field));
      CHECK_FALSE(std::filesystem::exists(dir / "h.json"));
    }
  }
  SECTION("negative or unsorted thresholds on the command line: usage error") {
    for (const char* list : {"0.5,0.2", "-0.1,0.5"}) {
      auto r = RunCli({"hysteresis", "fit", "--model", "pi", "--thresholds", list, dir / "rec.csv",
                       "-o", dir / "h.json"});
      CHECK(r.exit_code == 1);
      CHECK_THAT(r.err, Catch::Contains("--thresholds") && Catch::Contains("thresholds["));
      CHECK_FALSE(std::filesystem::exists(dir / "h.json"));
    }
    auto ok = RunCli({"hysteresis", "fit", "--model", "pi", "--thresholds", "0.5,1,1.5", "--json",
                      dir / "rec.csv", "-o", dir / "h.json"});
    REQUIRE(ok.exit_code == 0);
    // The recording's own thresholds: the fit is exact up to rounding (1e-12 of 1e-4 m).
    CHECK(nlohmann::json::parse(ok.out)["training_rms_m"].get<double>() < 1e-15);
  }
  SECTION("model files with unsorted or negative thresholds, non-finite or missing values") {
    REQUIRE(RunCli({"hysteresis", "fit", "--model", "pi", "--operators", "3", dir / "rec.csv",
                    "-o", dir / "h.json"}).exit_code == 0);
    const std::string good = sysid::test::ReadText(dir / "h.json");
    auto j = nlohmann::json::parse(good);
    struct Case {
      std::string what;
      std::function<void(nlohmann::json&)> edit;
      std::string field;
    };
    const std::vector<Case> cases = {
        {"unsorted", [](nlohmann::json& m) { std::swap(m["thresholds"][0], m["thresholds"][1]); }, "thresholds[1]"},
        {"negative", [](nlohmann::json& m) { m["thresholds"][0] = -0.1; }, "thresholds[0]"},
        {"null weight", [](nlohmann::json& m) { m["weights"][2] = nullptr; }, "weights[2]"},
        {"too many", [](nlohmann::json& m) {
           m["thresholds"] = nlohmann::json::array();
           for (int i = 1; i <= 201; ++i) m["thresholds"].push_back(0.01 * i);
         }, "thresholds"},
    };
    for (const auto& c : cases) {
      INFO(c.what);
      nlohmann::json bad = j;
      c.edit(bad);
      sysid::test::WriteText(dir / "bad.json", bad.dump(2));
      auto r = RunCli({"hysteresis", "simulate", "--model", dir / "bad.json", dir / "rec.csv", "-o",
                       dir / "out.csv"});
      CHECK(r.exit_code == 2);
      CHECK_THAT(r.err, Catch::Contains("bad.json:") && Catch::Contains(c.field));
      CHECK_FALSE(std::filesystem::exists(dir / "out.csv"));
    }
    SECTION("a non-invertible model asked to invert, and a reference out of range") {
      nlohmann::json flat = j;
      flat["polynomial"][0] = 0.0;
      sysid::test::WriteText(dir / "flat.json", flat.dump(2));
      const sysid::Recording rec = PiRecording(2);
      sysid::test::WriteText(dir / "ref.csv", "t,x\n0," + std::to_string(rec.data(0, 2)) + "\n0.005," +
                                                  std::to_string(rec.data(1, 2)) + "\n0.01,1.0\n");
      auto r = RunCli({"hysteresis", "invert", "--model", dir / "flat.json", dir / "ref.csv", "-o",
                       dir / "u.csv"});
      CHECK(r.exit_code == 2);
      CHECK_THAT(r.err, Catch::Contains("p0"));
      CHECK_FALSE(std::filesystem::exists(dir / "u.csv"));
      r = RunCli({"hysteresis", "invert", "--model", dir / "h.json", dir / "ref.csv", "-o", dir / "u.csv"});
      CHECK(r.exit_code == 2);
      CHECK_THAT(r.err, Catch::Contains("ref.csv") && Catch::Contains("reference sample 2"));
      CHECK_FALSE(std::filesystem::exists(dir / "u.csv"));
    }
  }
  SECTION("a recording without x") {
    sysid::test::WriteText(dir / "nox.csv", "t,u\n0,1\n0.005,2\n0.01,3\n");
    auto r = RunCli({"hysteresis", "fit", "--model", "pi", dir / "nox.csv", "-o", dir / "h.json"});
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.err, Catch::Contains("nox.csv") && Catch::Contains("x"));
    CHECK_FALSE(std::filesystem::exists(dir / "h.json"));
  }
}

TEST_CASE("sysid hysteresis simulate --periodic writes the periodic steady state", "[hysteresis]") {
  TempDir dir;
  sysid::WriteRecording(dir / "rec.csv", PiRecording(1200));
  REQUIRE(RunCli({"hysteresis", "fit", "--model", "pi", "--operators", "4", dir / "rec.csv", "-o",
                  dir / "h.json"}).exit_code == 0);
  // One period of a sine from 0 V: from rest the first period holds the initial loading
  // curve; the steady state is the last of several periods simulated in a row.
  const int n = 400;
  Eigen::VectorXd u(n);
  for (int k = 0; k < n; ++k) u[k] = 1.8 + 1.5 * std::sin(2 * M_PI * k / n);
  sysid::Recording one;
  one.names = {"t", "u"};
  one.data.resize(n, 2);
  for (int k = 0; k < n; ++k) one.data.row(k) << k * 5e-3, u[k];
  sysid::WriteRecording(dir / "period.csv", one);
  REQUIRE(RunCli({"hysteresis", "simulate", "--model", dir / "h.json", dir / "period.csv",
                  "--periodic", "-o", dir / "steady.csv"}).exit_code == 0);
  const auto model = sysid::PrandtlIshlinskiiFromJson(sysid::test::ReadText(dir / "h.json"), "h.json");
  const Eigen::VectorXd three = model->Simulate(u.replicate(3, 1), 5e-3);
  const sysid::Recording steady = sysid::ReadRecording(dir / "steady.csv", {{"t", "u", "x_model"}, {}});
  // A PI settles after one period (every operator has met both extremes); the CSV keeps 17
  // significant digits.
  CHECK((steady.column("x_model") - three.tail(n)).cwiseAbs().maxCoeff() < 1e-18);
  CHECK((three.head(n) - three.tail(n)).cwiseAbs().maxCoeff() > 1e-8);  // the transient exists
}

TEST_CASE("sysid hysteresis: bouc-wen-piezo through the dispatch (fit, model file, simulate, invert)",
          "[hysteresis][bouc-wen]") {
  TempDir dir;
  const sysid::Recording rec = PiRecording(1200);
  sysid::WriteRecording(dir / "rec.csv", rec);
  // The CLI's door to FitBoucWen and BoucWenModelFromJson: the file written by `fit` reads
  // back, its simulation follows the recording as closely as the fit reported (the PI loop
  // is not a Bouc-Wen loop, so the reference is the fit's own RMS, not zero), and `invert`
  // of that simulation gives u back (the piezo form's inverse is exact, 1e-9 V of 3.6 V).
  auto fit = RunCli({"hysteresis", "fit", "--model", "bouc-wen-piezo", "--json", dir / "rec.csv",
                     "-o", dir / "bw.json"});
  INFO(fit.err);
  REQUIRE(fit.exit_code == 0);
  const double rms = nlohmann::json::parse(fit.out)["training_rms_m"].get<double>();
  CHECK(nlohmann::json::parse(sysid::test::ReadText(dir / "bw.json"))["kind"] == "bouc-wen-piezo");
  REQUIRE(RunCli({"hysteresis", "simulate", "--model", dir / "bw.json", dir / "rec.csv", "-o",
                  dir / "bw_sim.csv"}).exit_code == 0);
  const sysid::Recording sim = sysid::ReadRecording((dir / "bw_sim.csv"),
                                                    sysid::ReadOptions{{"t", "u", "x_model"}, {}, true});
  const Eigen::VectorXd diff = sim.column("x_model") - rec.column("x");
  CHECK(std::sqrt(diff.squaredNorm() / static_cast<double>(diff.size())) ==
        Approx(rms).epsilon(1e-6));
  sysid::Recording ref;
  ref.names = {"t", "x"};
  ref.data.resize(sim.rows(), 2);
  ref.data.col(0) = sim.column("t");
  ref.data.col(1) = sim.column("x_model");
  sysid::WriteRecording((dir / "bw_ref.csv"), ref);
  auto inv = RunCli({"hysteresis", "invert", "--model", dir / "bw.json", dir / "bw_ref.csv", "-o",
                     dir / "bw_u.csv"});
  INFO(inv.err);
  REQUIRE(inv.exit_code == 0);
  const sysid::Recording u = sysid::ReadRecording((dir / "bw_u.csv"),
                                                  sysid::ReadOptions{{"t", "u"}, {}, true});
  CHECK((u.column("u") - rec.column("u")).cwiseAbs().maxCoeff() < 1e-9);
  }

TEST_CASE("sysid hysteresis fit: the Bouc-Wen simulation flags reach the model file",
          "[hysteresis][cli]") {
  TempDir dir;
  sysid::WriteRecording(dir / "rec.csv", PiRecording(600));
  // The piezo form fitted with a held input: the model file says how it simulates.
  auto r = RunCli({"hysteresis", "fit", "--model", "bouc-wen-piezo", "--input", "hold",
                   "--starts", "2", "--threads", "1", dir / "rec.csv", "-o", dir / "bw.json"});
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const auto j = nlohmann::json::parse(sysid::test::ReadText(dir / "bw.json"));
  CHECK(j["simulation"]["integrator"] == "cvode");
  CHECK(j["simulation"]["input"] == "hold");
  CHECK_THAT(j["fit"]["message"].get<std::string>(), Catch::Contains("2 starts"));
  // The benchmark's chain is the mechanical form's only; bad values name the flag.
  r = RunCli({"hysteresis", "fit", "--model", "pi", "--integrator", "benchmark-chain",
              dir / "rec.csv", "-o", dir / "pi.json"});
  CHECK(r.exit_code == 1);
  CHECK_THAT(r.err, Catch::Contains("--integrator"));
  r = RunCli({"hysteresis", "fit", "--model", "bouc-wen-piezo", "--starts", "0", dir / "rec.csv",
              "-o", dir / "pi.json"});
  CHECK(r.exit_code == 1);
  CHECK_THAT(r.err, Catch::Contains("--starts"));
  CHECK_FALSE(std::filesystem::exists(dir / "pi.json"));
  r = RunCli({"hysteresis", "fit", "--model", "bouc-wen-piezo", "--max-time", "-1", dir / "rec.csv",
              "-o", dir / "pi.json"});
  CHECK(r.exit_code == 1);
  CHECK_THAT(r.err, Catch::Contains("--max-time"));
  CHECK_FALSE(std::filesystem::exists(dir / "pi.json"));
}

TEST_CASE("sysid hysteresis fit: bouc-wen's default is the fixed step, its input chosen",
          "[hysteresis][cli]") {
  // A swept force on the benchmark's system, simulated by CVODE, not periodic: the default fit
  // takes the fixed step on the linear input, and its model file says so.
  TempDir dir;
  const double dt = 1.0 / 750;
  Eigen::VectorXd u(600);
  for (Eigen::Index i = 0; i < u.size(); ++i) {
    const double t = static_cast<double>(i) * dt;
    u[i] = 20 * (1 + t) * std::sin(2 * M_PI * (5 + 20 * t) * t);
  }
  const Eigen::VectorXd x = sysid::MechanicalBoucWen({}).Simulate(u, dt);
  sysid::Recording rec;
  rec.names = {"t", "u", "x"};
  rec.data.resize(u.size(), 3);
  for (Eigen::Index i = 0; i < u.size(); ++i)
    rec.data.row(i) << static_cast<double>(i) * dt, u[i], x[i];
  sysid::WriteRecording(dir / "rec.csv", rec);
  auto r = RunCli({"hysteresis", "fit", "--model", "bouc-wen", "--starts", "1", dir / "rec.csv",
                   "-o", dir / "bw.json"});
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const auto j = nlohmann::json::parse(sysid::test::ReadText(dir / "bw.json"));
  CHECK(j["simulation"]["integrator"] == "fixed-step");
  CHECK(j["simulation"]["input"] == "linear");
  CHECK(j["simulation"]["upsampling"].get<int>() >= 2);
  const std::string message = j["fit"]["message"].get<std::string>();
  CHECK_THAT(message, Catch::Contains("input linear between samples (chosen: not every"));
  CHECK_THAT(message, Catch::Contains("the final model against CVODE rtol 1e-9"));
  CHECK_THAT(message, Catch::Contains("Jacobian by forward sensitivities"));
  // A held input is CVODE's; the tolerance is bounded.
  r = RunCli({"hysteresis", "fit", "--model", "bouc-wen", "--integrator", "fixed-step", "--input",
              "hold", dir / "rec.csv", "-o", dir / "h.json"});
  CHECK(r.exit_code == 1);
  CHECK_THAT(r.err, Catch::Contains("--integrator fixed-step"));
  r = RunCli({"hysteresis", "fit", "--model", "bouc-wen", "--step-tolerance", "0", dir / "rec.csv",
              "-o", dir / "h.json"});
  CHECK(r.exit_code == 1);
  CHECK_THAT(r.err, Catch::Contains("--step-tolerance"));
  r = RunCli({"hysteresis", "fit", "--model", "bouc-wen-piezo", "--integrator", "fixed-step",
              dir / "rec.csv", "-o", dir / "h.json"});
  CHECK(r.exit_code == 1);
  CHECK_FALSE(std::filesystem::exists(dir / "h.json"));
}

TEST_CASE("sysid hysteresis fit: --progress reports the Bouc-Wen fit, --max-time stops it",
          "[hysteresis][cli]") {
  TempDir dir;
  sysid::WriteRecording(dir / "rec.csv", PiRecording(600));
  auto r = RunCli({"hysteresis", "fit", "--model", "bouc-wen-piezo", "--starts", "2", "--threads",
                   "1", "--progress", dir / "rec.csv", "-o", dir / "bw.json"});
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(r.err, Catch::Contains("fitting bouc-wen-piezo to 600 samples (2 starts)"));
  CHECK_THAT(r.err, Catch::Contains("bouc-wen-piezo start 2/2: iteration 1, training RMS "));
  CHECK_THAT(r.err, Catch::Contains("bouc-wen-piezo final fit: iteration 0, training RMS "));
  // Without --progress (stderr is not a terminal here) nothing is reported.
  r = RunCli({"hysteresis", "fit", "--model", "bouc-wen-piezo", "--starts", "2", "--threads", "1",
              dir / "rec.csv", "-o", dir / "bw2.json"});
  CHECK(r.exit_code == 0);
  CHECK(r.err.empty());
  // A bound of 1 ns: a model file all the same, with the reason; exit 0.
  r = RunCli({"hysteresis", "fit", "--model", "bouc-wen-piezo", "--max-time", "1e-9", "--json",
              dir / "rec.csv", "-o", dir / "bw3.json"});
  CHECK(r.exit_code == 0);
  const auto j = nlohmann::json::parse(sysid::test::ReadText(dir / "bw3.json"));
  CHECK(j["fit"]["converged"] == false);
  CHECK_THAT(j["fit"]["message"].get<std::string>(),
             Catch::Contains("stopped at the time bound max_time_s = 1e-09 s"));
}
