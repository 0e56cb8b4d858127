// Lab files as they come: a MAT recording whose variables are named as the lab named them, with
// x in µm, read through --var and --scale by the commands that read recordings. The reference is
// the same command on the CSV recording the MAT file was made from: its output must be the same.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "container_fixtures.hpp"
#include "support/test_support.hpp"
#include "sysid/io.hpp"
#include "sysid/error.hpp"

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


// A ControlDesk export as matio writes its layout: struct capture with X.Data, the time (not
// uniform: a real recorder's timestamps), and the signals' Y(k).Name in ControlDesk's quoted form.
struct ControlDeskFixture {
  std::vector<double> t, u, x;
  std::vector<std::string> names{"\"Model Root\"/\"DAC\"/\"u\"/\"Out1\"",
                                 "\"Model Root\"/\"Encoder\"/\"x\"/\"Out1\""};
  explicit ControlDeskFixture(const std::string& path) {
    for (int k = 0; k < 40; ++k) {
      t.push_back(0.25 + 1e-3 * k + 1e-6 * (k % 3));
      u.push_back(std::sin(0.3 * k));
      x.push_back(1e-4 * std::cos(0.2 * k));
    }
    WriteControlDesk(path, MatVersion::kV5, "capture", t, names, {u, x});
  }
};

ReadOptions Map(std::vector<std::pair<std::string, std::string>> vars) {
  ReadOptions o;
  o.required_columns = {"t", "u", "x"};
  o.mapping.variables = std::move(vars);
  return o;
}

TEST_CASE("a ControlDesk export: X.Data, Y(k).Data and every name form reach the signals",
          "[io][mat][controldesk][labfiles]") {
  TempDir dir;
  const std::string p = dir / "capture.mat";
  const ControlDeskFixture f(p);
  const auto same = [](const Eigen::VectorXd& got, const std::vector<double>& want) {
    return std::vector<double>(got.data(), got.data() + got.size()) == want;
  };
  // As stored, without the quotes, without the port, by index, with the struct's name.
  for (const std::string& u_name :
       {f.names[0], std::string("Model Root/DAC/u/Out1"), std::string("Model Root/DAC/u"),
        std::string("Y(1).Data"), std::string("capture.Y(1).Data")}) {
    INFO(u_name);
    const Recording r = ReadRecording(p, Map({{"u", u_name}, {"x", "Model Root/Encoder/x"}}));
    CHECK(r.names == std::vector<std::string>{"t", "u", "x"});
    CHECK(same(r.column("t"), f.t));  // X.Data itself: no --rate, the recorder's timestamps
    CHECK(same(r.column("u"), f.u));
    CHECK(same(r.column("x"), f.x));
  }
  const Recording explicit_t =
      ReadRecording(p, Map({{"t", "X.Data"}, {"u", "Y(1).Data"}, {"x", "capture.Y(2).Data"}}));
  CHECK(same(explicit_t.column("t"), f.t));
  CHECK(same(explicit_t.column("x"), f.x));
  CHECK_THAT(InputErrorMessage([&] { ReadRecording(p, Map({{"u", "Y(3).Data"}, {"x", "Y(2).Data"}})); }),
             Catch::Contains("Y(3).Data: expected Y(k).Data with k = 1..2"));
  CHECK_THAT(InputErrorMessage([&] { ReadRecording(p, Map({{"u", "Model Root/DAC"}, {"x", "Y(2).Data"}})); }),
             Catch::Contains("no variable 'Model Root/DAC'") &&
                 Catch::Contains("a ControlDesk signal by its Y(k).Name or Y(k).Data"));
  // Two ports of one block: the name without the port is ambiguous, and says so.
  WriteControlDesk(dir / "two.mat", MatVersion::kV5, "capture", f.t,
                   {"\"Model Root\"/\"DAC\"/\"Out1\"", "\"Model Root\"/\"DAC\"/\"Out2\""},
                   {f.u, f.x});
  CHECK_THAT(InputErrorMessage([&] { ReadRecording(dir / "two.mat", Map({{"u", "Model Root/DAC"}, {"x", "Y(2).Data"}})); }),
             Catch::Contains("'Model Root/DAC' names 2 signals of 'capture'"));
}

TEST_CASE("every name sysid info prints for a ControlDesk export works in --var and import",
          "[io][cli][controldesk][labfiles]") {
  TempDir dir;
  const std::string p = dir / "capture.mat";
  const ControlDeskFixture f(p);
  const CliResult info = RunCli({"info", p, "--json"});
  INFO(info.err);
  REQUIRE(info.exit_code == 0);
  std::vector<std::string> shown;
  const nlohmann::json listed = nlohmann::json::parse(info.out);
  for (const auto& v : listed["variables"]) {
    shown.push_back(v["name"]);
    const std::string type = v["type"];  // "double 40x1 (capture.Y(2).Data)"
    const size_t open = type.find('(');
    const size_t end = std::min(type.find(", ", open), type.size() - 1);
    if (open != std::string::npos) shown.push_back(type.substr(open + 1, end - open - 1));
  }
  INFO(info.out);
  int read = 0;
  for (const auto& name : shown) {
    if (name == "capture") continue;  // the struct itself
    const CliResult r = RunCli({"info", p, "--var", "u=" + name + ",x=" + name});
    INFO(name << ": " << r.err);
    CHECK(r.exit_code == 0);
    ++read;
  }
  CHECK(read == 6);  // X.Data and two signals, each by name and by struct.Y(k).Data
  // import keeps X.Data as t, bit for bit, and says where it came from.
  const std::string out = dir / "rec.csv";
  const CliResult imp = RunCli({"import", "--column", "u=" + p + ":Model Root/DAC/u", "--column",
                                "x=" + p + ":Y(2).Data", "--scale", "x=1", "-o", out});
  INFO(imp.err);
  REQUIRE(imp.exit_code == 0);
  const Recording rec = ReadRecording(out);
  const Eigen::VectorXd t = rec.column("t");
  CHECK(std::vector<double>(t.data(), t.data() + t.size()) == f.t);
  CHECK(rec.meta("source.t") == p + ":X.Data");
  CHECK(rec.meta("source.u") == p + ":Model Root/DAC/u");
  CHECK(rec.meta("sample_rate_hz").empty());
}

}  // namespace
}  // namespace sysid::test
