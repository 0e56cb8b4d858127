// The malformed-recording corpus: each case gives exit code 2 from `sysid info` and the exact
// FILE:LINE[:COLUMN] of the first offending place, counting physical lines from 1.
#include <catch2/catch.hpp>

#include <string>

#include "support/test_support.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"

using sysid::test::RunCli;
using sysid::test::TestData;

namespace {

struct BadCase {
  const char* file;
  const char* location;  // expected "LINE:" or "LINE:COLUMN:" right after the file name
  const char* says;      // a substring of the message
};

const BadCase kCases[] = {
    {"bad_empty.csv", "1:", "empty file"},
    {"bad_only_comments.csv", "2:", "no header line"},
    {"bad_header_only.csv", "1:", "header without rows"},
    {"bad_empty_cell.csv", "3:7:", "column 'u': expected a number, found an empty cell"},
    {"bad_abc.csv", "3:7:", "column 'u': expected a number, found \"abc\""},
    {"bad_exponent.csv", "3:11:", "column 'x': expected a number, found \"1e\""},
    {"bad_two_dots.csv", "3:7:", "found \"1.2.3\""},
    {"bad_trailing_garbage.csv", "3:7:", "found \"1.5x\""},
    {"bad_nan.csv", "3:7:", "expected a finite number, found \"nan\""},
    {"bad_inf.csv", "3:11:", "expected a finite number, found \"inf\""},
    {"bad_too_few.csv", "3:", "expected 3 fields (t,u,x), found 2"},
    {"bad_too_many.csv", "3:16:", "expected 3 fields (t,u,x), found more"},
    {"bad_missing_u.csv", "1:", "missing required column 'u'"},
    {"bad_missing_x_or_v.csv", "1:", "expected 'x' or 'v'"},
    {"bad_duplicate_time.csv", "4:1:", "time must be strictly increasing, found 0.001 after "
                                       "0.001 (line 3)"},
    {"bad_backwards_time.csv", "4:1:", "strictly increasing"},
    {"bad_blank_line.csv", "4:", "empty line"},
};

}  // namespace

TEST_CASE("every malformed recording fails with its exact location", "[io][errors]") {
  for (const auto& c : kCases) {
    const std::string path = TestData(std::string("io/") + c.file);
    INFO(c.file);
    try {
      sysid::ReadRecording(path);
      FAIL("no error for " << c.file);
    } catch (const sysid::InputError& e) {
      const std::string msg = e.what();
      CHECK(msg.rfind(path + ":" + c.location + " ", 0) == 0);
      CHECK_THAT(msg, Catch::Contains(c.says));
    }
  }
}

TEST_CASE("sysid info exits 2 with FILE:LINE for every malformed recording", "[io][cli]") {
  for (const auto& c : kCases) {
    const std::string path = TestData(std::string("io/") + c.file);
    INFO(c.file);
    const auto r = RunCli({"info", path});
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.err, Catch::Contains(path + ":" + c.location));
    CHECK(r.out.empty());
  }
}

TEST_CASE("a missing file is a clear error", "[io][errors]") {
  const auto r = RunCli({"info", "/nonexistent/run.csv"});
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Catch::Contains("/nonexistent/run.csv: cannot open: No such file"));
}

TEST_CASE("bad flags are a usage error (exit 1)", "[cli]") {
  CHECK(RunCli({"info", "--no-such-flag", TestData("io/good.csv")}).exit_code == 1);
  CHECK(RunCli({}).exit_code == 1);
  const auto help = RunCli({"--help"});
  CHECK(help.exit_code == 0);
  CHECK_THAT(help.out, Catch::Contains("info"));
}
