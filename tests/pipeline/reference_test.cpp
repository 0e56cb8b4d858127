// The report's reference numbers (PipelineReference), read by the pipeline before its first step
// so that the report reads nothing and a bad file costs no run. Reference: the same file parsed
// by nlohmann::json directly.
#include <catch2/catch.hpp>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "support/test_support.hpp"
#include "sysid/error.hpp"
#include "sysid/pipeline.hpp"

using sysid::test::SourcePath;
using sysid::test::TempDir;

TEST_CASE("the paper's reference numbers read as the JSON file holds them",
          "[pipeline][reference]") {
  const std::string path = SourcePath("experiments/paper_numbers.json");
  const sysid::PipelineReference ref = sysid::ReadPipelineReference(path);
  const auto j = nlohmann::json::parse(std::ifstream(path));
  CHECK(ref.label == j["label"].get<std::string>());
  REQUIRE(ref.model);
  CHECK(ref.model->size() == j["model"].size());
  for (const auto& [name, value] : j["model"].items())
    CHECK(ref.ModelValue(name) == value.get<double>());
  CHECK_FALSE(ref.ModelValue("a4"));
  CHECK(ref.dominance_ratio_bound == j["dominance_ratio_bound"].get<double>());
  REQUIRE(ref.sweep);
  REQUIRE(ref.sweep->size() == j["sweep"].size());
  for (size_t i = 0; i < ref.sweep->size(); ++i) {
    CHECK((*ref.sweep)[i].hidden == j["sweep"][i]["hidden"].get<int>());
    CHECK((*ref.sweep)[i].epochs == j["sweep"][i]["epochs"].get<int>());
    CHECK((*ref.sweep)[i].test_mse == j["sweep"][i]["test_mse"].get<double>());
  }
  REQUIRE(ref.tracking_max_error_mm);
  size_t n = 0;
  for (const auto& [f, schemes] : j["tracking_max_error_mm"].items())
    for (const auto& [scheme, mm] : schemes.items()) {
      ++n;
      bool found = false;
      for (const auto& e : *ref.tracking_max_error_mm)
        found = found || (e.frequency_hz == std::stod(f) && e.scheme == scheme &&
                          e.max_error_mm == mm.get<double>());
      CHECK(found);
    }
  CHECK(ref.tracking_max_error_mm->size() == n);
}

TEST_CASE("an empty reference sets nothing, a wrong type is named at its key",
          "[pipeline][reference]") {
  TempDir dir;
  sysid::test::WriteText(dir / "empty.json", "{}");
  const auto empty = sysid::ReadPipelineReference(dir / "empty.json");
  CHECK(empty.label == "reference");
  CHECK_FALSE(empty.model);
  CHECK_FALSE(empty.sweep);
  CHECK_FALSE(empty.tracking_max_error_mm);
  sysid::test::WriteText(dir / "bad.json", "{\"label\": \"x\",\n \"model\": {\"a1p\": \"fast\"}}");
  CHECK_THROWS_WITH(
      sysid::ReadPipelineReference(dir / "bad.json"),
      Catch::StartsWith(dir / "bad.json" + ":2:2: model: expected an object of numbers"));
  sysid::test::WriteText(dir / "freq.json", "{\"tracking_max_error_mm\": {\"fast\": {\"nn\": 1}}}");
  CHECK_THROWS_AS(sysid::ReadPipelineReference(dir / "freq.json"), sysid::InputError);
  // The pipeline reads it before its first step: a bad file fails at once, no recording read.
  sysid::PipelineInputs in;
  in.pulses = {dir / "no_such_pulses.csv"};
  sysid::PipelineOptions o;
  o.reference_path = dir / "bad.json";
  CHECK_THROWS_WITH(sysid::RunPipeline(in, o), Catch::Contains("model: expected an object"));
}
