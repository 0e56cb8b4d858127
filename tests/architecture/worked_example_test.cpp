// docs/architecture.md's worked example kept true: this file is built against a copy of
// sysid/delay.hpp with the example's two lines applied (scripts/apply_worked_example.py, run by
// the build), so the field it adds must reach the JSON writer, the positioned reader and the
// names Python's attributes come from with no other edit. If the example stops applying, the
// build says which line of the doc is wrong.
#include <catch2/catch.hpp>
#include <string>

#include "core/json_fields.hpp"
#include "signal/signal_json.hpp"  // the motion options' derivative method
#include "sysid/delay.hpp"
#include "sysid/error.hpp"

using sysid::DelayTuningOptions;
using sysid::internal::FieldNamesOf;
using sysid::internal::FieldsFromJson;
using sysid::internal::FieldsToJson;

TEST_CASE("the worked example's field is in JSON, its reader and Python's names",
          "[architecture][serialize]") {
  DelayTuningOptions o;
  CHECK(o.tau_start_s == 0.003);  // the doc's default, as --help would print it
  CHECK(FieldNamesOf(o).back() == "tau_start_s");  // DefFields' __fields__ walk the same list

  o.tau_start_s = 0.004;
  o.tau_max_s = 0.03;
  const std::string text = FieldsToJson(o, 2);
  CHECK(nlohmann::json::parse(text).at("tau_start_s") == 0.004);
  const auto back = FieldsFromJson<DelayTuningOptions>(text, "d.json");
  CHECK(back.tau_start_s == 0.004);
  CHECK(back.tau_max_s == 0.03);
  CHECK(FieldsToJson(back, 2) == text);

  // A misspelt key and a wrong type are positioned errors naming the field.
  CHECK_THROWS_WITH(FieldsFromJson<DelayTuningOptions>("{\"tau_strat_s\": 0.004}", "d.json"),
                    Catch::StartsWith("d.json:1:2:") && Catch::Contains("tau_strat_s"));
  CHECK_THROWS_WITH(FieldsFromJson<DelayTuningOptions>("{\n \"tau_start_s\": \"x\"}", "d.json"),
                    Catch::StartsWith("d.json:2:2: tau_start_s: expected a finite number"));
}
