// compare_json.cpp: CompareOptions round-trip through JSON; bad keys, types and rules are
// positioned errors.
#include <catch2/catch.hpp>
#include <string>

#include "sysid/compare.hpp"
#include "sysid/error.hpp"

TEST_CASE("compare options round-trip through JSON", "[compare][json]") {
  sysid::CompareOptions o;
  o.derivative.method = sysid::DerivativeMethod::kButterworthCentral;
  o.derivative.cutoff_hz = 20;
  o.derivative.butterworth_order = 2;
  o.trim_samples = 11;
  const std::string text = sysid::ToJson(o);
  const auto back = sysid::CompareOptionsFromJson(text, "c.json");
  CHECK(back.derivative.method == sysid::DerivativeMethod::kButterworthCentral);
  CHECK(back.derivative.cutoff_hz == 20);
  CHECK(back.derivative.butterworth_order == 2);
  CHECK(back.trim_samples == 11);
  CHECK(sysid::ToJson(back) == text);
}

TEST_CASE("compare options JSON: bad input names the place", "[compare][json]") {
  using Catch::Contains;
  CHECK_THROWS_WITH(sysid::CompareOptionsFromJson("{\"trim_samples\": -1}", "c.json"),
                    Contains("c.json:1:2: trim_samples: expected trim_samples >= 0, found -1"));
  CHECK_THROWS_WITH(sysid::CompareOptionsFromJson("{\"derivative\": {\"cutoff\": 3}}", "c.json"),
                    Contains("unknown key 'cutoff' in 'derivative'"));
}
