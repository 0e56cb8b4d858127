// One recording, three files (our CSV, MAT v5 via WriteRecordingMat, HDF5 via the HDF5 library):
// identify, dominance and compare must print the same results for each (the file name aside).
#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "container_fixtures.hpp"
#include "support/test_support.hpp"
#include "sysid/io.hpp"
#include "sysid/io_containers.hpp"
#include "sysid/model.hpp"

namespace sysid::test {
namespace {

std::string Replace(std::string s, const std::string& from, const std::string& to) {
  for (size_t p = s.find(from); p != std::string::npos; p = s.find(from, p + to.size()))
    s.replace(p, from.size(), to);
  return s;
}

// Runs `args` + {file} for each file; the outputs with the file's path (and stem) replaced.
std::vector<std::string> RunEach(const std::vector<std::string>& args,
                                 const std::vector<std::string>& files) {
  std::vector<std::string> outs;
  for (const auto& f : files) {
    auto a = args;
    a.push_back(f);
    const CliResult r = RunCli(a);
    INFO(f << ": " << r.err);
    REQUIRE(r.exit_code == 0);
    outs.push_back(Replace(r.out, f, "REC"));
  }
  return outs;
}

TEST_CASE(
    "a recording from MAT, HDF5 and CSV gives identical identify, dominance and compare "
    "results",
    "[io][mat][hdf5][cli]") {
  TempDir dir;
  Recording rec = ReadRecording(SourcePath("datasets/virtual/pulses.csv"));
  rec.metadata.clear();  // MAT and HDF5 carry no metadata lines
  const std::string csv = dir / "rec.csv", mat = dir / "rec.mat", h5 = dir / "rec.h5";
  WriteRecording(csv, rec);
  WriteRecordingMat(mat, rec);
  std::vector<H5Array> arrays;
  for (size_t c = 0; c < rec.names.size(); ++c) {
    const Eigen::VectorXd col = rec.data.col(static_cast<Eigen::Index>(c));
    arrays.push_back({"/" + rec.names[c],
                      {static_cast<std::uint64_t>(col.size())},
                      std::vector<double>(col.data(), col.data() + col.size())});
  }
  WriteH5(h5, arrays);
  const std::vector<std::string> files{csv, mat, h5};

  auto out = RunEach({"identify", "--method", "pulse", "--json"}, files);
  CHECK(out[1] == out[0]);
  CHECK(out[2] == out[0]);
  const FrictionModel model = ParseModel(out[0], "identify");
  WriteText(dir / "m.json", out[0]);

  out = RunEach({"dominance", "--model", dir / "m.json", "--json", "--threads", "1"}, files);
  CHECK(out[1] == out[0]);
  CHECK(out[2] == out[0]);

  out = RunEach({"compare", "--model", dir / "m.json", "--json"}, files);
  CHECK(out[1] == out[0]);
  CHECK(out[2] == out[0]);
  CHECK(model.a3 > 0);
}

}  // namespace
}  // namespace sysid::test

namespace sysid::test {
namespace {

TEST_CASE("compare --traces mat writes the traces as MAT v5, equal to the CSV ones",
          "[io][mat][cli]") {
  TempDir dir;
  const std::string rec = SourcePath("datasets/virtual/pulses.csv");
  CliResult r = RunCli({"identify", "--method", "pulse", "--json", rec});
  REQUIRE(r.exit_code == 0);
  WriteText(dir / "m.json", r.out);
  r = RunCli({"compare", "--model", dir / "m.json", "--no-plots", "-o", dir / "csv", rec});
  REQUIRE(r.exit_code == 0);
  r = RunCli({"compare", "--model", dir / "m.json", "--no-plots", "--traces", "mat", "-o",
              dir / "mat", rec});
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  ReadOptions any;
  any.required_columns.clear();
  any.any_of_columns.clear();
  const Recording a = ReadRecording(dir / "csv/pulses_traces.csv", any);
  const Recording b = ReadRecording(dir / "mat/pulses_traces.mat", any);
  CHECK(b.names == a.names);
  CHECK(b.data == a.data);
}

}  // namespace
}  // namespace sysid::test

namespace sysid::test {
namespace {

TEST_CASE("identify --table reads a MAT pulse table through --var", "[io][mat][cli]") {
  TempDir dir;
  const std::string csv = SourcePath("datasets/paper/pulse_table.csv");
  ReadOptions table;
  table.required_columns = {"u", "v"};
  table.any_of_columns.clear();
  const Recording t = ReadRecording(csv, table);
  const Eigen::VectorXd u = t.column("u"), v = t.column("v");
  const auto n = static_cast<std::size_t>(t.rows());
  WriteMat(dir / "table.mat", MatVersion::kV5,
           {{"volts", n, 1, std::vector<double>(u.data(), u.data() + u.size())},
            {"speed", 1, n, std::vector<double>(v.data(), v.data() + v.size())}});
  const CliResult a = RunCli({"identify", "--table", csv, "--json"});
  const CliResult b = RunCli({"identify", "--table", dir / "table.mat", "--var",
                              "u=volts,v=speed", "--json"});
  INFO(b.err);
  REQUIRE(a.exit_code == 0);
  REQUIRE(b.exit_code == 0);
  CHECK(ParseModel(b.out, "b").a1p == ParseModel(a.out, "a").a1p);
  CHECK(ParseModel(b.out, "b").a2n == ParseModel(a.out, "a").a2n);
}

}  // namespace
}  // namespace sysid::test
