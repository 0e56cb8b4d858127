// a3 is never silently the paper's value (issue 29): the pulse fit cannot separate it from a1
// and a2, so every report says whether it was given or is the HR-8 data-sheet default.
#include <catch2/catch.hpp>

#include <string>

#include "support/test_support.hpp"
#include "sysid/identify.hpp"

using sysid::test::RunCli;

namespace {
const std::string kDefaultNote =
    "a3 = 6 (default: the paper's HR-8 data sheet; give --a3 for your stage)";
}

TEST_CASE("identify without --a3 says a3 is the paper's default, with --a3 that it was given",
          "[identify][cli]") {
  const std::string pulses = sysid::test::SourcePath("datasets/virtual/pulses.csv");
  const auto by_default = RunCli({"identify", pulses});
  REQUIRE(by_default.exit_code == 0);
  CHECK(by_default.out.find(kDefaultNote) != std::string::npos);
  CHECK(by_default.err.find("warning: " + kDefaultNote) != std::string::npos);
  CHECK(by_default.out.find("(given)") == std::string::npos);

  // The same number typed by the user is given: the flag, not the value, decides.
  const auto given = RunCli({"identify", "--a3", "6", pulses});
  REQUIRE(given.exit_code == 0);
  CHECK(given.out.find("a3 = 6 (given)") != std::string::npos);
  CHECK(given.err.find("warning") == std::string::npos);

  // --json goes to a program: the warning still reaches the user on stderr.
  const auto json = RunCli({"identify", "--json", pulses});
  REQUIRE(json.exit_code == 0);
  CHECK(json.err.find("warning: " + kDefaultNote) != std::string::npos);
}

TEST_CASE("an options file that names a3 gives it", "[identify]") {
  CHECK_FALSE(sysid::PulseFitOptionsFromJson("{}", "o.json").a3_given);
  const auto o = sysid::PulseFitOptionsFromJson(R"({"a3": 5})", "o.json");
  CHECK(o.a3_given);
  CHECK(o.a3 == 5);
  CHECK(sysid::DescribeA3(5, true) == "a3 = 5 (given)");
}
