// dominance_json.cpp: `sysid dominance --json` prints the library's text, and the pooled
// ranking of a batch is the RMS over all moving samples (two copies of one recording pool to
// that recording's own statistics).
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>
#include <cmath>
#include <limits>
#include <string>

#include "support/test_support.hpp"
#include "sysid/dominance.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"
#include "sysid/model.hpp"

using sysid::test::RunCli;
using sysid::test::SourcePath;

TEST_CASE("dominance JSON: the CLI prints the library's text; pooling", "[dominance][json]") {
  sysid::test::TempDir dir;
  const auto model = sysid::FrictionModel::Paper();
  sysid::WriteModel(dir / "m.json", model);
  const std::string a = SourcePath("datasets/virtual/waveform_square.csv");
  const std::string b = SourcePath("datasets/virtual/waveform_sine_0.0525_6.csv");
  const auto s =
      sysid::AnalyzeDominanceBatch(model, {sysid::ReadRecording(a), sysid::ReadRecording(b)});
  const auto cli = RunCli({"dominance", "--json", "--model", dir / "m.json", a, b});
  REQUIRE(cli.exit_code == 0);
  CHECK(cli.out == sysid::ToJson(s));
  const auto j = nlohmann::json::parse(cli.out);
  CHECK(j["recordings"][1] == nlohmann::json::parse(sysid::ToJson(s.results[1])));
  CHECK(j["negligible_ratio"] == sysid::DominanceOptions{}.negligible_ratio);

  const auto one = sysid::AnalyzeDominance(model, sysid::ReadRecording(a));
  const auto twice =
      sysid::AnalyzeDominanceBatch(model, {sysid::ReadRecording(a), sysid::ReadRecording(a)});
  REQUIRE(twice.ranking.size() == one.ranking.size());
  for (size_t i = 0; i < one.ranking.size(); ++i) {
    CHECK(twice.ranking[i].name == one.ranking[i].name);
    CHECK(twice.ranking[i].rms == Approx(one.ranking[i].rms).epsilon(1e-12));
    CHECK(twice.ranking[i].peak == one.ranking[i].peak);
    CHECK(twice.ranking[i].negligible == one.ranking[i].negligible);
  }
}

TEST_CASE("one recording's dominance JSON round trip and positioned errors",
          "[dominance][json]") {
  sysid::DominanceResult r;
  r.source = "rec.csv";
  r.samples = 1000;
  r.moving_samples = 640;
  r.ranking = {{"v", 2.5, 4.25, 1.0, 1.0, 1.0, false}, {"a", 0.5, 1.5, 0.2, 0.375, 0.75, false}};
  r.terms = {{"acceleration", 0.5, 1.5, 0.2, 0, 0, false}, {"viscous", 2.5, 4.25, 1.0, 0, 0, false}};
  r.dominant = "v";
  r.margin = 5.0;
  r.peak_ratio = 0.35;
  r.pointwise_ratio_quantile = 0.3;
  r.pointwise_ratio_max = 0.9;
  const std::string text = sysid::ToJson(r);
  const sysid::DominanceResult back = sysid::DominanceResultFromJson(text, "dom.json");
  CHECK(sysid::ToJson(back) == text);
  CHECK(back.source == "rec.csv");
  CHECK(back.moving_samples == 640);
  REQUIRE(back.ranking.size() == 2);
  CHECK(back.ranking[1].ratio_bound == 0.375);
  CHECK(back.terms[1].name == "viscous");
  CHECK(back.margin == 5.0);
  r.margin = std::numeric_limits<double>::infinity();  // a single candidate: written as null
  CHECK(std::isinf(sysid::DominanceResultFromJson(sysid::ToJson(r), "dom.json").margin));
  auto j = nlohmann::json::parse(text);
  j["moving_samples"] = 2000;  // more than the record's samples
  try {
    sysid::DominanceResultFromJson(j.dump(1), "bad.json");
    FAIL("moving_samples > samples was read");
  } catch (const sysid::InputError& e) {
    CHECK_THAT(e.what(), Catch::StartsWith("bad.json:"));
    CHECK_THAT(e.what(), Catch::Contains("moving_samples"));
  }
}
