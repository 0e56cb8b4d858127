// dominance_json.cpp: DominanceOptions round-trip through JSON; bad keys, types and rules are
// positioned errors.
#include <catch2/catch.hpp>
#include <string>

#include "sysid/dominance.hpp"
#include "sysid/error.hpp"

TEST_CASE("dominance options round-trip through JSON", "[dominance][json]") {
  sysid::DominanceOptions o;
  o.motion.max_relative_jitter = 0.02;
  o.min_speed_mps = 2e-3;
  o.negligible_ratio = 0.2;
  o.bound_quantile = 0.95;
  o.candidates = {{"temperature", "T", 0.5}, {"load", "F", -2.0}};
  o.threads = 1;
  const std::string text = sysid::ToJson(o);
  const auto back = sysid::DominanceOptionsFromJson(text, "o.json");
  CHECK(back.motion.max_relative_jitter == 0.02);
  CHECK(back.negligible_ratio == 0.2);
  CHECK(back.bound_quantile == 0.95);
  REQUIRE(back.candidates.size() == 2);
  CHECK(back.candidates[1].variable == "load");
  CHECK(back.candidates[1].column == "F");
  CHECK(back.candidates[1].gain == -2.0);
  CHECK(back.threads == 1);
  CHECK(sysid::ToJson(back) == text);
  // A candidate's gain is optional (default 1).
  CHECK(sysid::DominanceOptionsFromJson(
            "{\"candidates\": [{\"variable\": \"t\", \"column\": \"T\"}]}", "o.json")
            .candidates[0]
            .gain == 1.0);
}

TEST_CASE("dominance options JSON: bad input names the place", "[dominance][json]") {
  using Catch::Contains;
  CHECK_THROWS_WITH(sysid::DominanceOptionsFromJson("{\"negligible_ratio\": 1.5}", "o.json"),
                    Contains("o.json:1:2: negligible_ratio: expected 0 < negligible_ratio < 1"));
  CHECK_THROWS_WITH(
      sysid::DominanceOptionsFromJson("{\"candidates\": [{\"variable\": \"t\"}]}", "o.json"),
      Contains("candidates[0]: missing required key 'column'"));
  CHECK_THROWS_WITH(sysid::DominanceOptionsFromJson(
                        "{\"candidates\": [\n{\"variable\": \"velocity\", \"column\": \"v\"}]}",
                        "o.json"),
                    Contains("o.json:2:2: candidates[0].variable: expected a name other than acceleration"));
  CHECK_THROWS_WITH(sysid::DominanceOptionsFromJson("{\"threads\": 1.5}", "o.json"),
                    Contains("threads: expected an integer"));
}
