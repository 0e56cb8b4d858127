// No writer publishes inf or NaN (the readers refuse both, so such a file could not be read
// back), and the finite inputs that used to overflow into them are errors with the reason:
// a gain of 1e308 in the pulse least squares, a --scale factor, a network range of +-1e308.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <limits>
#include <string>

#include "support/test_support.hpp"
#include "sysid/error.hpp"
#include "sysid/identify.hpp"
#include "sysid/io.hpp"
#include "sysid/io_containers.hpp"
#include "sysid/model.hpp"
#include "sysid/nn.hpp"

using sysid::test::RunCli;
using sysid::test::SourcePath;
using sysid::test::TempDir;

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}  // namespace

TEST_CASE("writers refuse inf and NaN and leave no file", "[io][errors]") {
  TempDir dir;
  sysid::Recording rec;
  rec.names = {"t", "u", "x"};
  rec.data = Eigen::MatrixXd::Zero(3, 3);
  rec.data(1, 0) = 0.001;
  rec.data(2, 0) = 0.002;
  rec.data(2, 1) = kInf;
  CHECK_THROWS_WITH(sysid::WriteRecording(dir / "r.csv", rec),
                    Catch::Contains("r.csv: column 'u', row 3 is Inf"));
  CHECK_THROWS_AS(sysid::FormatRecording(rec), sysid::NumericalError);
  CHECK_THROWS_AS(sysid::WriteRecordingByExtension(dir / "r.mat", rec), sysid::NumericalError);
  rec.data(2, 1) = 1;  // finite again: written, and reads back
  sysid::WriteRecording(dir / "r.csv", rec);
  CHECK(sysid::ReadRecording(dir / "r.csv").data == rec.data);

  sysid::FrictionModel m = sysid::FrictionModel::Paper();
  m.a1n = std::nan("");
  CHECK_THROWS_WITH(sysid::WriteModel(dir / "m.json", m), Catch::Contains("a1n = nan"));
  CHECK_FALSE(std::filesystem::exists(dir / "m.json"));

  sysid::NeuralNetwork net({{"v", "m/s", -0.1, 0.1}}, {"u", "V", -2, 2}, 2);
  Eigen::VectorXd theta = net.parameters();
  theta[0] = kInf;
  net.set_parameters(theta);
  CHECK_THROWS_WITH(sysid::WriteNeuralNetwork(dir / "n.json", net),
                    Catch::Contains("n.json: the network's weights hold inf or NaN"));
  CHECK_FALSE(std::filesystem::exists(dir / "n.json"));
}

TEST_CASE("finite inputs that overflowed are errors with the reason", "[io][errors]") {
  TempDir dir;
  // The pulse least squares with a3 = 1e308: its targets a3 |u| overflow. Exit 3, no file.
  auto r = RunCli({"identify", "--a3", "1e308", SourcePath("datasets/virtual/pulses.csv"), "-o",
                   dir / "m.json"});
  CHECK(r.exit_code == 3);
  CHECK_THAT(r.err, Catch::Contains("least squares for a1p, a2p, a1n, a2n: the target holds inf"));
  CHECK_FALSE(std::filesystem::exists(dir / "m.json"));
  sysid::PulseFitOptions fit;
  fit.a3 = 1e308;
  const auto table = sysid::ReadPulseTable(SourcePath("datasets/paper/pulse_table.csv"));
  CHECK_THROWS_AS(sysid::FitPulseTable(table, fit), sysid::NumericalError);

  // A --scale that takes a value past the largest double: a usage error naming the value.
  const std::string pz = SourcePath("datasets/piezo_aye_ang/Model_Vi_Do.dat");
  r = RunCli({"import", "--column", "u=" + pz + ":1", "--column", "x=" + pz + ":5", "--scale",
              "x=1e308", "--rate", "200", "-o", dir / "p.csv"});
  CHECK(r.exit_code == 1);
  CHECK_THAT(r.err, Catch::Contains("--scale x=1e+308: ") && Catch::Contains("[1] becomes -Inf"));
  CHECK_FALSE(std::filesystem::exists(dir / "p.csv"));

  // A network range whose width overflows: the scaling would divide by inf.
  r = RunCli({"train", "--train", SourcePath("datasets/virtual/training.csv"), "--inputs", "v",
              "--output", "u", "--hidden", "2", "--max-epochs", "1", "--output-range",
              "-1e308:1e308", "-o", dir / "n.json"});
  CHECK(r.exit_code == 1);
  CHECK_THAT(r.err, Catch::Contains("max - min finite"));
  sysid::test::WriteText(
      dir / "wide.json",
      R"({"type": "tanh-mlp", "inputs": [{"name": "v", "unit": "m/s", "min": -0.1, "max": 0.1}],
 "output": {"name": "u", "unit": "V", "min": -1e308, "max": 1e308}, "hidden": 1,
 "W1": [[1]], "b1": [0], "W2": [1], "b2": 0})");
  CHECK_THROWS_WITH(sysid::ReadNeuralNetwork(dir / "wide.json"),
                    Catch::StartsWith(dir / "wide.json:2:") &&
                        Catch::Contains("output.max: expected a number > min") &&
                        Catch::Contains("max - min finite"));
}
