// dominance_json.cpp: `sysid dominance --json` prints the library's text, and the pooled
// ranking of a batch is the RMS over all moving samples (two copies of one recording pool to
// that recording's own statistics).
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>
#include <string>

#include "support/test_support.hpp"
#include "sysid/dominance.hpp"
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
