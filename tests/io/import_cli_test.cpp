// sysid import and sysid info on MAT/HDF5 files: the bundled outside data sets reproduced byte
// for byte, values equal to the originals to the last bit, and the bad cases with their messages.
#include <catch2/catch.hpp>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "container_fixtures.hpp"
#include "support/test_support.hpp"
#include "sysid/io.hpp"
#include "sysid/io_containers.hpp"

namespace sysid::test {
namespace {

// Runs the CLI from the repository root, so that relative paths (as the regeneration script
// uses them, and as the files' source.* metadata records them) resolve.
CliResult RunFromSource(const std::vector<std::string>& args) {
  const auto here = std::filesystem::current_path();
  std::filesystem::current_path(SourcePath(""));
  CliResult r = RunCli(args);
  std::filesystem::current_path(here);
  return r;
}

TEST_CASE("sysid import reproduces the bundled outside data sets byte for byte",
          "[io][import][datasets]") {
  TempDir dir;
  struct Case {
    std::vector<std::string> args;
    std::string committed;
  };
  const std::string b = "datasets/boucwen/", p = "datasets/piezo_aye_ang/";
  const std::vector<Case> cases{
      {{"--column", "u=" + b + "train.h5:/multisine/u", "--column",
        "x=" + b + "train.h5:/multisine/y", "--rate", "750", "--unit", "u=N"},
       b + "train.csv"},
      {{"--column", "u=" + b + "uval_multisine.mat:uval_multisine", "--column",
        "x=" + b + "yval_multisine.mat:yval_multisine", "--rate", "750", "--unit", "u=N"},
       b + "test_multisine.csv"},
      {{"--column", "u=" + p + "Model_Vi_Do.dat:1", "--column", "x=" + p + "Model_Vi_Do.dat:5",
        "--scale", "x=1e-6", "--rate", "200"},
       p + "piezo.csv"}};
  for (const auto& c : cases) {
    std::vector<std::string> args{"import"};
    args.insert(args.end(), c.args.begin(), c.args.end());
    args.insert(args.end(), {"-o", dir / "out.csv"});
    const CliResult r = RunFromSource(args);
    INFO(c.committed << ": " << r.err);
    REQUIRE(r.exit_code == 0);
    CHECK(ReadText(dir / "out.csv") == ReadText(SourcePath(c.committed)));
    std::filesystem::remove(dir / "out.csv");
  }
}

TEST_CASE("imported values equal the MAT and HDF5 originals to the last bit",
          "[io][import][datasets]") {
  const std::string b = SourcePath("datasets/boucwen/");
  const Recording test = ReadRecording(b + "test_multisine.csv");
  REQUIRE(test.rows() == 8192);
  CHECK(test.column("u") == ReadSignal(b + "uval_multisine.mat", "uval_multisine"));
  CHECK(test.column("x") == ReadSignal(b + "yval_multisine.mat", "yval_multisine"));
  CHECK(test.meta("unit.u") == "N");
  CHECK(test.meta("unit.x") == "m");
  const Recording train = ReadRecording(b + "train.csv");
  REQUIRE(train.rows() == 40960);
  CHECK(train.column("u") == ReadSignal(b + "train.h5", "/multisine/u"));
  CHECK(train.column("x") == ReadSignal(b + "train.h5", "/multisine/y"));
  CHECK(train.column("t")[750] == 1.0);  // t = k / 750 Hz
  // The piezo recording: x is the sensor's column 5 in metres, read from the text itself.
  const Recording piezo = ReadRecording(SourcePath("datasets/piezo_aye_ang/piezo.csv"));
  REQUIRE(piezo.rows() == 8027);
  CHECK(piezo.column("x")[0] == -123.059139 * 1e-6);
  CHECK(piezo.column("u")[1] == 1.856539);
}

TEST_CASE("sysid info lists a MAT file's variables, text and JSON", "[io][info][cli]") {
  const std::string mat = SourcePath("datasets/boucwen/uval_multisine.mat");
  CliResult r = RunCli({"info", mat});
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(r.out, Catch::Contains("MAT v5") && Catch::Contains("uval_multisine") &&
                        Catch::Contains("1 x 8192") && Catch::Contains("double"));
  r = RunCli({"info", SourcePath("datasets/boucwen/train.h5"), "--json"});
  REQUIRE(r.exit_code == 0);
  const auto j = nlohmann::json::parse(r.out);
  CHECK(j["format"] == "HDF5");
  REQUIRE(j["variables"].size() == 3);
  CHECK(j["variables"][1]["name"] == "/multisine/u");
  CHECK(j["variables"][1]["length"] == 40960);
  // With a mapping, info summarises the recording as for a CSV.
  r = RunCli({"info", SourcePath("datasets/boucwen/train.h5"), "--var",
              "u=/multisine/u,x=/multisine/y", "--rate", "750", "--json"});
  REQUIRE(r.exit_code == 0);
  CHECK(nlohmann::json::parse(r.out)["rows"] == 40960);
  CHECK(nlohmann::json::parse(r.out)["sample_rate_hz"].get<double>() == Approx(750));
}

TEST_CASE("sysid info escapes control bytes and line breaks in MAT and HDF5 variable names",
          "[io][info][cli][errors]") {
  // Issue 38: an HDF5 dataset or MAT v7.3 variable name may hold an escape sequence or a
  // newline; info printed them raw to the terminal.
  TempDir dir;
  const std::string h5 = dir / "names.h5";
  WriteH5(h5, {{"/u\x1B[2Jx", {3}, {1, 2, 3}}, {"/a\nb", {3}, {4, 5, 6}}});
  const CliResult r = RunCli({"info", h5});
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  CHECK(r.out.find('\x1B') == std::string::npos);
  CHECK_THAT(r.out, Catch::Contains("/u\\x1B[2Jx") && Catch::Contains("/a\\x0Ab"));
  // Every line of the table is one variable or the table's frame: the newline did not split one.
  CHECK(r.out.find("\nb ") == std::string::npos);
}

TEST_CASE("sysid import: bad input exits 2 with the file and variable, nothing written",
          "[io][import][errors]") {
  TempDir dir;
  WriteMat(dir / "a.mat", MatVersion::kV5, {{"u", 1, 3, {1, 2, 3}}, {"x", 1, 4, {1, 2, 3, 4}}});
  CliResult r = RunCli({"import", "--column", "u=" + (dir / "a.mat") + ":u", "--column",
                        "x=" + (dir / "a.mat") + ":x", "--rate", "10", "-o", dir / "o.csv"});
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Catch::Contains("a.mat:x: 4 samples, but") &&
                        Catch::Contains("a.mat:u has 3 (lengths differ)"));
  CHECK_FALSE(std::filesystem::exists(dir / "o.csv"));
  r = RunCli({"import", "--column", "u=" + (dir / "a.mat") + ":w", "--rate", "10"});
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Catch::Contains("a.mat: no variable 'w' (variables: u, x)"));
  // No time and no rate.
  r = RunCli({"import", "--column", "u=" + (dir / "a.mat") + ":u"});
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Catch::Contains("no time column 't'") && Catch::Contains("--rate HZ"));
  // A time column that does not increase.
  WriteText(dir / "t.txt", "0 1\n0.1 2\n0.1 3\n");
  r = RunCli({"import", "--column", "t=" + (dir / "t.txt") + ":1", "--column",
              "u=" + (dir / "t.txt") + ":2"});
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Catch::Contains("t.txt:1[3]: time must be strictly increasing, found 0.1 "
                                    "after 0.1"));
  // A headerless text column out of range, and a bad cell with its line and column.
  r = RunCli({"import", "--column", "u=" + (dir / "t.txt") + ":3", "--rate", "1"});
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Catch::Contains("t.txt: no column '3': expected a column number 1..2 "
                                    "(1-based)"));
  WriteText(dir / "bad.txt", "1 2\n3 x4\n");
  r = RunCli({"import", "--column", "u=" + (dir / "bad.txt") + ":2", "--rate", "1"});
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Catch::Contains("bad.txt:2:3: column 2: expected a number, found \"x4\""));
  // A unit is printable text: an escape sequence is a usage error, shown as \xHH.
  r = RunCli({"import", "--column", "u=" + (dir / "a.mat") + ":u", "--rate", "10", "--unit",
              "u=\x1b[2J", "-o", dir / "o.csv"});
  CHECK(r.exit_code == 1);
  CHECK_THAT(r.err, Catch::Contains("--unit u=\\x1B[2J: expected a unit of 1 to 32 printable") &&
                        !Catch::Contains("\x1b"));
  CHECK_FALSE(std::filesystem::exists(dir / "o.csv"));
}

TEST_CASE("sysid import -o never replaces a file it did not write", "[io][import][errors]") {
  TempDir dir;
  WriteText(dir / "u.txt", "1\n2\n3\n");
  WriteText(dir / "mine.csv", "t,u\n0,1\n");
  const std::vector<std::string> base{"import", "--column", "u=" + (dir / "u.txt") + ":1",
                                      "--rate", "2",        "-o"};
  auto args = base;
  args.push_back(dir / "mine.csv");
  CliResult r = RunCli(args);
  CHECK(r.exit_code == 1);
  CHECK_THAT(r.err, Catch::Contains("mine.csv: exists and was not written by sysid ("));
  CHECK(ReadText(dir / "mine.csv") == "t,u\n0,1\n");
  args = base;
  args.push_back(dir / "new.csv");
  REQUIRE(RunCli(args).exit_code == 0);
  const std::string first = ReadText(dir / "new.csv");
  CHECK(RunCli(args).exit_code == 0);  // its own file: replaced
  CHECK(ReadText(dir / "new.csv") == first);
  CHECK_THAT(first, Catch::StartsWith("# generator: sysid "));
  CHECK_THAT(first, Catch::Contains("\n# source.u: "));
}

}  // namespace
}  // namespace sysid::test

namespace sysid::test {
namespace {

TEST_CASE("simulate reads a MAT input table through --var and writes -o OUT.mat",
          "[io][mat][cli]") {
  TempDir dir;
  WriteText(dir / "in.csv", "t,u\n0,0\n0.1,1.6\n0.5,-2.3\n0.8,0\n1,0\n");
  WriteMat(dir / "in.mat", MatVersion::kV5Compressed,
           {{"time", 5, 1, {0, 0.1, 0.5, 0.8, 1}}, {"volts", 1, 5, {0, 1.6, -2.3, 0, 0}}});
  CliResult r = RunCli({"simulate", "--paper-model", "--input", dir / "in.csv", "--t-end", "1",
                        "-o", dir / "a.csv"});
  REQUIRE(r.exit_code == 0);
  r = RunCli({"simulate", "--paper-model", "--input", dir / "in.mat", "--var", "t=time,u=volts",
              "--t-end", "1", "-o", dir / "b.mat"});
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const Recording a = ReadRecording(dir / "a.csv");
  const Recording b = ReadRecording(dir / "b.mat");
  CHECK(b.names == a.names);
  CHECK(b.data == a.data);  // same input values, same simulation; MAT holds the doubles exactly
  // Without the mapping the MAT file has no t and u: the message says how to map them.
  r = RunCli({"simulate", "--paper-model", "--input", dir / "in.mat", "--t-end", "1"});
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Catch::Contains("no time column 't'") && Catch::Contains("--var t=NAME"));
}

}  // namespace
}  // namespace sysid::test
