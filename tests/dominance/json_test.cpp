// dominance_json.cpp: `sysid dominance --json` prints the library's text, and the pooled
// ranking of a batch is the RMS over all moving samples (two copies of one recording pool to
// that recording's own statistics).
#include <algorithm>
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

TEST_CASE("dominance JSON: the CLI prints the library's text, pooling", "[dominance][json]") {
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

TEST_CASE("a batch's dominance JSON round-trips, counts in the batch's order",
          "[dominance][json]") {
  const auto model = sysid::FrictionModel::Paper();
  const std::string a = SourcePath("datasets/virtual/waveform_square.csv");
  const std::string b = SourcePath("datasets/virtual/waveform_sine_0.0525_6.csv");
  const auto s =
      sysid::AnalyzeDominanceBatch(model, {sysid::ReadRecording(a), sysid::ReadRecording(b)});
  const std::string text = sysid::ToJson(s);
  const auto back = sysid::DominanceSummaryFromJson(text, "batch.json");
  CHECK(sysid::ToJson(back) == text);
  REQUIRE(back.results.size() == 2);
  CHECK(sysid::ToJson(back.results[1]) == sysid::ToJson(s.results[1]));
  CHECK(back.dominant == s.dominant);
  CHECK(back.dominant_counts == s.dominant_counts);
  CHECK(back.min_margin == s.min_margin);
  CHECK(back.median_margin == s.median_margin);
  CHECK(back.negligible_ratio == s.negligible_ratio);
  CHECK(back.min_speed_mps == s.min_speed_mps);
  REQUIRE(back.ranking.size() == s.ranking.size());
  CHECK(back.ranking[0].name == s.ranking[0].name);
  CHECK(back.ranking[0].rms == s.ranking[0].rms);
  CHECK(back.ranking.back().negligible == s.ranking.back().negligible);

  // Counts whose names sort against their order ("a" before "v", 1 below 2): the reader sees
  // the keys sorted and must order them as the batch does. Infinite margins are written null.
  sysid::DominanceSummary t;
  t.results = {s.results[0], s.results[0], s.results[1]};
  t.results[0].margin = std::numeric_limits<double>::infinity();
  t.dominant_counts = {{"v", 2}, {"a", 1}};
  t.dominant = "v";
  t.min_margin = std::numeric_limits<double>::infinity();
  t.median_margin = std::numeric_limits<double>::infinity();
  t.ranking = s.ranking;
  t.negligible_ratio = 0.05;
  t.min_speed_mps = 1e-4;
  const std::string ttext = sysid::ToJson(t);
  CHECK_THAT(ttext, Catch::Contains("\"min_margin\": null"));
  const auto tback = sysid::DominanceSummaryFromJson(ttext, "t.json");
  CHECK(tback.dominant_counts == t.dominant_counts);
  CHECK(tback.dominant == "v");
  CHECK(std::isinf(tback.min_margin));
  CHECK(std::isinf(tback.results[0].margin));
  CHECK(sysid::ToJson(tback) == ttext);
}

TEST_CASE("a batch's dominance JSON errors name the place and the key", "[dominance][json]") {
  sysid::DominanceSummary s;
  sysid::DominanceResult r;
  r.source = "rec.csv";
  r.samples = 10;
  r.moving_samples = 8;
  r.ranking = {{"v", 2.5, 4.25, 1.0, 1.0, 1.0, false}};
  r.dominant = "v";
  r.margin = 5;
  s.results = {r};
  s.dominant_counts = {{"v", 1}};
  s.dominant = "v";
  s.ranking = {{"v", 2.5, 4.25, 1.0, 0, 0, false}};
  s.negligible_ratio = 0.05;
  const std::string text = sysid::ToJson(s);
  REQUIRE_NOTHROW(sysid::DominanceSummaryFromJson(text, "b.json"));
  auto replaced = [&](const std::string& from, const std::string& to) {
    std::string t = text;
    REQUIRE(t.find(from) != std::string::npos);
    return t.replace(t.find(from), from.size(), to);
  };
  const auto line = [&](const std::string& from) {
    const std::string head = text.substr(0, text.find(from));
    return std::to_string(std::count(head.begin(), head.end(), '\n') + 1);
  };
  // A recording's value, named with its path in the batch.
  CHECK_THROWS_WITH(
      sysid::DominanceSummaryFromJson(replaced("\"moving_samples\": 8", "\"moving_samples\": 11"),
                                      "b.json"),
      Catch::StartsWith("b.json:" + line("\"moving_samples\"") +
                        ":7: recordings[0].moving_samples: expected an integer in [0, 10]"));
  CHECK_THROWS_WITH(
      sysid::DominanceSummaryFromJson(replaced("\"v\": 1", "\"v\": 2"), "b.json"),
      Catch::StartsWith("b.json:" + line("\"v\": 1") +
                        ":7: summary.dominant_counts.v: expected an integer in [1, 1]"));
  CHECK_THROWS_WITH(
      sysid::DominanceSummaryFromJson(replaced("\"negligible_ratio\": 0.05",
                                               "\"negligible_ratio\": 1"),
                                      "b.json"),
      Catch::StartsWith("b.json:" + line("\"negligible_ratio\"") +
                        ":3: negligible_ratio: expected a number in (0, 1)"));
}
