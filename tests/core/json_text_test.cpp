// The JSON reader every file goes through (core/json_text.cpp) refuses what nlohmann's parser
// lets pass (issue #29): a key twice in one object, and bytes after the JSON text.
#include "core/json_text.hpp"

#include <catch2/catch.hpp>
#include <string>

#include "sysid/error.hpp"

using sysid::internal::ParseJsonText;

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
