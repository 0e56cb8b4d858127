// Lab files as they come: a MAT recording whose variables are named as the lab named them, with
// x in µm, read through --var and --scale by the commands that read recordings. The reference is
// the same command on the CSV recording the MAT file was made from: its output must be the same.
#include <catch2/catch.hpp>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "container_fixtures.hpp"
#include "support/test_support.hpp"
#include "sysid/io.hpp"

namespace sysid::test {
namespace {

std::vector<double> Column(const Recording& r, const std::string& name, double factor = 1) {
  const Eigen::VectorXd c = r.column(name) * factor;
  return std::vector<double>(c.data(), c.data() + c.size());
}

// `csv`'s columns t, u, x (and v, a when present) as a MAT v5 file of the lab's names: time,
// volts, pos_um (x in µm), vel, acc.
void WriteLabMat(const std::string& path, const Recording& csv) {
  const auto n = static_cast<std::size_t>(csv.rows());
  std::vector<MatArray> arrays{{"time", n, 1, Column(csv, "t")},
                               {"volts", n, 1, Column(csv, "u")},
                               {"pos_um", n, 1, Column(csv, "x", 1e6)}};
  if (csv.has("v")) arrays.push_back({"vel", n, 1, Column(csv, "v")});
  if (csv.has("a")) arrays.push_back({"acc", n, 1, Column(csv, "a")});
  WriteMat(path, MatVersion::kV5, arrays);
}

// `out` with every occurrence of `from` replaced by `to` (the recording's name in a table).
std::string Replace(std::string out, const std::string& from, const std::string& to) {
  for (size_t at = out.find(from); at != std::string::npos; at = out.find(from, at + to.size()))
    out.replace(at, from.size(), to);
  return out;
}

TEST_CASE("--var and --scale take one value each: the recording after them stays a recording",
          "[io][cli][labfiles]") {
  TempDir dir;
  REQUIRE(RunCli({"generate", "pulses", "-o", dir.path().string()}).exit_code == 0);
  // Paths of one length: the tables' columns are as wide.
  const std::string csv = dir / "pulses.csv", mat = dir / "pulses.mat";
  WriteLabMat(mat, ReadRecording(csv));
  const CliResult want = RunCli({"identify", csv});
  REQUIRE(want.exit_code == 0);
  // Both flags before the recording, each with one comma list, and repeated.
  const CliResult got = RunCli({"identify", "--var", "t=time,u=volts,x=pos_um", "--var",
                                "v=vel,a=acc", "--scale", "x=1e-6", mat});
  INFO(got.err);
  REQUIRE(got.exit_code == 0);
  CHECK(Replace(got.out, mat, csv) == want.out);
  // The flags after the recording work as well.
  const std::string model = dir / "model.json";
  REQUIRE(RunCli({"identify", csv, "-o", model}).exit_code == 0);
  const CliResult dom_want = RunCli({"dominance", "--model", model, csv});
  const CliResult dom = RunCli({"dominance", "--model", model, mat, "--var", "t=time,u=volts,x=pos_um,v=vel,a=acc",
                                "--scale", "x=1e-6"});
  INFO(dom.err);
  REQUIRE(dom.exit_code == 0);
  CHECK(Replace(dom.out, mat, csv) == dom_want.out);
  // A missing value is still a usage error, not a recording taken as the value.
  const CliResult bad = RunCli({"identify", "--scale", "x=1e-6", "--var"});
  CHECK(bad.exit_code == 1);
}

TEST_CASE("hysteresis fit, simulate and invert read a MAT recording through --var and --scale",
          "[io][cli][labfiles][hysteresis]") {
  TempDir dir;
  const std::string csv = SourcePath("datasets/piezo_aye_ang/piezo.csv"), mat = dir / "lab.mat";
  const Recording rec = ReadRecording(csv);
  WriteLabMat(mat, rec);
  const CliResult want = RunCli({"hysteresis", "fit", "--model", "pi", "--operators", "4", csv,
                                 "--json", "-o", dir / "want.json"});
  REQUIRE(want.exit_code == 0);
  const std::vector<std::string> map{"--var", "t=time,u=volts,x=pos_um", "--scale", "x=1e-6"};
  std::vector<std::string> fit{"hysteresis", "fit", "--model", "pi", "--operators", "4"};
  fit.insert(fit.end(), map.begin(), map.end());
  fit.insert(fit.end(), {mat, "--json", "-o", dir / "got.json"});
  const CliResult got = RunCli(fit);
  INFO(got.err);
  REQUIRE(got.exit_code == 0);
  // x = (x·1e6)·1e-6 differs from x in the last bit at most: the fits agree to 1e-9 relative.
  const auto a = nlohmann::json::parse(want.out), b = nlohmann::json::parse(got.out);
  CHECK(b["samples"] == a["samples"]);
  REQUIRE(b["parameters"].size() == a["parameters"].size());
  for (size_t i = 0; i < a["parameters"].size(); ++i) {
    const double pa = a["parameters"][i]["value"], pb = b["parameters"][i]["value"];
    INFO(a["parameters"][i]["name"]);
    CHECK(pb == Approx(pa).epsilon(1e-9).margin(1e-18));
  }
  for (const char* sub : {"simulate", "invert"}) {
    std::vector<std::string> args{"hysteresis", sub, "--model", dir / "want.json"};
    args.insert(args.end(), map.begin(), map.end());
    args.insert(args.end(), {mat, "-o", dir / (std::string(sub) + ".csv")});
    const CliResult r = RunCli(args);
    INFO(sub << ": " << r.err);
    CHECK(r.exit_code == 0);
    CHECK(ReadRecording(dir / (std::string(sub) + ".csv"), ReadOptions{{"t"}, {}, true, {}})
              .rows() == rec.rows());
  }
  // Without --var the lab's names are refused, naming the flag to use.
  const CliResult bare = RunCli({"hysteresis", "simulate", "--model", dir / "want.json", mat, "-o",
                                 dir / "bare.csv"});
  CHECK(bare.exit_code == 2);
  CHECK_THAT(bare.err, Catch::Contains("--var"));
}

}  // namespace
}  // namespace sysid::test
