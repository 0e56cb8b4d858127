// Global options (issue 29): --json, --threads and --progress work before or after the
// subcommand's name, with the same output either way.
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>
#include <string>

#include "support/test_support.hpp"
#include "sysid/model.hpp"

using sysid::test::RunCli;

TEST_CASE("global options: --json and --threads before the subcommand act as after it", "[cli]") {
  const std::string pulses = sysid::test::SourcePath("datasets/virtual/pulses.csv");
  const auto after = RunCli({"info", pulses, "--json"});
  REQUIRE(after.exit_code == 0);
  const auto before = RunCli({"--json", "info", pulses});
  CHECK(before.exit_code == 0);
  CHECK(before.out == after.out);  // the reference: the documented order's output

  sysid::test::TempDir dir;
  sysid::WriteModel(dir / "m.json", sysid::FrictionModel::Paper());
  const auto d_after =
      RunCli({"dominance", "--model", dir / "m.json", pulses, "--threads", "1", "--json"});
  REQUIRE(d_after.exit_code == 0);
  const auto d_before =
      RunCli({"--threads", "1", "--json", "dominance", "--model", dir / "m.json", pulses});
  CHECK(d_before.exit_code == 0);
  CHECK(d_before.out == d_after.out);
  const auto d_equals = RunCli({"--threads=1", "dominance", "--model", dir / "m.json", pulses});
  CHECK(d_equals.exit_code == 0);
}

TEST_CASE("global options: --json before a nested subcommand lands after both names", "[cli]") {
  const auto r = RunCli({"--json", "stage", "facts", "--facts", "F1"});
  REQUIRE(r.exit_code == 0);
  CHECK_NOTHROW(nlohmann::json::parse(r.out));  // the JSON form, not the table
}

TEST_CASE("global options: --progress after the subcommand is accepted (it was 'not expected')", "[cli]") {
  const std::string pulses = sysid::test::SourcePath("datasets/virtual/pulses.csv");
  const auto r = RunCli({"info", pulses, "--progress"});
  CHECK(r.exit_code == 0);
  CHECK(r.err.find("not expected") == std::string::npos);
  CHECK(RunCli({"--progress", "info", pulses}).exit_code == 0);
}

TEST_CASE("misplaced options still fail as usage errors", "[cli]") {
  // No subcommand at all, and an option no subcommand defines: exit 1 with CLI11's message.
  CHECK(RunCli({"--json"}).exit_code == 1);
  const auto r = RunCli({"--no-such-flag", "info", "x.csv"});
  CHECK(r.exit_code == 1);
  CHECK(r.err.find("--no-such-flag") != std::string::npos);
}
