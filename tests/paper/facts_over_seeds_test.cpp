// The stage facts over several seeds: the seed parser's ranges, lists and bounds; a sweep equals
// the single-seed runs made separately; the command's --seeds output and errors.
#include <catch2/catch.hpp>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "support/test_support.hpp"
#include "sysid/error.hpp"
#include "sysid/stage.hpp"
#include "sysid/stage_facts.hpp"

using sysid::FactsOptions;
using sysid::ParseFactsSeeds;
using Seeds = std::vector<std::uint64_t>;

namespace {

// The OptionsError's message and field for `text`, or "" when it parses.
std::string SeedsError(const std::string& text) {
  try {
    ParseFactsSeeds(text);
  } catch (const sysid::OptionsError& e) {
    CHECK(e.field() == "seeds");
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("ParseFactsSeeds: ranges, lists and their bounds", "[stage][facts]") {
  CHECK(ParseFactsSeeds("1-3") == Seeds{1, 2, 3});
  CHECK(ParseFactsSeeds("7") == Seeds{7});
  CHECK(ParseFactsSeeds("7-7") == Seeds{7});
  CHECK(ParseFactsSeeds("5,2,7") == Seeds{5, 2, 7});
  // A repeated seed would count one seed's run as several ("3 of 3" over 1,1,1).
  CHECK(SeedsError("5,2,5").find("seed 5 is given twice") != std::string::npos);
  CHECK(ParseFactsSeeds("0-999").size() == sysid::kMaxFactsSeeds);
  CHECK(ParseFactsSeeds("4611686018427387904") == Seeds{std::uint64_t{1} << 62});
  CHECK(SeedsError("3-1").find("runs backwards") != std::string::npos);
  CHECK(SeedsError("0-1000").find("at most 1000") != std::string::npos);
  CHECK(SeedsError("0-18446744073709551615").find("above 2^62") != std::string::npos);
  std::string many = "0";
  for (int k = 1; k <= 1000; ++k) many += "," + std::to_string(k);
  CHECK(SeedsError(many).find("at most 1000") != std::string::npos);
  for (const char* bad : {"", "a", "1,,2", "1-", "-1", "1-2-3", "+1", "1.5", "1,"})
    CHECK(SeedsError(bad).find("expected 'A-B' or 'A,B,...'") != std::string::npos);
}

TEST_CASE("RunStageFactsOverSeeds equals the runs at each seed", "[stage][facts]") {
  FactsOptions o = FactsOptions::Reduced();
  o.facts = {"F1", "F2", "F3"};
  o.threads = 2;
  o.seed = 99;  // replaced by each seed of the sweep
  const auto stage = sysid::StageParameters::Default();
  const sysid::FactsSeedSweep sweep = sysid::RunStageFactsOverSeeds(stage, {2, 1}, o);
  REQUIRE(sweep.runs.size() == 2);
  CHECK(sweep.seeds == Seeds{2, 1});
  bool everywhere = true;
  for (std::size_t k = 0; k < 2; ++k) {
    FactsOptions single = o;
    single.seed = sweep.seeds[k];
    const sysid::StageFacts alone = sysid::RunStageFacts(stage, single);
    CHECK(sweep.runs[k].ToJson() == alone.ToJson());
    everywhere = everywhere && alone.RequiredMet();
  }
  CHECK(sweep.RequiredMetEverywhere() == everywhere);
  const auto j = nlohmann::json::parse(sweep.ToJson());
  CHECK(j["seeds"] == nlohmann::json::array({2, 1}));
  REQUIRE(j["facts"].size() == 3);
  for (const auto& f : j["facts"]) {
    Seeds met;
    for (std::size_t k = 0; k < 2; ++k)
      if (sweep.runs[k].Find(f["id"].get<std::string>())->met) met.push_back(sweep.seeds[k]);
    CHECK(f["met_seeds"].get<Seeds>() == met);
    CHECK(f["met_count"] == met.size());
    CHECK(f["runs"] == 2);
    CHECK(f["virtual"].size() == 2);
  }
  CHECK(j["required_met_everywhere"] == everywhere);
  CHECK_THROWS_AS(sysid::RunStageFactsOverSeeds(stage, {}, o), sysid::OptionsError);
}

TEST_CASE("sysid stage facts --seeds", "[stage][facts][cli]") {
  const auto ok = sysid::test::RunCli(
      {"stage", "facts", "--reduced", "--facts", "F1", "--seeds", "1-2", "--json"});
  REQUIRE(ok.exit_code == 0);
  const auto j = nlohmann::json::parse(ok.out);
  CHECK(j["seeds"] == nlohmann::json::array({1, 2}));
  CHECK(j["facts"][0]["id"] == "F1");
  CHECK(j["facts"][0]["runs"] == 2);
  const auto table =
      sysid::test::RunCli({"stage", "facts", "--reduced", "--facts", "F1", "--seeds", "3,4"});
  CHECK(table.exit_code == 0);
  CHECK(table.out.find("| F1 |") != std::string::npos);
  const auto backwards = sysid::test::RunCli({"stage", "facts", "--seeds", "3-1"});
  CHECK(backwards.exit_code == 1);
  CHECK(backwards.err.find("--seeds") != std::string::npos);
  CHECK(backwards.out.empty());
  CHECK(sysid::test::RunCli({"stage", "facts", "--seeds", "1", "--seed", "2"}).exit_code == 1);
}
