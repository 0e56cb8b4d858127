// Issue #24's two gaps: `sysid generate --format mat` writes the data-set folder as MAT v5, and
// `sysid pipeline` reads MAT/HDF5 recordings in its folder, through --var/--rate/--scale.
// The reference is the CSV folder of the same seed: the CSV holds each double's shortest
// round-trip text, so both folders carry the same values and must identify the same model.
#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "support/test_support.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"
#include "sysid/io_containers.hpp"
#include "sysid/pipeline.hpp"

using sysid::test::RunCli;
using sysid::test::TempDir;
namespace fs = std::filesystem;

namespace {

// The stage-method pipeline at its smallest (one 4-unit network, 3 epochs, no tracking).
nlohmann::json SmallPipelineJson(const std::vector<std::string>& extra) {
  std::vector<std::string> args = {"pipeline", "--hidden", "4", "--max-epochs", "3",
                                   "--no-typical", "--no-track", "--threads", "1", "--json"};
  args.insert(args.end(), extra.begin(), extra.end());
  const auto r = RunCli(args);
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  nlohmann::json j = nlohmann::json::parse(r.out);
  j.erase("report");  // the output folder's path
  j.erase("steps");   // wall times
  return j;
}

// DIR/SUB/NAME as text.
std::string In(const TempDir& dir, const std::string& sub, const std::string& name) {
  return (dir.path() / sub / name).string();
}

std::vector<std::string> FilesIn(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace

TEST_CASE("generate --format mat writes the CSV folder's recordings as MAT files, and the "
          "pipeline identifies the same model from them",
          "[pipeline][mat][cli]") {
  TempDir dir;
  REQUIRE(RunCli({"generate", "all", "--seed", "5", "-o", dir / "csv"}).exit_code == 0);
  REQUIRE(RunCli({"generate", "all", "--seed", "5", "--format", "mat", "-o", dir / "mat"})
              .exit_code == 0);
  const auto csv_names = FilesIn(dir / "csv"), mat_names = FilesIn(dir / "mat");
  REQUIRE(csv_names.size() == mat_names.size());
  size_t recordings = 0;
  for (size_t i = 0; i < csv_names.size(); ++i) {
    const fs::path c = csv_names[i];
    if (c.extension() != ".csv") {
      CHECK(mat_names[i] == csv_names[i]);  // stage.json
      continue;
    }
    REQUIRE(mat_names[i] == c.stem().string() + ".mat");
    const auto csv = sysid::ReadRecording(In(dir, "csv", c.string()));
    const auto mat = sysid::ReadRecording(In(dir, "mat", mat_names[i]));
    INFO(mat_names[i]);
    CHECK(sysid::DescribeFileFormat(In(dir, "mat", mat_names[i])) == "MAT v5");
    CHECK(mat.names == csv.names);
    REQUIRE(mat.data.rows() == csv.data.rows());
    CHECK(mat.data == csv.data);  // the CSV's shortest round-trip text: equal to the bit
    ++recordings;
  }
  CHECK(recordings == 10);  // pulses, training, test, the triangle loop, six waveforms

  const auto from_csv = SmallPipelineJson({dir / "csv", "-o", dir / "rep_csv"});
  const auto from_mat = SmallPipelineJson({dir / "mat", "-o", dir / "rep_mat"});
  CHECK(from_mat["model"]["a1p"].get<double>() > 50);  // a real identification, not empty
  CHECK(from_mat == from_csv);

  // A MAT file of the same name that generate did not write is kept without --force.
  sysid::Recording own;
  own.names = {"t", "u", "x"};
  own.data = Eigen::MatrixXd::Zero(3, 3);
  own.data.col(0) << 0, 1e-3, 2e-3;
  // A header that does not name sysid, as a lab's own MAT export has.
  sysid::WriteRecordingMat(In(dir, "mat", "pulses.mat"), own, "exported by the lab's rig");
  const auto refused = RunCli({"generate", "pulses", "--format", "mat", "-o", dir / "mat"});
  CHECK(refused.exit_code == 1);
  CHECK_THAT(refused.err, Catch::Contains("pulses.mat exists and was not written by sysid (it "
                                          "does not start with sysid's generator mark)"));
  CHECK(sysid::ReadRecording(In(dir, "mat", "pulses.mat")).rows() == 3);
  CHECK(RunCli({"generate", "pulses", "--format", "mat", "--force", "-o", dir / "mat"})
            .exit_code == 0);
  CHECK(sysid::ReadRecording(In(dir, "mat", "pulses.mat")).rows() > 1000);
}

TEST_CASE("sysid pipeline maps every MAT recording of its folder with --var/--rate/--scale",
          "[pipeline][mat][cli]") {
  TempDir dir;
  REQUIRE(RunCli({"generate", "pulses", "--seed", "6", "-o", dir / "csv"}).exit_code == 0);
  REQUIRE(RunCli({"generate", "tracking", "--seed", "6", "-o", dir / "csv"}).exit_code == 0);
  // A lab's files: no time vector (1 kHz), the voltage as "volts", the position in µm.
  fs::create_directory(dir / "lab");
  for (const std::string name : {"pulses", "training", "test"}) {
    const auto rec = sysid::ReadRecording(In(dir, "csv", (name + ".csv")));
    REQUIRE(rec.meta("sample_rate_hz") == "1000");
    sysid::Recording lab;
    lab.SetColumn("volts", rec.column("u"));
    lab.SetColumn("pos_um", 1e6 * rec.column("x"));
    lab.SetColumn("v", rec.column("v"));
    lab.SetColumn("a", rec.column("a"));
    sysid::WriteRecordingMat(In(dir, "lab", (name + ".mat")), lab);
  }
  const std::vector<std::string> mapping = {"--var", "u=volts,x=pos_um,v=v,a=a", "--rate",
                                            "1000", "--scale", "x=1e-6"};
  std::vector<std::string> lab_args = {dir / "lab", "-o", dir / "rep_lab"};
  lab_args.insert(lab_args.end(), mapping.begin(), mapping.end());
  const auto from_lab = SmallPipelineJson(lab_args);
  const auto from_csv = SmallPipelineJson({dir / "csv", "-o", dir / "rep_csv"});
  // t = k / rate and x = (1e6 x) 1e-6 differ from the generated values in the last bits only:
  // the pulse least squares agrees to 1e-6, the delay to BOBYQA's step tolerance (1e-7 s,
  // DelayTuningOptions::x_tolerance_s; measured 1.1e-7 s apart).
  for (const char* p : {"a1p", "a1n", "a2p", "a2n"}) {
    INFO(p);
    CHECK(from_lab["model"][p].get<double>() ==
          Approx(from_csv["model"][p].get<double>()).epsilon(1e-6));
  }
  CHECK(from_lab["model"]["tau"].get<double>() ==
        Approx(from_csv["model"]["tau"].get<double>()).margin(5e-7));
  CHECK(from_lab["dominant"] == from_csv["dominant"]);
  // The report says how its files were read.
  CHECK_THAT(sysid::test::ReadText(In(dir, "rep_lab", "report.md")),
             Catch::Contains("Read with `--var u=volts,x=pos_um,v=v,a=a --rate 1000 --scale "
                             "x=1e-06`."));

  // Without the mapping the lab files have no t, u, x: the error names the file (exit 2).
  const auto bare = RunCli({"pipeline", dir / "lab", "-o", dir / "rep_bare"});
  CHECK(bare.exit_code == 2);
  CHECK_THAT(bare.err, Catch::Contains("lab/pulses.mat"));
  CHECK_FALSE(fs::exists(dir / "rep_bare"));
  // A mapping naming a variable the files lack: exit 2, naming file and variable.
  const auto wrong = RunCli({"pipeline", dir / "lab", "-o", dir / "rep_wrong", "--var",
                             "u=volt,x=pos_um", "--rate", "1000"});
  CHECK(wrong.exit_code == 2);
  CHECK_THAT(wrong.err, Catch::Contains("pulses.mat") && Catch::Contains("volt"));
}

TEST_CASE("the pipeline folder picks up .mat, .h5 and .hdf5 recordings by the same names",
          "[pipeline][mat]") {
  TempDir dir;
  for (const char* name : {"pulses_1.mat", "pulses_2.H5", "training.hdf5", "test.csv",
                           "waveform_a.mat", "loop_b.h5", "notes.txt"})
    sysid::test::WriteText(dir / name, "");
  const auto in = sysid::PipelineInputs::FromDirectory(dir.path().string());
  CHECK(in.pulses.size() == 2);
  CHECK(fs::path(in.training).filename() == "training.hdf5");
  CHECK(fs::path(in.test).filename() == "test.csv");
  CHECK(in.waveforms.size() == 1);
  CHECK(in.loops.size() == 1);

  // One recording in two formats is ambiguous: refused, naming both.
  sysid::test::WriteText(dir / "test.mat", "");
  CHECK_THROWS_WITH(sysid::PipelineInputs::FromDirectory(dir.path().string()),
                    Catch::Contains("test.csv and test.mat are the same recording"));

  // Without pulses, training or test: a stack data set, MAT and HDF5 files included.
  TempDir stack;
  for (const char* name : {"run1.mat", "run2.h5", "run3.csv"})
    sysid::test::WriteText(stack / name, "");
  CHECK(sysid::PipelineInputs::FromDirectory(stack.path().string()).stack.size() == 3);
}
