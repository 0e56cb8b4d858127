// The pipeline on a stack data set (no pulse test; recordings t, u, x): the hysteresis models'
// table, fitted on the first 40 % of each recording and scored on the rest.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "support/known_pi.hpp"
#include "support/plot_index_check.hpp"
#include "support/test_support.hpp"
#include "sysid/compare_stack.hpp"
#include "sysid/error.hpp"
#include "sysid/hysteresis.hpp"
#include "sysid/io.hpp"
#include "sysid/pipeline.hpp"
#include "sysid/report.hpp"

using sysid::test::RunCli;
using sysid::test::TempDir;

namespace {

constexpr double kDt = 5e-3;  // [s]

// A known classical PI (its own parameters) driven by faster decaying loops, with 2 nm of
// uniform noise on x (seeded).
sysid::Recording StackRecording(int n) {
  sysid::PiParameters p;
  p.thresholds = {0.4, 0.9, 1.4};
  p.weights = {3e-6, 1.5e-6, 0.7e-6};
  p.polynomial = {5e-6};
  p.offset_m = -1.1e-4;
  p.input_min_v = 0;
  p.input_max_v = 3.6;
  sysid::test::KnownPiDrive drive;
  drive.period_samples = 200;
  drive.envelope_samples = 300;
  drive.depth = 0.35;
  drive.sample_time_s = kDt;
  drive.noise_width_m = 2e-9;
  return sysid::test::KnownPiRecording(p, n, drive);
}

}  // namespace

TEST_CASE("a folder or manifest without a pulse test is a stack data set", "[pipeline][stack]") {
  TempDir dir;
  sysid::WriteRecording(dir / "piezo.csv", StackRecording(50));
  auto in = sysid::PipelineInputs::FromDirectory(dir.path().string());
  REQUIRE(in.IsStack());
  CHECK(in.stack.size() == 1);
  CHECK(in.stack[0].find("piezo.csv") != std::string::npos);
  CHECK(in.pulses.empty());
  // A stage folder missing its pulse test is still the stage's error, not a stack.
  TempDir stage;
  sysid::WriteRecording(stage / "training.csv", StackRecording(50));
  CHECK_THROWS_WITH(sysid::PipelineInputs::FromDirectory(stage.path().string()),
                    Catch::Contains("missing pulse recordings"));
  // The manifest names the stack's recordings; a stage's keys beside them are refused.
  sysid::test::WriteText(dir / "manifest.json", "{\"stack\": [\"piezo.csv\"], \"note\": \"x\"}");
  in = sysid::PipelineInputs::FromDirectory(dir.path().string());
  REQUIRE(in.IsStack());
  CHECK(in.stack[0] == (std::filesystem::path(dir.path()) / "piezo.csv").string());
  sysid::test::WriteText(dir / "manifest.json",
                         "{\"stack\": [\"piezo.csv\"],\n \"pulses\": [\"p.csv\"]}");
  CHECK_THROWS_WITH(sysid::PipelineInputs::FromDirectory(dir.path().string()),
                    Catch::Contains("manifest.json:2:2:") && Catch::Contains("pulses"));
  sysid::test::WriteText(dir / "manifest.json", "{\"stack\": []}");
  CHECK_THROWS_WITH(sysid::PipelineInputs::FromDirectory(dir.path().string()),
                    Catch::Contains("stack") && Catch::Contains("non-empty"));
}

TEST_CASE("the training part is the first 40 % of the rows and both parts need 2 rows",
          "[pipeline][stack]") {
  const sysid::Recording rec = StackRecording(1001);
  const sysid::Recording part = sysid::TrainingPart(rec, 0.4);
  CHECK(part.rows() == 400);  // round(400.4)
  CHECK(part.data == rec.data.topRows(400));
  CHECK_THROWS_AS(sysid::TrainingPart(StackRecording(3), 0.4), sysid::InputError);
  CHECK_THROWS_AS(sysid::TrainingPart(rec, 1.0), sysid::OptionsError);
}

TEST_CASE("the stack pipeline scores each model as fitting and simulating it directly does",
          "[pipeline][stack]") {
  const sysid::Recording rec = StackRecording(2000);
  TempDir dir;
  sysid::WriteRecording(dir / "stack.csv", rec);
  sysid::PipelineInputs in;
  in.root = dir.path().string();
  in.stack = {(dir / "stack.csv")};
  sysid::PipelineOptions o;
  o.threads = 2;
  const sysid::PipelineResult r = sysid::RunPipeline(in, o);
  REQUIRE(r.stack_models.size() == sysid::StackModelSpecs().size());
  REQUIRE(r.stack_dominance.size() == 1);
  CHECK(r.stack_dominance[0].dominant == "x");  // a stack: displacement carries the voltage
  const auto& pi = r.stack_models[0];
  CHECK(pi.kind == "pi");
  CHECK(pi.parameters == 22);  // p0, 20 weights, offset
  CHECK(pi.train_samples == 800);
  CHECK(pi.test_samples == 1200);
  // An independent computation of the same row: fit on the first 800 rows, simulate and invert
  // the whole recording, score rows 800.. (RMS and population std by hand).
  sysid::PiFitOptions fo;
  fo.operators = 20;
  const auto direct = sysid::FitPrandtlIshlinskii({sysid::TrainingPart(rec, 0.4)}, fo);
  const Eigen::VectorXd xm = direct->Simulate(rec.column("u"), kDt);
  const Eigen::VectorXd um = direct->Invert(rec.column("x"), kDt);
  double se = 0, su = 0, mx = 0, mu = 0;
  for (int k = 800; k < 2000; ++k) mx += rec.data(k, 2) / 1200, mu += rec.data(k, 1) / 1200;
  double vx = 0, vu = 0;
  for (int k = 800; k < 2000; ++k) {
    se += std::pow(xm[k] - rec.data(k, 2), 2) / 1200;
    su += std::pow(um[k] - rec.data(k, 1), 2) / 1200;
    vx += std::pow(rec.data(k, 2) - mx, 2) / 1200;
    vu += std::pow(rec.data(k, 1) - mu, 2) / 1200;
  }
  CHECK(pi.forward_rms_m == Approx(std::sqrt(se)).epsilon(1e-10));
  CHECK(pi.forward_nrmse_std == Approx(std::sqrt(se / vx)).epsilon(1e-8));
  CHECK(pi.inverse_rms_v == Approx(std::sqrt(su)).epsilon(1e-10));
  CHECK(pi.inverse_nrmse_std == Approx(std::sqrt(su / vu)).epsilon(1e-8));
  // 20 uniform operators approximate the 3-operator truth on data it never saw.
  CHECK(pi.forward_nrmse_std < 0.02);
  CHECK(pi.inverse_nrmse_std < 0.02);
  for (const auto& s : r.stack_models) {
    INFO(s.label << ": " << s.error << s.inverse_error);
    CHECK(s.error.empty());
    CHECK(s.forward_nrmse_std < 0.5);  // even the static network, a line through the loop
    if (s.inverse_error.empty()) CHECK(s.inverse_nrmse_std < 0.5);
  }
  // The report's figures, computed here: the scored part's first 600 rows (800..1399) of the
  // recording and of the direct fit's simulation and inverse, under the table's row labels.
  const auto& f = r.figures;
  CHECK(f.stack_source == dir / "stack.csv");
  REQUIRE(f.stack_position.size() == r.stack_models.size() + 1);
  REQUIRE(f.stack_voltage.size() >= 2);
  CHECK(f.stack_position[0].label == "measured");
  CHECK(f.stack_position[1].label == "1 " + pi.label);
  CHECK(f.stack_voltage[1].label == "1 " + pi.label);
  for (const auto* traces : {&f.stack_position, &f.stack_voltage})
    for (const auto& t : *traces) {
      REQUIRE(t.x.size() == sysid::kStackFigureSamples);
      CHECK(t.x[0] == rec.data(800, 0));
      CHECK(t.x[599] == rec.data(1399, 0));
    }
  CHECK(f.stack_position[0].y[0] == rec.data(800, 2));
  CHECK(f.stack_voltage[0].y[599] == rec.data(1399, 1));
  CHECK(f.stack_position[1].y[0] == Approx(xm[800]).epsilon(1e-10));
  CHECK(f.stack_voltage[1].y[599] == Approx(um[1399]).epsilon(1e-10));
  // The summary names the split and carries the table.
  const auto j = nlohmann::ordered_json::parse(sysid::ToJson(sysid::StackSummaryOf(r)));
  CHECK(j["dataset"] == "stack");
  CHECK_FALSE(j.contains("report"));  // the CLI's, set by it
  CHECK(j["train_fraction"] == 0.4);
  CHECK(j["models"].size() == r.stack_models.size());
  CHECK(j["models"][0]["forward_rms_m"].get<double>() == pi.forward_rms_m);
  // The score's keys, the fit's outcome last (of its summary, converged and message).
  std::vector<std::string> keys;
  for (auto it = j["models"][0].begin(); it != j["models"][0].end(); ++it)
    keys.push_back(it.key());
  CHECK(keys == std::vector<std::string>{"label", "kind", "parameters", "fit_time_s",
                                         "train_samples", "test_samples", "forward_rms_m",
                                         "forward_nrmse_std", "inverse_rms_v",
                                         "inverse_nrmse_std", "inverse_error", "error",
                                         "converged", "message"});
  CHECK(j["models"][0]["converged"] == pi.summary.converged);
  CHECK(j["models"][0]["message"] == pi.summary.message);
  CHECK(j["dominance"][0]["dominant"] == "x");
  CHECK(j["dominance"][0]["r2"].get<double>() == r.stack_dominance[0].r2);
}

TEST_CASE("sysid pipeline on a stack folder writes the model table", "[pipeline][stack][cli]") {
  TempDir dir;
  std::filesystem::create_directory(dir / "stack");
  sysid::WriteRecording(dir / "stack/piezo.csv", StackRecording(1200));
  const auto r = RunCli({"pipeline", dir / "stack", "-o", dir / "report", "--threads", "2", "--json"});
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const auto j = nlohmann::json::parse(r.out);
  CHECK(j["dataset"] == "stack");
  CHECK(j["models"].size() == 6);
  const auto summary = nlohmann::json::parse(sysid::test::ReadText(dir / "report/summary.json"));
  CHECK(summary["models"] == j["models"]);
  const std::string md = sysid::test::ReadText(dir / "report/report.md");
  CHECK_THAT(md, Catch::Contains("first 40 %") &&
                     Catch::Contains("| model | parameters | fit time [s] | forward e_RMS [m]") &&
                     Catch::Contains("Bouc–Wen, piezo form"));
  const std::string csv = sysid::test::ReadText(dir / "report/models.csv");
  CHECK(csv.rfind("model,kind,parameters,fit_time_s,", 0) == 0);
  CHECK(std::filesystem::exists(dir / "report/model_1_pi.json"));
  // The model file is the one scored: `hysteresis simulate` with it gives the table's row.
  CHECK(sysid::ReadHysteresisModel(dir / "report/model_1_pi.json")->kind() == "pi");
  // The forward and inverse plots: one label and one colour per model in both, the two networks
  // told apart by their table labels, the measured trace black and last.
  CHECK(sysid::test::CheckPlotIndex(dir / "report") == 2);
  const auto plots = nlohmann::json::parse(sysid::test::ReadText(dir / "report/plots.json"));
  const auto& fwd = plots["stack_forward.png"]["series"];
  const auto& inv = plots["stack_inverse.png"]["series"];
  CHECK(fwd.size() == 7);  // six models and the measured trace
  CHECK(plots["stack_forward.png"]["y_label"] == "x [um]");
  bool static_net = false, operator_net = false;
  for (const auto& s : fwd) {
    static_net |= s["label"] == "5 dominant-variable network (static, H = 10)";
    operator_net |= s["label"] == "6 operator-input network (4 play operators, H = 10)";
  }
  CHECK(static_net);
  CHECK(operator_net);
  // Each model in the inverse plot has its forward colour (an inverse refused there, as rdpi's on
  // the piezo recording, must not shift the others': PlotColours' own test).
  for (const auto& s : inv)
    for (const auto& f : fwd)
      if (f["label"] == s["label"]) CHECK(f["colour"] == s["colour"]);
  // Too short to split: exit 2 naming the file, no report.
  std::filesystem::create_directory(dir / "short");
  sysid::WriteRecording(dir / "short/s.csv", StackRecording(3));
  const auto bad = RunCli({"pipeline", dir / "short", "-o", dir / "report2"});
  CHECK(bad.exit_code == 2);
  CHECK_THAT(bad.err, Catch::Contains("s.csv") && Catch::Contains("at least 2 rows"));
  CHECK_FALSE(std::filesystem::exists(dir / "report2"));
}
