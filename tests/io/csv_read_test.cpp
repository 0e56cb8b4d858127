#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <random>
#include <string>

#include "support/test_support.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"

using sysid::test::RunCli;
using sysid::test::TempDir;
using sysid::test::TestData;

TEST_CASE("a file with BOM and CRLF reads the same as a clean one", "[io]") {
  const auto clean = sysid::ReadRecording(TestData("io/good.csv"));
  const auto bom = sysid::ReadRecording(TestData("io/good_bom_crlf.csv"));
  CHECK(bom.names == clean.names);
  REQUIRE(bom.rows() == 3);
  CHECK(bom.data == clean.data);  // exact: the same text must give the same doubles
  CHECK(clean.column("x")[2] == 3e-6);
}

TEST_CASE("metadata lines are kept in order, plain comments are not", "[io]") {
  const auto rec = sysid::ReadRecording(TestData("io/good_metadata.csv"));
  REQUIRE(rec.metadata.size() == 2);
  CHECK(rec.meta("stage") == "virtual");
  CHECK(rec.meta("units") == "t [s], u [V], x [m]");
  CHECK(rec.meta("absent", "fallback") == "fallback");
}

TEST_CASE("control bytes in metadata and names never reach a terminal or break a line", "[io]") {
  TempDir dir;
  const std::string path = dir / "esc.csv";
  // An OSC title sequence and a screen clear in a comment: kept, as \xHH text.
  sysid::test::WriteText(path, "# note: a\x1b]0;t\x07\x1b[2J b\nt,u,x\n0,1,0\n0.001,1,0\n");
  const auto rec = sysid::ReadRecording(path);
  CHECK(rec.meta("note") == "a\\x1B]0;t\\x07\\x1B[2J b");
  // A column name with one is an error at its place.
  sysid::test::WriteText(path, "t,u,x\x1b[2J\n0,1,0\n0.001,1,0\n");
  CHECK_THROWS_WITH(sysid::ReadRecording(path),
                    Catch::StartsWith(path + ":1:5: header: expected a column name of printable") &&
                        Catch::Contains("\"x\\x1B[2J\"") && !Catch::Contains("\x1b"));
  // A metadata value with a newline (a file name may hold one) is written as one line and
  // reads back as the same text.
  sysid::Recording out;
  out.names = {"t", "u", "x"};
  out.data = Eigen::MatrixXd::Zero(2, 3);
  out.data(1, 0) = 0.001;
  out.metadata = {{"input", "lab\nrun 2.csv"}, {"unit", "m/s\xC2\xB2"}};
  sysid::WriteRecording(path, out);
  const auto back = sysid::ReadRecording(path);
  REQUIRE(back.metadata.size() == 2);
  CHECK(back.meta("input") == "lab\\x0Arun 2.csv");
  CHECK(back.meta("unit") == "m/s\xC2\xB2");  // UTF-8 text passes unchanged
  CHECK(back.names == out.names);
}

TEST_CASE("a file name with an escape sequence reaches the terminal as text", "[io][cli]") {
  TempDir dir;
  const std::string name = dir / "e\x1b[2J\x1b]0;t\x07\xc2\x9bx.csv";
  sysid::test::WriteText(name, "t,u,x\n0,1,zz\n");
  const auto r = RunCli({"info", name});
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Catch::Contains("e\\x1B[2J\\x1B]0;t\\x07\\x9Bx.csv:2:5: column 'x'"));
  CHECK(r.err.find('\x1b') == std::string::npos);
  CHECK(r.err.find('\x07') == std::string::npos);
}

TEST_CASE("numbers parse exactly as strtod does, signs and exponents included", "[io]") {
  const std::string text = "t,u,v\n0,+1.5,-2.5e-3\n1e-3, 2 ,.5\n2E-3,-0,1.7976931348623157e308\n";
  const auto rec = sysid::ParseRecording(text, "mem");
  CHECK(rec.data(0, 1) == 1.5);
  CHECK(rec.data(0, 2) == std::strtod("-2.5e-3", nullptr));
  CHECK(rec.data(1, 1) == 2.0);
  CHECK(rec.data(1, 2) == 0.5);
  CHECK(rec.data(2, 0) == 2e-3);
  CHECK(rec.data(2, 2) == 1.7976931348623157e308);
  CHECK_THROWS_WITH(sysid::ParseRecording("t,u,v\n0,1,1e999\n", "mem"),
                    Catch::Contains("mem:2:5: column 'v': number out of range"));
}

TEST_CASE("write then read round-trips every double exactly, atomically", "[io]") {
  std::mt19937_64 gen(42);
  std::uniform_real_distribution<double> dist(-1e3, 1e3);
  sysid::Recording rec;
  rec.names = {"t", "u", "x"};
  rec.metadata = {{"seed", "42"}};
  rec.data.resize(500, 3);
  for (int r = 0; r < 500; ++r) {
    rec.data(r, 0) = r * 1e-3;
    rec.data(r, 1) = dist(gen);
    rec.data(r, 2) = dist(gen) * 1e-9;
  }
  TempDir dir;
  const std::string path = dir / "out.csv";
  sysid::WriteRecording(path, rec);
  const auto back = sysid::ReadRecording(path);
  CHECK(back.data == rec.data);
  CHECK(back.meta("seed") == "42");
  // No temporary file is left beside the result.
  int files = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir.path())) {
    (void)e;
    ++files;
  }
  CHECK(files == 1);
  CHECK_THROWS_AS(sysid::WriteRecording("/nonexistent/dir/out.csv", rec), sysid::InputError);
}

TEST_CASE("sampling analysis: nominal rate, jitter, irregular sampling", "[io]") {
  Eigen::VectorXd t(1001);
  for (int k = 0; k <= 1000; ++k) t[k] = k * 1e-3;
  auto s = sysid::AnalyzeSampling(t);
  CHECK(s.sample_rate_hz == Approx(1000.0).epsilon(1e-12));
  CHECK(s.max_jitter_s < 1e-15);  // k * 1e-3 rounding only
  CHECK_FALSE(s.irregular);
  t[500] += 0.3e-3;  // one sample late by 30 % of the interval
  s = sysid::AnalyzeSampling(t);
  CHECK(s.irregular);
  CHECK(s.max_jitter_s == Approx(0.3e-3).epsilon(1e-9));
  CHECK((s.worst_index == 499 || s.worst_index == 500));
}

TEST_CASE("resampling onto a uniform grid is exact for linear signals", "[io]") {
  sysid::Recording rec;
  rec.names = {"t", "u", "x"};
  rec.data.resize(4, 3);
  rec.data << 0.0, 1.0, 0.0,  //
      0.0013, 1.0, 0.0026,    //
      0.0021, 1.0, 0.0042,    //
      0.0040, 1.0, 0.0080;
  const auto out = sysid::Resample(rec, 1000.0);
  REQUIRE(out.rows() == 5);
  for (int k = 0; k < 5; ++k) {
    CHECK(out.data(k, 0) == Approx(k * 1e-3).margin(1e-15));
    CHECK(out.data(k, 2) == Approx(2.0 * k * 1e-3).margin(1e-15));  // x = 2 t exactly
  }
  CHECK_THROWS_AS(sysid::Resample(rec, 0.0), sysid::OptionsError);
}

TEST_CASE("sysid info --json summarises a recording", "[io][cli]") {
  const auto r = RunCli({"info", "--json", TestData("io/good_metadata.csv")});
  REQUIRE(r.exit_code == 0);
  const auto j = nlohmann::json::parse(r.out);
  CHECK(j["rows"] == 3);
  CHECK(j["columns"] == nlohmann::json::array({"t", "u", "x"}));
  CHECK(j["duration_s"].get<double>() == Approx(0.002));
  CHECK(j["sample_rate_hz"].get<double>() == Approx(1000.0));
  CHECK(j["metadata"]["stage"] == "virtual");
}

TEST_CASE("a recording's shape as JSON, with the SI unit of each column", "[io][json]") {
  sysid::Recording r;
  r.SetColumn("t", Eigen::Vector3d(0.5, 1.0, 1.5));
  r.SetColumn("waveform", Eigen::Vector3d(0, 0, 1));
  r.SetColumn("x_ref", Eigen::Vector3d(0, 1e-3, 2e-3));
  r.SetColumn("a_ref", Eigen::Vector3d(0, 0, 0));
  const auto j = nlohmann::json::parse(sysid::RecordingShapeToJson(r));
  CHECK(j["samples"] == 3);
  CHECK(j["duration_s"] == 1.0);
  CHECK(j["columns"] == nlohmann::json({"t", "waveform", "x_ref", "a_ref"}));
  CHECK(j["units"] == nlohmann::json({{"t", "s"}, {"waveform", "1"}, {"x_ref", "m"},
                                      {"a_ref", "m/s^2"}}));
  CHECK(sysid::ColumnUnit("u") == "V");
  CHECK(sysid::ColumnUnit("v_ref") == "m/s");
  CHECK(nlohmann::json::parse(sysid::RecordingShapeToJson(sysid::Recording{}))["duration_s"] == 0.0);
}

TEST_CASE("a recording's summary as JSON: sampling, ranges and metadata", "[io][json]") {
  sysid::Recording r;
  r.source = "rec.csv";
  // Intervals 1, 1, 1.5 ms: median 1 ms, worst at the third interval (row 4 of the file).
  r.SetColumn("t", Eigen::Vector4d(0, 0.001, 0.002, 0.0035));
  r.SetColumn("u", Eigen::Vector4d(0, 1, -1, 2));
  r.metadata = {{"stage", "virtual"}};
  const auto j = nlohmann::json::parse(sysid::RecordingSummaryToJson(r, 0.01));
  CHECK(j["file"] == "rec.csv");
  CHECK(j["rows"] == 4);
  CHECK(j["duration_s"].get<double>() == Approx(0.0035));
  CHECK(j["t_start_s"] == 0.0);
  CHECK(j["sample_rate_hz"].get<double>() == Approx(1000.0));
  CHECK(j["sampling"]["max_relative_jitter"].get<double>() == Approx(0.5));
  CHECK(j["sampling"]["irregular"] == true);
  CHECK_THAT(j["sampling"]["warning"].get<std::string>(), Catch::Contains("row 4"));
  CHECK(j["column_stats"]["u"]["min"] == -1.0);
  CHECK(j["column_stats"]["u"]["max"] == 2.0);
  CHECK(j["column_stats"]["u"]["mean"].get<double>() == Approx(0.5));
  CHECK(j["metadata"]["stage"] == "virtual");
  // A tolerance above the jitter: regular, no warning; one row: no sampling at all.
  const auto loose = nlohmann::json::parse(sysid::RecordingSummaryToJson(r, 0.6));
  CHECK(loose["sampling"]["irregular"] == false);
  CHECK_FALSE(loose["sampling"].contains("warning"));
  sysid::Recording one;
  one.SetColumn("t", Eigen::VectorXd::Constant(1, 2.0));
  const auto single = nlohmann::json::parse(sysid::RecordingSummaryToJson(one, 0.01));
  CHECK(single["sample_rate_hz"].is_null());
  CHECK_FALSE(single.contains("sampling"));
}
