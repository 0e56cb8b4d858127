// Lab files as they come: a MAT recording whose variables are named as the lab named them, with
// x in µm, read through --var and --scale by the commands that read recordings. The reference is
// the same command on the CSV recording the MAT file was made from: its output must be the same.
#include <fmt/format.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "container_fixtures.hpp"
#include "support/test_support.hpp"
#include "sysid/error.hpp"
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

TEST_CASE("the flags --var and --scale take one value each: the recording after them stays one",
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
  const CliResult dom = RunCli({"dominance", "--model", model, mat, "--var",
                                "t=time,u=volts,x=pos_um,v=vel,a=acc", "--scale", "x=1e-6"});
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
    CHECK(
        ReadRecording(dir / (std::string(sub) + ".csv"), ReadOptions{{"t"}, {}, true, {}}).rows() ==
        rec.rows());
  }
  // Without --var the lab's names are refused, naming the flag to use.
  const CliResult bare =
      RunCli({"hysteresis", "simulate", "--model", dir / "want.json", mat, "-o", dir / "bare.csv"});
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
  CHECK_THAT(InputErrorMessage([&] {
               ReadRecording(p, Map({{"u", "Y(3).Data"}, {"x", "Y(2).Data"}}));
             }),
             Catch::Contains("Y(3).Data: expected Y(k).Data with k = 1..2"));
  CHECK_THAT(InputErrorMessage([&] {
               ReadRecording(p, Map({{"u", "Model Root/DAC"}, {"x", "Y(2).Data"}}));
             }),
             Catch::Contains("no variable 'Model Root/DAC'") &&
                 Catch::Contains("a ControlDesk signal by its Y(k).Name or Y(k).Data"));
  // Two ports of one block: the name without the port is ambiguous, and says so.
  WriteControlDesk(dir / "two.mat", MatVersion::kV5, "capture", f.t,
                   {"\"Model Root\"/\"DAC\"/\"Out1\"", "\"Model Root\"/\"DAC\"/\"Out2\""},
                   {f.u, f.x});
  CHECK_THAT(InputErrorMessage([&] {
               ReadRecording(dir / "two.mat", Map({{"u", "Model Root/DAC"}, {"x", "Y(2).Data"}}));
             }),
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

TEST_CASE("a unit warning on a MAT recording advises --scale, on a CSV a '# units:' line",
          "[io][cli][labfiles][units]") {
  TempDir dir;
  REQUIRE(RunCli({"generate", "pulses", "-o", dir.path().string()}).exit_code == 0);
  const std::string mat = dir / "pulses.mat";
  WriteLabMat(mat, ReadRecording(dir / "pulses.csv"));
  // x in µm read as metres, v and a mapped as they are (m/s): x alone moves too fast.
  const CliResult r = RunCli({"identify", "--var", "t=time,u=volts,x=pos_um,v=vel,a=acc", mat});
  INFO(r.err);
  CHECK_THAT(r.err, Catch::Contains(mat + ": x moves at up to") &&
                        Catch::Contains("if x is in um, scale it to m with --scale x=1e-6 (a "
                                        "MAT v5 file holds no '# units:' line)") &&
                        !Catch::Contains("declare it"));
  // The advised flag removes the warning.
  const CliResult fixed = RunCli(
      {"identify", "--var", "t=time,u=volts,x=pos_um,v=vel,a=acc", "--scale", "x=1e-6", mat});
  CHECK(fixed.exit_code == 0);
  CHECK_THAT(fixed.err, !Catch::Contains("warning: " + mat));
}

TEST_CASE("derive and the hysteresis writers keep where the columns came from",
          "[io][cli][labfiles]") {
  TempDir dir;
  REQUIRE(RunCli({"generate", "pulses", "-o", dir.path().string()}).exit_code == 0);
  const std::string mat = dir / "pulses.mat", out = dir / "derived.csv";
  WriteLabMat(mat, ReadRecording(dir / "pulses.csv"));
  const CliResult r = RunCli({"derive", "--var", "t=time,u=volts,x=pos_um", "--scale", "x=1e-6",
                              "--rate", "1000", mat, "-o", out});
  // --rate with a t column mapped is refused: the mapping is checked as a whole.
  CHECK(r.exit_code == 2);
  const CliResult ok =
      RunCli({"derive", "--var", "t=time,u=volts,x=pos_um", "--scale", "x=1e-6", mat, "-o", out});
  INFO(ok.err);
  REQUIRE(ok.exit_code == 0);
  const Recording d = ReadRecording(out);
  CHECK(d.meta("source.t") == mat + ":time");
  CHECK(d.meta("source.u") == mat + ":volts");
  CHECK(d.meta("source.x") == mat + ":pos_um");
  CHECK(d.meta("scale.x") == "1e-06");
  CHECK(!d.meta("derive").empty());
  // A window is provenance too.
  const CliResult cropped = RunCli({"derive", "--var", "t=time,u=volts,x=pos_um", "--scale",
                                    "x=1e-6", "--t-start", "1", "--t-end", "2", mat, "-o", out});
  INFO(cropped.err);
  REQUIRE(cropped.exit_code == 0);
  CHECK(ReadRecording(out).meta("crop_s") == "1 2");
  // hysteresis simulate keeps t's and u's sources (its x_model is its own).
  const std::string piezo = dir / "piezo.mat";
  WriteLabMat(piezo, ReadRecording(SourcePath("datasets/piezo_aye_ang/piezo.csv")));
  const std::vector<std::string> map{"--var", "t=time,u=volts,x=pos_um", "--scale", "x=1e-6"};
  std::vector<std::string> fit{"hysteresis", "fit", "--model", "pi",          "--operators",
                               "3",          piezo, "-o",      dir / "h.json"};
  fit.insert(fit.end(), map.begin(), map.end());
  REQUIRE(RunCli(fit).exit_code == 0);
  std::vector<std::string> sim{"hysteresis", "simulate", "--model",      dir / "h.json",
                               piezo,        "-o",       dir / "sim.csv"};
  sim.insert(sim.end(), map.begin(), map.end());
  REQUIRE(RunCli(sim).exit_code == 0);
  const Recording s = ReadRecording(dir / "sim.csv", ReadOptions{{"t", "u"}, {}, true, {}});
  CHECK(s.meta("source.u") == piezo + ":volts");
  CHECK(s.meta("source.t") == piezo + ":time");
  CHECK(s.meta("source.x").empty());
  CHECK(s.meta("scale.x").empty());  // x is not written
}

// The rows of t within [a, b], counted directly: the reference for the window.
Eigen::Index RowsWithin(const Recording& r, double a, double b) {
  Eigen::Index n = 0;
  for (Eigen::Index k = 0; k < r.rows(); ++k) n += r.column("t")[k] >= a && r.column("t")[k] <= b;
  return n;
}

TEST_CASE("CropRecording keeps the rows of the window and refuses one outside or empty",
          "[io][labfiles][crop]") {
  TempDir dir;
  REQUIRE(RunCli({"generate", "pulses", "-o", dir.path().string()}).exit_code == 0);
  const Recording rec = ReadRecording(dir / "pulses.csv");
  const double first = rec.column("t")[0], last = rec.column("t")[rec.rows() - 1];
  for (const auto& [a, b] : {std::pair{first, last}, {1.0, 2.0}, {0.5005, 0.5035}, {3.2, last}}) {
    INFO(a << " .. " << b);
    const Recording c = CropRecording(rec, a, b);
    REQUIRE(c.rows() == RowsWithin(rec, a, b));
    CHECK(c.names == rec.names);
    CHECK(c.column("t")[0] >= a);
    CHECK(c.column("t")[c.rows() - 1] <= b);
    // The same rows, bit for bit, starting where t first reaches a.
    Eigen::Index k0 = 0;
    while (rec.column("t")[k0] < a) ++k0;
    CHECK(c.data == rec.data.middleRows(k0, c.rows()));
  }
  CHECK_THAT(InputErrorMessage([&] { CropRecording(rec, 1, last + 1); }),
             Catch::Contains("reaches outside the recording"));
  CHECK_THAT(InputErrorMessage([&] { CropRecording(rec, first - 1, 2); }),
             Catch::Contains("reaches outside the recording"));
  CHECK_THAT(InputErrorMessage([&] { CropRecording(rec, 1.0001, 1.0002); }),
             Catch::Contains("holds 0 samples"));
  CHECK_THAT(InputErrorMessage([&] { CropRecording(rec, 2, 1); }),
             Catch::Contains("the start before the end"));
}

TEST_CASE("a time window on every reader and a fit fraction on the fitting commands",
          "[io][cli][labfiles][crop]") {
  TempDir dir;
  REQUIRE(RunCli({"generate", "pulses", "-o", dir.path().string()}).exit_code == 0);
  const std::string csv = dir / "pulses.csv";
  const Recording rec = ReadRecording(csv);
  const CliResult info = RunCli({"info", csv, "--t-start", "1", "--t-end", "2.5", "--json"});
  INFO(info.err);
  REQUIRE(info.exit_code == 0);
  CHECK(nlohmann::json::parse(info.out)["rows"] == RowsWithin(rec, 1, 2.5));
  // Outside, empty, reversed: refused with a clear message, nothing printed.
  const CliResult outside = RunCli({"identify", csv, "--t-end", "1000"});
  CHECK(outside.exit_code == 2);
  CHECK_THAT(outside.err, Catch::Contains("reaches outside the recording"));
  CHECK(outside.out.empty());
  CHECK(RunCli({"identify", csv, "--t-start", "1.0001", "--t-end", "1.0002"}).exit_code == 2);
  CHECK(RunCli({"identify", csv, "--t-start", "2", "--t-end", "1"}).exit_code == 1);
  // --fit-fraction F fits on t <= t0 + F (tN - t0): the same as that window given by hand.
  const double first = rec.column("t")[0], last = rec.column("t")[rec.rows() - 1];
  const double cut = first + 0.5 * (last - first);
  const CliResult half = RunCli({"identify", csv, "--fit-fraction", "0.5", "--json"});
  const CliResult by_hand = RunCli({"identify", csv, "--t-end", fmt::format("{}", cut), "--json"});
  INFO(half.err);
  REQUIRE(half.exit_code == 0);
  REQUIRE(by_hand.exit_code == 0);
  CHECK(half.out == by_hand.out);
  CHECK(half.out != RunCli({"identify", csv, "--json"}).out);  // fewer pulses, another fit
  CHECK_THAT(half.err, Catch::Contains("the first 50 %") && Catch::Contains("is not used") &&
                           Catch::Contains("--t-start"));
  for (const char* bad : {"0", "1.5", "-0.2"})
    CHECK(RunCli({"identify", csv, "--fit-fraction", bad}).exit_code == 1);
  // hysteresis fit: the samples it fitted are those of the first part.
  const std::string piezo = SourcePath("datasets/piezo_aye_ang/piezo.csv");
  const Recording p = ReadRecording(piezo);
  const double p0 = p.column("t")[0], p1 = p.column("t")[p.rows() - 1];
  const CliResult h = RunCli({"hysteresis", "fit", "--model", "pi", "--operators", "3",
                              "--fit-fraction", "0.25", piezo, "--json", "-o", dir / "h.json"});
  INFO(h.err);
  REQUIRE(h.exit_code == 0);
  CHECK(nlohmann::json::parse(h.out)["samples"] == RowsWithin(p, p0, p0 + 0.25 * (p1 - p0)));
}

// tune-delay, refine and sweep: --fit-fraction F is the recording's first part, the same run as
// that part given by hand (--t-end on a single file; for sweep, a training file cut by hand,
// since --t-end would cut the test file too).
TEST_CASE("a fit fraction on tune-delay, refine and sweep fits the first part only",
          "[io][cli][labfiles][crop]") {
  TempDir dir;
  const std::string csv = SourcePath("datasets/virtual/pulses.csv");
  REQUIRE(RunCli({"identify", csv, "-o", dir / "m.json"}).exit_code == 0);
  const Recording rec = ReadRecording(csv);
  const double first = rec.column("t")[0], last = rec.column("t")[rec.rows() - 1];
  const double cut = first + 0.5 * (last - first);
  // The outputs without their wall time (the one field that differs between two runs).
  auto without_time = [](const std::string& text) {
    nlohmann::json j = nlohmann::json::parse(text);
    j.erase("wall_time_s");
    return j;
  };
  for (const std::vector<std::string>& command :
       {std::vector<std::string>{"tune-delay"},
        std::vector<std::string>{"refine", "--max-iterations", "1"}}) {
    std::vector<std::string> base = command;
    for (const std::string& a :
         {std::string("--model"), dir / "m.json", csv, std::string("--json")})
      base.push_back(a);
    auto with = [&](std::vector<std::string> extra) {
      std::vector<std::string> args = base;
      args.insert(args.end(), extra.begin(), extra.end());
      return RunCli(args);
    };
    const CliResult half = with({"--fit-fraction", "0.5"});
    const CliResult by_hand = with({"--t-end", fmt::format("{:.17g}", cut)});
    const CliResult whole = with({});
    INFO(command[0] << ": " << half.err);
    REQUIRE(half.exit_code == 0);
    REQUIRE(by_hand.exit_code == 0);
    REQUIRE(whole.exit_code == 0);
    CHECK(without_time(half.out) == without_time(by_hand.out));
    CHECK(without_time(half.out) != without_time(whole.out));
    CHECK_THAT(half.err, Catch::Contains("sysid " + command[0] + ": fitting on") &&
                             Catch::Contains("the first 50 %") &&
                             Catch::Contains(fmt::format("--t-start {:.6g}", cut)));
    CHECK(with({"--fit-fraction", "0"}).exit_code == 1);
  }
  // sweep on the training set's first 30 % against the same rows written to a file by hand.
  const std::string training = SourcePath("datasets/virtual/training.csv");
  const Recording train = ReadRecording(training);
  const double t0 = train.column("t")[0], t1 = train.column("t")[train.rows() - 1];
  std::string text = "t,u,v\n";
  const Eigen::VectorXd t = train.column("t"), u = train.column("u"), v = train.column("v");
  for (Eigen::Index k = 0; k < t.size(); ++k)
    if (t[k] <= t0 + 0.3 * (t1 - t0))
      text += fmt::format("{:.17g},{:.17g},{:.17g}\n", t[k], u[k], v[k]);
  WriteText(dir / "train_part.csv", text);
  const std::vector<std::string> sweep{"sweep",
                                       "--hidden",
                                       "2,3",
                                       "--max-epochs",
                                       "3",
                                       "--test",
                                       SourcePath("datasets/virtual/test.csv"),
                                       "--json"};
  auto run_sweep = [&](const std::string& file, std::vector<std::string> extra) {
    std::vector<std::string> args = sweep;
    args.insert(args.end(), {"--train", file});
    args.insert(args.end(), extra.begin(), extra.end());
    const CliResult r = RunCli(args);
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    return std::make_pair(nlohmann::json::parse(r.out)["rows"], r.err);
  };
  const auto [part_rows, part_err] = run_sweep(training, {"--fit-fraction", "0.3"});
  const auto [hand_rows, hand_err] = run_sweep(dir / "train_part.csv", {});
  const auto [whole_rows, whole_err] = run_sweep(training, {});
  REQUIRE(part_rows.size() == 2);
  for (size_t i = 0; i < 2; ++i) {
    CHECK(part_rows[i]["train_mse"].get<double>() ==
          Approx(hand_rows[i]["train_mse"].get<double>()).epsilon(1e-12));
    CHECK(part_rows[i]["test_mse"].get<double>() ==
          Approx(hand_rows[i]["test_mse"].get<double>()).epsilon(1e-12));
    CHECK(part_rows[i]["train_mse"] != whole_rows[i]["train_mse"]);
  }
  CHECK_THAT(part_err,
             Catch::Contains("sysid sweep: fitting on") && Catch::Contains("the first 30 %"));
}

}  // namespace
}  // namespace sysid::test
