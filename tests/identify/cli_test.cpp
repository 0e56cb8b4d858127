// The identify, tune-delay, refine and dominance commands: JSON shapes, exit codes, no partial
// output on error.
#include <catch2/catch.hpp>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "identify/simulated_recording.hpp"
#include "identify/synthetic_motion.hpp"
#include "support/test_support.hpp"
#include "sysid/delay.hpp"
#include "sysid/io.hpp"
#include "sysid/model.hpp"

using sysid::test::RunCli;
using sysid::test::SourcePath;
using sysid::test::TempDir;

TEST_CASE("identify --json prints a valid model file with diagnostics", "[identify][cli]") {
  TempDir dir;
  const auto r = RunCli({"identify", "--table", SourcePath("datasets/paper/pulse_table.csv"),
                         "--json", "-o", dir / "m.json"});
  REQUIRE(r.exit_code == 0);
  const auto model = sysid::ParseModel(r.out, "stdout");  // stdout itself is a model file
  CHECK(std::round(model.a1p * 1e4) / 1e4 == 104.0154);
  const auto j = nlohmann::json::parse(r.out);
  CHECK(j["diagnostics"]["method"] == "pulse");
  CHECK(j["diagnostics"]["equations"].size() == 10);
  CHECK(j["diagnostics"]["r_diagonal"].size() == 4);
  CHECK(j["diagnostics"]["parameters"]["a2n"]["std_error"].get<double>() > 0);
  CHECK(sysid::ReadModel(dir / "m.json").a2n == model.a2n);
}

TEST_CASE("identify exits 3 for one-sided pulses and 1 or 2 for bad usage or input",
          "[identify][cli][errors]") {
  TempDir dir;
  sysid::test::WriteText(dir / "pos.csv", "u,v\n1.3,0.04465\n1.6,0.06222\n2.0,0.08519\n");
  auto r = RunCli({"identify", "--table", dir / "pos.csv", "-o", dir / "m.json"});
  CHECK(r.exit_code == 3);
  CHECK_THAT(r.err, Catch::Contains("a1n, a2n: no negative pulses"));
  CHECK_FALSE(std::filesystem::exists(dir / "m.json"));
  r = RunCli({"identify", "--method", "magic", "--table", dir / "pos.csv"});
  CHECK(r.exit_code == 1);
  sysid::test::WriteText(dir / "bad.csv", "u,v\n1.3,0.04465\n1.6,abc\n");
  r = RunCli({"identify", "--table", dir / "bad.csv"});
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Catch::Contains("bad.csv:3:"));
}

TEST_CASE("tune-delay and refine on a simulated pulse recording", "[identify][cli][sim]") {
  TempDir dir;
  const auto truth = sysid::FrictionModel::Paper();
  sysid::PulseTrainSpec spec;
  spec.amplitudes_v = {1.6, -2.3};
  spec.repeats = 1;
  spec.start_s = 0.1;
  sysid::test::RigSampling s;
  s.seed = 5;
  const auto rec =
      sysid::test::RigRecording(truth, sysid::MakePulseTrain(spec), spec.duration_s(), s);
  sysid::WriteRecording(dir / "rec.csv", rec);
  auto start = truth;
  start.tau_s = 0;
  sysid::WriteModel(dir / "start.json", start);
  auto r = RunCli({"tune-delay", "--model", dir / "start.json", "--tau-max", "0.01", "--json", "-o",
                   dir / "tuned.json", dir / "rec.csv"});
  REQUIRE(r.exit_code == 0);
  const auto j = nlohmann::json::parse(r.out);
  CHECK(j["tau"].get<double>() == Approx(0.0035).margin(1e-4));  // the 0.1 ms
  CHECK(j["evaluations"].get<int>() > 0);
  CHECK(j["cost"].get<double>() >= 0);
  CHECK(j["model"]["tau"] == j["tau"]);
  CHECK(sysid::ReadModel(dir / "tuned.json").tau_s == j["tau"].get<double>());
  CHECK(sysid::ToJson(sysid::DelayTuningResultFromJson(r.out, "stdout")) == r.out);  // library text
  r = RunCli({"refine", "--model", dir / "tuned.json", "--fix-a3", "--json", dir / "rec.csv"});
  REQUIRE(r.exit_code == 0);
  const auto refined = sysid::ParseModel(r.out, "stdout");
  CHECK(refined.a1p == Approx(truth.a1p).epsilon(0.01));  // 1 %: the pulse acceptance bound
  CHECK(refined.tau_s == Approx(truth.tau_s).margin(1e-4));
  CHECK(sysid::ToJson(sysid::RefineResultFromJson(r.out, "stdout")) == r.out);
}

TEST_CASE("dominance --json ranks variables and -o writes the table", "[dominance][cli]") {
  TempDir dir;
  const auto m = sysid::FrictionModel::Paper();
  auto rec = sysid::test::ClosedFormRecording(m, {{0.01, 0.5, 0.0}}, 4.0, 1000.0, 1e-7, 0, 1);
  sysid::WriteRecording(dir / "rec.csv", rec);
  sysid::WriteModel(dir / "m.json", m);
  auto r = RunCli({"dominance", "--model", dir / "m.json", "--json", "-o", dir / "t.csv",
                   dir / "rec.csv", dir / "rec.csv"});
  REQUIRE(r.exit_code == 0);
  const auto j = nlohmann::json::parse(r.out);
  CHECK(j["dominant"] == "velocity");
  REQUIRE(j["ranking"].size() == 2);
  CHECK(j["ranking"][0]["variable"] == "velocity");
  CHECK(j["ranking"][0]["ratio_to_top"] == 1.0);
  CHECK(j["ranking"][1]["rms"].get<double>() > 0);
  CHECK(j["recordings"].size() == 2);
  CHECK_THAT(sysid::test::ReadText(dir / "t.csv"), Catch::Contains(",1,velocity,"));
  r = RunCli({"dominance", "--model", dir / "m.json", "--candidate", "bad", dir / "rec.csv"});
  CHECK(r.exit_code == 1);
  CHECK_THAT(r.err, Catch::Contains("expected NAME=COLUMN"));
}
