// The shared JSON reader of the model, network and stage files: positions, rules, escaping.
#include <catch2/catch.hpp>
#include <string>

#include "core/json_text.hpp"
#include "sysid/error.hpp"

using sysid::internal::JsonDocument;
using sysid::internal::NumberRule;
using sysid::internal::Printable;

TEST_CASE("Printable escapes what a terminal would interpret, keeps text", "[json]") {
  CHECK(Printable("abc") == "abc");
  CHECK(Printable(std::string("a\x1b[2J\x07", 6)) == "a\\x1B[2J\\x07");
  CHECK(Printable(std::string("a\0b", 3)) == "a\\x00b");      // a NUL no longer cuts the text
  CHECK(Printable("\x7f") == "\\x7F");                         // DEL
  CHECK(Printable("\xc2\x9b" "31m") == "\\xC2\\x9B31m");       // C1 CSI in UTF-8
  CHECK(Printable("\x9b") == "\\x9B");                         // a lone byte, invalid UTF-8
  CHECK(Printable("caf\xc3\xa9 \xce\xbc" "m") == "caf\xc3\xa9 \xce\xbc" "m");  // é, µ kept
  CHECK(Printable("abcdef", 3) == "abc...");
}

TEST_CASE("number rules describe themselves as the messages print them", "[json]") {
  CHECK(NumberRule::Positive().Describe() == "a number > 0");
  CHECK(NumberRule::NonNegative().Describe() == "a number >= 0");
  CHECK(NumberRule::Closed(0, 1).Describe() == "a number in [0, 1]");
  CHECK(NumberRule::Finite().Describe() == "a finite number");
  CHECK_FALSE(NumberRule::Positive().Accepts(0.0));
  CHECK(NumberRule::NonNegative().Accepts(0.0));
  CHECK_FALSE(NumberRule::Closed(0, 1).Accepts(1.5));
}

TEST_CASE("values are found by pointer: nested, in arrays, a duplicate key is refused",
          "[json]") {
  // Issue #29: nlohmann kept the last of duplicate keys silently; the reader names both.
  const std::string dup = "{\n  \"a\": {\"b\": [1,\n    2, \"x\"]},\n  \"c\": 1, \"c\": -2\n}";
  CHECK_THROWS_WITH(JsonDocument(dup, "f.json"),
                    Catch::StartsWith("f.json:4:11: duplicate key 'c' (first at 4:3)"));
  const std::string text = "{\n  \"a\": {\"b\": [1,\n    2, \"x\"]},\n  \"d\": 1, \"c\": -2\n}";
  const JsonDocument doc(text, "f.json");
  const auto root = doc.Root();
  CHECK_THROWS_WITH(root.Get("a").Get("b").Element(2).Number(),
                    Catch::Equals("f.json:3:8: a.b[2]: expected a finite number, found string "
                                  "\"x\""));
  CHECK_THROWS_WITH(root.Get("a").Get("b").Element(1).Number(NumberRule::Closed(5, 6)),
                    Catch::Equals("f.json:3:5: a.b[1]: expected a number in [5, 6], found 2"));
  CHECK_THROWS_WITH(root.Get("c").Number(NumberRule::Positive()),
                    Catch::Equals("f.json:4:11: c: expected a number > 0, found -2"));
  CHECK_THROWS_WITH(root.Get("a").Get("z"), Catch::Equals("f.json:2:3: a: missing required key 'z'"));
  CHECK_THROWS_WITH(root.Get("a").Integer(0, 3),
                    Catch::Equals("f.json:2:3: a: expected an integer in [0, 3], found an object"));
}

TEST_CASE("deep nesting neither overflows the stack nor makes the index quadratic", "[json]") {
  const int depth = 100000;
  const std::string text = "{\"a\": " + std::string(depth, '[') + std::string(depth, ']') + "}";
  const JsonDocument doc(text, "deep.json");
  CHECK_THROWS_WITH(doc.Root().Get("a").Number(),
                    Catch::Equals("deep.json:1:2: a: expected a finite number, found an array of "
                                  "1 value"));
}
