// The JSON reader every file goes through (core/json_text.cpp) refuses what nlohmann's parser
// lets pass (issue #29): a key twice in one object, and bytes after the JSON text.
#include "core/json_text.hpp"

#include <catch2/catch.hpp>
#include <string>

#include "sysid/error.hpp"

using sysid::internal::JsonDocument;
using sysid::internal::ParseJsonText;
using sysid::internal::ReadName;

TEST_CASE("duplicate keys are an error naming both positions", "[core][json]") {
  CHECK_THROWS_WITH(ParseJsonText("{\"a\": 1,\n  \"a\": 2}", "f.json"),
                    Catch::Equals("f.json:2:3: duplicate key 'a' (first at 1:2): a key may "
                                  "appear once in an object"));
  // Nested, and spelled differently (an escape decodes to the same key).
  CHECK_THROWS_WITH(ParseJsonText("{\"o\": {\"k\": [1, {\"x\": 0}], \"\\u006b\": 3}}", "f.json"),
                    Catch::StartsWith("f.json:1:28: duplicate key 'k' (first at 1:8)"));
  // The same key in different objects, and in objects inside arrays, is fine.
  CHECK_NOTHROW(ParseJsonText("{\"a\": {\"a\": 1}, \"b\": [{\"a\": 1}, {\"a\": 2}]}", "f.json"));
  CHECK_NOTHROW(ParseJsonText("[{\"a\": 1}, {\"a\": 1}]", "f.json"));
}

TEST_CASE("bytes after the JSON text are an error, a NUL included", "[core][json]") {
  const std::string nul("{\"a\": 1}\0{\"a\": 2}", 17);
  CHECK_THROWS_WITH(ParseJsonText(nul, "f.json"),
                    Catch::StartsWith("f.json:1:9: unexpected a NUL byte after the JSON text"));
  const std::string scalar("5\0x", 3);
  CHECK_THROWS_WITH(ParseJsonText(scalar, "f.json"), Catch::StartsWith("f.json:1:2: unexpected"));
  CHECK_THROWS_AS(ParseJsonText("{} x", "f.json"), sysid::InputError);  // nlohmann's own check
  CHECK_NOTHROW(ParseJsonText("{\"a\": \"x\\\"}\"} \n\t\r\n", "f.json"));  // trailing blanks
  CHECK_NOTHROW(ParseJsonText("\xEF\xBB\xBF{\"a\": 1}", "f.json"));      // a BOM
}

namespace {
enum class Colour { kRed, kGreen, kBlue };
std::string ColourName(Colour c) {
  return c == Colour::kRed ? "red" : c == Colour::kGreen ? "green" : "blue";
}
}  // namespace

TEST_CASE("an enum's name is read from the writer's list, which also says what was expected",
          "[core][json]") {
  const std::string text = "{\"a\": \"green\", \"b\": \"blue\", \"c\": \"pink\"}";
  const JsonDocument doc(text, "f.json");
  const auto root = doc.Root();
  CHECK(ReadName(root.Get("a"), {Colour::kRed, Colour::kGreen, Colour::kBlue}, ColourName) ==
        Colour::kGreen);
  CHECK(ReadName(root.Get("b"), {Colour::kRed, Colour::kGreen, Colour::kBlue}, ColourName) ==
        Colour::kBlue);
  CHECK_THROWS_WITH(
      ReadName(root.Get("c"), {Colour::kRed, Colour::kGreen, Colour::kBlue}, ColourName),
      Catch::Equals("f.json:1:29: c: expected \"red\", \"green\" or \"blue\", found string \"pink\""));
  CHECK_THROWS_WITH(ReadName(root.Get("c"), {Colour::kRed, Colour::kGreen}, ColourName, "a colour"),
                    Catch::EndsWith("c: expected a colour (red or green), found string \"pink\""));
  // A value the list leaves out is refused though the writer names it.
  CHECK_THROWS_WITH(ReadName(root.Get("b"), {Colour::kRed}, ColourName),
                    Catch::EndsWith("b: expected \"red\", found string \"blue\""));
}
