// An options rule is reported through internal::FailOption (core/option_rule.hpp): the
// OptionsError carries owner, field, value and rule as members, and the JSON readers place it
// at FILE:LINE:COL from those members alone. The references are the members set by hand and the
// line and column counted by hand in the test's own text; a message reworded so that it holds
// none of "::", " = " or "Violated constraint" must be placed just the same.
#include "core/option_rule.hpp"

#include <catch2/catch.hpp>
#include <string>

#include "core/json_text.hpp"
#include "sysid/error.hpp"
#include "sysid/identify.hpp"

using sysid::OptionsError;
using sysid::internal::JsonDocument;
using sysid::internal::ValidateOptions;

namespace {

// The InputError text ValidateOptions makes of `error`, thrown by a Validate() over `text`.
std::string Placed(const std::string& text, const OptionsError& error,
                   const std::string& base = "") {
  const JsonDocument doc(text, "f.json");
  try {
    ValidateOptions(
        doc, [&] { throw error; }, base);
  } catch (const sysid::InputError& e) {
    return e.what();
  }
  return "(nothing thrown)";
}

}  // namespace

TEST_CASE("FailOption: the members are the parts, the message reads as before", "[core][options]") {
  try {
    sysid::internal::FailOption("PlateauOptions", "window_fraction", 1.5,
                                "0 < window_fraction <= 1");
    FAIL("nothing thrown");
  } catch (const OptionsError& e) {
    CHECK(e.owner() == "PlateauOptions");
    CHECK(e.field() == "window_fraction");
    CHECK(e.value() == "1.5");
    CHECK(e.rule() == "0 < window_fraction <= 1");
    CHECK(std::string(e.what()) ==
          "PlateauOptions::window_fraction = 1.5. Violated constraint: 0 < window_fraction <= 1");
  }
  // Without an owner the message starts at the field; a string value is taken as it is.
  const OptionsError bare("", "hold", "'cubic'", "one of zoh, linear");
  CHECK(std::string(bare.what()) == "hold = 'cubic'. Violated constraint: one of zoh, linear");
  // Context (a CLI flag) changes the text only.
  const OptionsError flagged = bare.WithMessage(std::string("--hold: ") + bare.what());
  CHECK(std::string(flagged.what()).rfind("--hold: hold = 'cubic'", 0) == 0);
  CHECK(flagged.field() == "hold");
  CHECK(flagged.value() == "'cubic'");
  CHECK(flagged.rule() == "one of zoh, linear");
  // The errors that are no rule on one field keep an empty rule.
  CHECK(OptionsError("give exactly one model").rule().empty());
  CHECK(OptionsError("no recordings", "recordings").rule().empty());
}

TEST_CASE("a bad option read from JSON is placed at its value from the error's members",
          "[core][options][json]") {
  // The library's own Validate(): window_fraction's key is at line 2, column 3.
  const std::string text = "{\"min_window_samples\": 5,\n  \"window_fraction\": 1.5}";
  try {
    sysid::PlateauOptionsFromJson(text, "p.json");
    FAIL("nothing thrown");
  } catch (const sysid::InputError& e) {
    CHECK(std::string(e.what()) ==
          "p.json:2:3: window_fraction: expected 0 < window_fraction <= 1, found 1.5");
  }
  // The error Validate() throws, read directly: the same parts.
  sysid::PlateauOptions o;
  o.window_fraction = 1.5;
  try {
    o.Validate();
    FAIL("nothing thrown");
  } catch (const OptionsError& e) {
    CHECK(e.owner() == "PlateauOptions");
    CHECK(e.field() == "window_fraction");
    CHECK(e.value() == "1.5");
  }
}

TEST_CASE("a reworded message is placed the same: nothing reads the message text",
          "[core][options][json]") {
  const std::string text = "{\"a\": 1,\n \"candidates\": [{\"gain\": 1},\n  {\"gain\": \"x\"}]}";
  // No "::", no " = ", no "Violated constraint" in the text; only the members say where.
  const OptionsError reworded =
      OptionsError("DominanceOptions", "candidates[1].gain", "inf", "finite")
          .WithMessage("the second candidate's gain is not a number");
  // candidates[1]'s "gain" key: line 3, column 4.
  CHECK(Placed(text, reworded) == "f.json:3:4: candidates[1].gain: expected finite, found inf");
  // A field that is not written in the file: the document's start, marked as the default.
  const OptionsError absent =
      OptionsError("PlateauOptions", "settle_tolerance", "0", "settle_tolerance > 0")
          .WithMessage("reworded");
  const JsonDocument doc(text, "f.json");
  CHECK_THROWS_WITH(doc.FailValidation(absent, "/settle_tolerance"),
                    "f.json:1:1: settle_tolerance: expected settle_tolerance > 0, found 0 (the "
                    "built-in default)");
  // An error without a rule is not placed at a field, whatever its text or field says.
  CHECK(Placed(text, OptionsError("X::a = 1. Violated constraint: y", "a")) ==
        "f.json:1:1: X::a = 1. Violated constraint: y");
  // Nested under `base`: the struct's own key wins over a key of the same name elsewhere.
  const std::string nested = "{\"gain\": 1,\n \"inner\": {\"gain\": 2}}";
  CHECK(Placed(nested, OptionsError("Inner", "gain", "2", "gain < 2"), "/inner") ==
        "f.json:2:12: inner.gain: expected gain < 2, found 2");
}
