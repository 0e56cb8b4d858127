// MAT (v5, v5 compressed, v7.3) and HDF5 recordings through ReadRecording and a SourceMapping.
// The reference is the values the fixture wrote with matio / HDF5 themselves: every value must
// come back bit for bit.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "container_fixtures.hpp"
#include "support/test_support.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"
#include "sysid/io_containers.hpp"

namespace sysid::test {
namespace {

std::vector<double> Ramp(size_t n, double scale, double offset = 0) {
  std::vector<double> v(n);
  for (size_t i = 0; i < n; ++i)
    v[i] = offset + scale * std::sin(0.37 * static_cast<double>(i) + 0.1);
  return v;
}

ReadOptions Map(std::vector<std::pair<std::string, std::string>> vars, double rate_hz = 0) {
  ReadOptions o;
  o.mapping.variables = std::move(vars);
  o.mapping.rate_hz = rate_hz;
  return o;
}

void CheckColumn(const Recording& r, const std::string& name, const std::vector<double>& want) {
  REQUIRE(r.rows() == static_cast<Eigen::Index>(want.size()));
  const auto c = r.column(name);
  for (size_t i = 0; i < want.size(); ++i) REQUIRE(c[static_cast<Eigen::Index>(i)] == want[i]);
}

TEST_CASE("MAT v4, v5, v5 compressed and v7.3: named variables are a recording, bit for bit",
          "[io][mat]") {
  TempDir dir;
  const auto u = Ramp(50, 2.5), x = Ramp(50, 1e-3, 0.01);
  std::vector<double> t(50);
  for (size_t i = 0; i < t.size(); ++i) t[i] = 0.001 * static_cast<double>(i);
  for (const auto version :
       {MatVersion::kV4, MatVersion::kV5, MatVersion::kV5Compressed, MatVersion::kV73}) {
    const std::string path = dir / "rec.mat";
    // t a column vector, u and x row vectors: both orientations are vectors.
    WriteMat(path, version, {{"t", 50, 1, t}, {"u", 1, 50, u}, {"x", 1, 50, x}});
    CHECK(DetectFileFormat(path) == FileFormat::kMat);
    const Recording r = ReadRecording(path);  // no mapping: the variables' own names
    CHECK(r.names == std::vector<std::string>{"t", "u", "x"});
    CheckColumn(r, "t", t);
    CheckColumn(r, "u", u);
    CheckColumn(r, "x", x);
    CHECK(r.source == path);
  }
  CHECK(DescribeFileFormat(dir / "rec.mat") == "MAT v7.3");
}

TEST_CASE("a mapping picks variables, matrix columns (1-based) and derives t from the rate",
          "[io][mat]") {
  TempDir dir;
  const std::string path = dir / "m.mat";
  // data is 40 x 3, column-major: column k holds Ramp(40, k).
  std::vector<double> data;
  for (int k = 1; k <= 3; ++k) {
    const auto c = Ramp(40, k);
    data.insert(data.end(), c.begin(), c.end());
  }
  WriteMat(path, MatVersion::kV5Compressed, {{"data", 40, 3, data}});
  const Recording r = ReadRecording(path, Map({{"u", "data[:,2]"}, {"x", "data[:,3]"}}, 500));
  CHECK(r.names == std::vector<std::string>{"t", "u", "x"});
  CheckColumn(r, "u", Ramp(40, 2));
  CheckColumn(r, "x", Ramp(40, 3));
  CHECK(r.column("t")[39] == 39.0 / 500);  // t = k / rate, k from 0
  // A row of the matrix: data[2,:] is the second sample of each column.
  const Recording row = ReadRecording(path, Map({{"u", "data[2,:]"}, {"x", "data[3,:]"}}, 1));
  CHECK(row.rows() == 3);
  CHECK(row.column("u")[1] == Ramp(40, 2)[1]);

  CHECK_THAT(InputErrorMessage([&] {
               ReadRecording(path, Map({{"u", "data[:,4]"}, {"x", "data[:,1]"}}, 1));
             }),
             Catch::Contains("m.mat:data[:,4]: column 4 out of range: the matrix is double 40x3 "
                             "(indices are 1-based, like MATLAB)"));
  CHECK_THAT(InputErrorMessage([&] {
               ReadRecording(path, Map({{"u", "data[:,0]"}}, 1));
             }),
             Catch::Contains("index 0: indices start at 1"));
  CHECK_THAT(InputErrorMessage([&] {
               ReadRecording(path, Map({{"u", "data"}, {"x", "data"}}, 1));
             }),
             Catch::Contains("m.mat:data: is a matrix (double 40x3); pick a column with "
                             "data[:,k] or a row with data[k,:] (k 1-based, like MATLAB)"));
  CHECK_THAT(InputErrorMessage([&] {
               ReadRecording(path, Map({{"u", "data[:,1]"}, {"x", "data[:,2]"}}));
             }),
             Catch::Contains("no time column 't'") && Catch::Contains("--rate"));
}

TEST_CASE("integer and single classes are converted to double", "[io][mat]") {
  TempDir dir;
  for (const auto version : {MatVersion::kV5, MatVersion::kV73}) {
    WriteMatOddVariable(dir / "i.mat", version, "u", "int16");
    CHECK(ReadSignal(dir / "i.mat", "u") == Eigen::Vector3d(-2, 0, 7));
    WriteMatOddVariable(dir / "s.mat", version, "u", "single");
    CHECK(ReadSignal(dir / "s.mat", "u") == Eigen::Vector3d(0.5, 1.25, -3.0));  // exact in float
  }
}

TEST_CASE("complex, sparse, cell, char, struct and empty variables are refused by name",
          "[io][mat]") {
  TempDir dir;
  const std::string p = dir / "odd.mat";
  const auto message = [&](const std::string& kind, MatVersion v) {
    WriteMatOddVariable(p, v, "u", kind);
    return InputErrorMessage([&] { ReadRecording(p, Map({{"u", "u"}, {"x", "u"}}, 10)); });
  };
  for (const auto v : {MatVersion::kV5, MatVersion::kV5Compressed}) {
    CHECK_THAT(message("complex", v), Catch::Contains("odd.mat:u: is complex (double 1x3)"));
    CHECK_THAT(message("sparse", v), Catch::Contains("odd.mat:u: is a sparse matrix"));
    CHECK_THAT(message("cell", v), Catch::Contains("odd.mat:u: is a cell array (1x1)"));
    CHECK_THAT(message("char", v), Catch::Contains("odd.mat:u: is a char (1x3)"));
    CHECK_THAT(message("struct", v), Catch::Contains("odd.mat:u: is a struct (1x1)"));
    CHECK_THAT(message("empty", v), Catch::Contains("odd.mat:u: is empty (double 0x0)"));
  }
  // Without a mapping, a file of only a struct has nothing to read.
  WriteMatOddVariable(p, MatVersion::kV5, "s", "struct");
  CHECK_THAT(InputErrorMessage([&] { ReadRecording(p); }),
             Catch::Contains("no top-level numeric vectors") && Catch::Contains("s (struct 1x1)"));
}

TEST_CASE("a dSPACE ControlDesk export is read by naming its signals", "[io][mat][controldesk]") {
  TempDir dir;
  std::vector<double> t(30);
  for (size_t i = 0; i < t.size(); ++i) t[i] = 0.01 * static_cast<double>(i);
  const auto volts = Ramp(30, 3), pos = Ramp(30, 2e-3);
  // Uncompressed v5 and v7.3. matio 1.5.23 does not read back the compressed nested struct
  // arrays it writes in this layout ("fields[1], Uncompressed type not MAT_T_MATRIX": it sizes
  // Y.Name's element for 2-byte characters and writes UTF-8, so Y.Type starts inside it): that
  // file is refused as malformed (checked below), never misread. The layout check
  // (mat_layout.cpp) finds it before matio does.
  for (const auto version : {MatVersion::kV5, MatVersion::kV73}) {
    const std::string p = dir / "capture.mat";
    WriteControlDesk(p, version, "capture_001", t, {"Model Root/u_out", "Model Root/encoder"},
                     {volts, pos});
    const Recording r =
        ReadRecording(p, Map({{"u", "Model Root/u_out"}, {"x", "Model Root/encoder"}}));
    CHECK(r.names == std::vector<std::string>{"t", "u", "x"});
    CheckColumn(r, "t", t);
    CheckColumn(r, "u", volts);
    CheckColumn(r, "x", pos);
    CHECK_THAT(InputErrorMessage([&] { ReadRecording(p); }),
               Catch::Contains("a dSPACE ControlDesk struct 'capture_001': name its signals with "
                               "--var u=NAME,x=NAME (signals: Model Root/u_out, "
                               "Model Root/encoder)"));
    CHECK_THAT(InputErrorMessage([&] {
                 ReadRecording(p, Map({{"u", "speed"}, {"x", "Model Root/encoder"}}));
               }),
               Catch::Contains("no variable 'speed' (variables: capture_001, Model Root/u_out, "
                               "Model Root/encoder)"));
  }
  WriteControlDesk(dir / "z.mat", MatVersion::kV5Compressed, "capture_001", t, {"Model Root/u_out"},
                   {volts});
  CHECK_THAT(InputErrorMessage([&] {
               ReadRecording(dir / "z.mat", Map({{"u", "Model Root/u_out"}}));
             }),
             Catch::StartsWith(dir / "z.mat:capture_001.Y.Type: malformed or truncated MAT file: "
                                     "an element of MAT data type 4, expected a matrix"));
}

TEST_CASE("HDF5: datasets in groups by path, NaN at its 1-based index, missing ones listed",
          "[io][hdf5]") {
  TempDir dir;
  const std::string p = dir / "train.h5";
  auto u = Ramp(2000, 50), y = Ramp(2000, 1e-3);
  WriteH5(p, {{"/multisine/u", {2000, 1}, u},
              {"/multisine/y", {2000, 1}, y},
              {"/multisine/fs", {1}, {750}}});
  CHECK(DetectFileFormat(p) == FileFormat::kHdf5);
  const Recording r = ReadRecording(p, Map({{"u", "/multisine/u"}, {"x", "/multisine/y"}}, 750));
  CheckColumn(r, "u", u);
  CheckColumn(r, "x", y);
  CHECK_THAT(InputErrorMessage([&] {
               ReadRecording(p, Map({{"u", "/multisine/v"}, {"x", "/multisine/y"}}, 750));
             }),
             Catch::Contains("train.h5: no dataset '/multisine/v' (datasets: /multisine/fs, "
                             "/multisine/u, /multisine/y)"));
  u[1522] = std::numeric_limits<double>::quiet_NaN();
  WriteH5(p, {{"/multisine/u", {2000, 1}, u}, {"/multisine/y", {2000, 1}, y}});
  CHECK_THAT(InputErrorMessage([&] {
               ReadRecording(p, Map({{"u", "/multisine/u"}, {"x", "/multisine/y"}}, 750));
             }),
             Catch::EndsWith("train.h5:/multisine/u[1523]: expected a finite number, found NaN"));
  // Lengths that differ.
  WriteH5(p, {{"/u", {20}, Ramp(20, 1)}, {"/x", {19}, Ramp(19, 1)}});
  CHECK_THAT(InputErrorMessage([&] {
               ReadRecording(p, Map({{"u", "/u"}, {"x", "/x"}}, 10));
             }),
             Catch::Contains("train.h5:/x: 19 samples, but ") &&
                 Catch::Contains("train.h5:/u has 20 (lengths differ)"));
  // Root datasets named like columns are read without a mapping.
  WriteH5(p, {{"/t", {3}, {0, 0.5, 1}}, {"/u", {3}, {1, 2, 3}}, {"/x", {3}, {4, 5, 6}}});
  CHECK(ReadRecording(p).names == std::vector<std::string>{"t", "u", "x"});
  // Empty, integer and compound datasets.
  WriteH5(p, {{"/u", {0}, {}}});
  CHECK_THAT(InputErrorMessage([&] { ReadSignal(p, "/u"); }),
             Catch::Contains("train.h5:/u: is empty"));
  WriteH5Odd(p);
  CHECK(ReadSignal(p, "counts") == Eigen::Vector3d(4, -5, 6));
  CHECK_THAT(InputErrorMessage([&] { ReadSignal(p, "/z"); }),
             Catch::Contains("train.h5:/z: is a compound"));
}

TEST_CASE("MAT v4: a header declaring a name or data past the file's end is refused first",
          "[io][mat][robustness]") {
  // matio allocates what a v4 header declares before reading it: a 54-byte file declaring a
  // 0x7fffffff-byte name made it allocate 2.1 GB, then fail on the short read.
  TempDir dir;
  const std::string p = dir / "v4.mat";
  const std::vector<double> t{0, 0.001, 0.002, 0.003};
  // The reference: a well-formed header reads back bit for bit.
  WriteRawMat4(p, "t", 1, 4, t);
  CHECK(ReadSignal(p, "t") == Eigen::Map<const Eigen::VectorXd>(t.data(), 4));
  WriteRawMat4(p, "t", 1, 4, t, 0x7fffffff);  // 20 + 2 + 32 = 54 bytes
  CHECK(InputErrorMessage([&] { ListVariables(p); }) ==
        p + ": malformed or truncated MAT file: at byte 0: a MAT v4 variable with a "
            "2147483647-byte name, the file has 34 bytes left");
  WriteRawMat4(p, "t", 1, 2000000000, t);
  CHECK(InputErrorMessage([&] { ListVariables(p); }) ==
        p + ":t: malformed or truncated MAT file: declares 1x2000000000 (2000000000 elements, "
            "16000000000 bytes), the file has 32 bytes left");
  WriteRawMat4(p, "t", 1, 8, t);  // 4 of 8 values
  CHECK(InputErrorMessage([&] { ReadSignal(p, "t"); }) ==
        p + ":t: malformed or truncated MAT file: declares 1x8 (8 elements, 64 bytes), the file "
            "has 32 bytes left");
  WriteRawMat4(p, "t", -5, 4, t);
  CHECK_THAT(InputErrorMessage([&] { ListVariables(p); }),
             Catch::EndsWith("a MAT v4 header declaring -5 rows, 4 columns, a 2-byte name"));
}

TEST_CASE("HDF5: a dataspace declaring more than the dataset's storage holds is refused",
          "[io][hdf5][robustness]") {
  // HDF5 1.10 reads a contiguous dataset at the offsets its dataspace gives: /rec/u patched from
  // 16x1 to 16x17 over storage for 16 doubles read u[:,2] from the bytes after it, exit 0.
  TempDir dir;
  const std::string p = dir / "h_dimB_17.h5";
  const auto u = Ramp(16, 1), x = Ramp(16, 1e-3), t = Ramp(16, 0.1, 1);
  const std::vector<H5Array> arrays{{"/t", {16}, t}, {"/rec/u", {16, 1}, u}, {"/rec/x", {16}, x}};
  // The reference: unpatched (16 -> 1), the values come back bit for bit.
  WriteH5PatchedDims(p, arrays, 16, 1, 1);
  CHECK(ReadSignal(p, "/rec/u") == Eigen::Map<const Eigen::VectorXd>(u.data(), 16));
  WriteH5PatchedDims(p, arrays, 16, 1, 17);
  const std::string detail =
      ": malformed HDF5 dataset: its dataspace declares 272 elements (2176 bytes), its "
      "contiguous storage holds 128 bytes";
  CHECK(InputErrorMessage([&] {
          ReadRecording(p, Map({{"u", "/rec/u[:,2]"}, {"x", "/rec/x"}}, 10));
        }) == p + ":/rec/u[:,2]" + detail);
  CHECK(InputErrorMessage([&] { ReadSignal(p, "/rec/u[:,1]"); }) == p + ":/rec/u[:,1]" + detail);
  CHECK(InputErrorMessage([&] { ListVariables(p); }) == p + ":/rec/u" + detail);  // sysid info
  // A dataset created and never written has no storage: HDF5 defines its values as the fill
  // value (0), a legal file.
  WriteH5(dir / "unwritten.h5", {{"/u", {3}, {}}});
  CHECK(ReadSignal(dir / "unwritten.h5", "/u") == Eigen::Vector3d::Zero());
}

TEST_CASE("MAT: a non-finite value is named with its variable and 1-based index", "[io][mat]") {
  TempDir dir;
  auto u = Ramp(100, 1);
  u[41] = std::numeric_limits<double>::infinity();
  WriteMat(dir / "bad.mat", MatVersion::kV5Compressed,
           {{"u", 1, 100, u}, {"x", 1, 100, Ramp(100, 1)}});
  CHECK_THAT(InputErrorMessage([&] { ReadRecording(dir / "bad.mat", Map({}, 100)); }),
             Catch::EndsWith("bad.mat:u[42]: expected a finite number, found Inf"));
}

TEST_CASE("truncated files, wrong magic and huge declared sizes are refused", "[io][robustness]") {
  TempDir dir;
  const auto u = Ramp(4000, 1), x = Ramp(4000, 2);
  const auto truncate = [](const std::string& from, const std::string& to, double fraction) {
    std::ifstream in(from, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::ofstream(to, std::ios::binary)
        << bytes.substr(0, static_cast<size_t>(bytes.size() * fraction));
  };
  for (const auto version : {MatVersion::kV5, MatVersion::kV5Compressed, MatVersion::kV73}) {
    WriteMat(dir / "whole.mat", version, {{"u", 1, 4000, u}, {"x", 1, 4000, x}});
    truncate(dir / "whole.mat", dir / "cut.mat", 0.6);
    const std::string m = InputErrorMessage([&] { ReadRecording(dir / "cut.mat", Map({}, 10)); });
    INFO(m);
    CHECK_THAT(m, Catch::StartsWith(dir / "cut.mat"));
  }
  WriteH5(dir / "whole.h5", {{"/u", {4000}, u}, {"/x", {4000}, x}});
  truncate(dir / "whole.h5", dir / "cut.h5", 0.5);
  CHECK_THAT(InputErrorMessage([&] {
               ReadRecording(dir / "cut.h5", Map({{"u", "/u"}, {"x", "/x"}}, 10));
             }),
             Catch::StartsWith(dir / "cut.h5"));
  // A MAT v5 header followed by garbage.
  {
    std::string bytes(128, ' ');
    bytes[126] = 'I';
    bytes[127] = 'M';
    bytes[124] = 0;
    bytes[125] = 1;
    bytes += std::string(64, '\x7f');
    std::ofstream(dir / "garbage.mat", std::ios::binary) << bytes;
    const std::string m =
        InputErrorMessage([&] { ReadRecording(dir / "garbage.mat", Map({}, 10)); });
    CHECK_THAT(m, Catch::StartsWith(dir / "garbage.mat"));
  }
  // Not a MAT file at all, named .mat: read as text, and refused as text.
  WriteText(dir / "text.mat", "hello world\n");
  CHECK(DetectFileFormat(dir / "text.mat") == FileFormat::kText);
  CHECK_THAT(InputErrorMessage([&] { ListVariables(dir / "text.mat"); }),
             Catch::Contains("text.mat: not a MAT or HDF5 file"));
  // Declared sizes beyond kMaxVariableElements, refused before allocation.
  WriteMatHugeDeclaration(dir / "huge.mat", 2000000000u);
  CHECK_THAT(InputErrorMessage([&] {
               ReadRecording(dir / "huge.mat", Map({{"u", "u"}, {"x", "u"}}, 10));
             }),
             Catch::Contains("huge.mat:u: declares 1x2000000000") &&
                 Catch::Contains("more than the 20000000"));
  WriteH5Huge(dir / "huge.h5", "/u", 4000000000ull);
  CHECK_THAT(InputErrorMessage([&] {
               ReadRecording(dir / "huge.h5", Map({{"u", "/u"}, {"x", "/u"}}, 10));
             }),
             Catch::Contains("huge.h5:/u: declares double 4000000000x1") &&
                 Catch::Contains("more than the 20000000"));
}

TEST_CASE("MAT v5: data holding another number of values than the dims declare are refused",
          "[io][mat][robustness]") {
  // libmatio 1.5.23 sizes a variable's buffer from its dims and reads what the data element
  // holds without comparing the two: x declaring 1x8 and storing 3 values came back with 5
  // values of uninitialised memory (valgrind), or the next variable's bytes, and exit 0.
  TempDir dir;
  std::vector<double> t(8), u(8, 1.0), x(8);
  for (size_t i = 0; i < t.size(); ++i) {
    t[i] = 0.001 * static_cast<double>(i);
    x[i] = 1e-6 * static_cast<double>(i);
  }
  const std::vector<double> x3(x.begin(), x.begin() + 3);
  for (const bool compressed : {false, true}) {
    INFO("compressed: " << compressed);
    const std::string p = dir / "short_x.mat";
    // The reference: the same bytes with every value stored read back bit for bit.
    WriteRawMat(p, {{"t", 8, t}, {"u", 8, u}, {"x", 8, x}}, compressed);
    const Recording r = ReadRecording(p);
    CheckColumn(r, "t", t);
    CheckColumn(r, "u", u);
    CheckColumn(r, "x", x);
    // x stores 3 of its 8 values: refused by name, whichever variable is asked for (the file is
    // corrupt), and by `sysid info` (ListVariables) too.
    WriteRawMat(p, {{"t", 8, t}, {"u", 8, u}, {"x", 8, x3}}, compressed);
    const std::string want =
        p + ":x: malformed or truncated MAT file: declares 1x8 (8 elements), holds 3";
    CHECK(InputErrorMessage([&] { ReadRecording(p); }) == want);
    CHECK(InputErrorMessage([&] { ListVariables(p); }) == want);
    CHECK(InputErrorMessage([&] { ReadSignal(p, "t"); }) == want);
    // First in the file: matio would have taken the next variable's bytes as x's values.
    WriteRawMat(p, {{"x", 8, x3}, {"t", 8, t}, {"u", 8, u}}, compressed);
    CHECK(InputErrorMessage([&] { ReadRecording(p); }) == want);
    WriteRawMat(p, {{"u", 5000, x3}}, compressed);
    CHECK(InputErrorMessage([&] { ListVariables(p); }) ==
          p + ":u: malformed or truncated MAT file: declares 1x5000 (5000 elements), holds 3");
    // More values than declared is as corrupt.
    WriteRawMat(p, {{"u", 2, x3}}, compressed);
    CHECK(InputErrorMessage([&] { ListVariables(p); }) ==
          p + ":u: malformed or truncated MAT file: declares 1x2 (2 elements), holds 3");
  }
}

TEST_CASE("a MAT file whose variables matio cannot all list is refused, a file of none is not",
          "[io][mat][robustness]") {
  TempDir dir;
  const auto slurp = [](const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  };
  // A valid v5 header, then 200 bytes of 0xFF: matio stopped there silently and the file was a
  // MAT file of 0 variables, exit 0.
  WriteRawMat(dir / "garbage.mat", {}, false);
  std::ofstream(dir / "garbage.mat", std::ios::binary | std::ios::app) << std::string(200, '\xff');
  CHECK(InputErrorMessage([&] { ListVariables(dir / "garbage.mat"); }) ==
        dir / "garbage.mat: malformed or truncated MAT file: at byte 128: an element of MAT data "
              "type 4294967295 where a variable belongs (garbage, or a damaged file)");
  // A few bytes after the last variable: a cut tag.
  WriteRawMat(dir / "tail.mat", {{"u", 2, {1, 2}}}, true);
  std::ofstream(dir / "tail.mat", std::ios::binary | std::ios::app) << std::string(3, '\0');
  CHECK_THAT(InputErrorMessage([&] { ListVariables(dir / "tail.mat"); }),
             Catch::EndsWith("3 stray bytes where a variable's tag belongs"));
  // MAT v7.3 cut anywhere (the HDF5 part begins at byte 512): matio opened it and listed no
  // variables, exit 0. HDF5 refuses it (its superblock records the file's end).
  const std::vector<double> v = Ramp(16, 1);
  WriteMat(dir / "whole73.mat", MatVersion::kV73, {{"t", 16, 1, v}, {"u", 1, 16, v}});
  const std::string bytes = slurp(dir / "whole73.mat");
  for (size_t n = 128; n < bytes.size(); n += 97) {
    INFO("cut to " << n << " of " << bytes.size() << " bytes");
    std::ofstream(dir / "cut73.mat", std::ios::binary | std::ios::trunc) << bytes.substr(0, n);
    CHECK(InputErrorMessage([&] { ListVariables(dir / "cut73.mat"); }) ==
          dir / "cut73.mat: malformed or truncated MAT file: a MAT v7.3 file that HDF5 cannot "
                "open (truncated, or no HDF5 data after the 512-byte MAT header)");
  }
  CHECK(ListVariables(dir / "whole73.mat").size() == 2);
  // Files that really hold no variables stay legal, v5 (the 128-byte header alone) and v7.3.
  WriteRawMat(dir / "none.mat", {}, false);
  CHECK(ListVariables(dir / "none.mat").empty());
  WriteMat(dir / "none73.mat", MatVersion::kV73, {});
  CHECK(ListVariables(dir / "none73.mat").empty());
  CHECK_THAT(InputErrorMessage([&] { ReadRecording(dir / "none73.mat"); }),
             Catch::EndsWith("none73.mat: holds no variables (an empty or truncated file)"));
}

TEST_CASE("the mapping renames CSV columns, scales them and adds t from a rate", "[io][csv]") {
  const std::string csv = "# unit: test\nvolts,um\n1,10\n2,20\n3,30\n";
  ReadOptions o = Map({{"u", "volts"}, {"x", "um"}}, 4);
  o.mapping.scales = {{"x", 1e-6}};
  const Recording r = ParseRecording(csv, "a.csv", o);
  CHECK(r.names == std::vector<std::string>{"t", "u", "x"});
  CHECK(r.column("t")[2] == 0.5);
  CHECK(r.column("x")[1] == 20 * 1e-6);
  CHECK(r.meta("unit") == "test");
  // The same flags on a CSV with a t column: --rate is refused, the other columns are kept.
  const std::string with_t = "t,volts,x\n0,1,2\n1,2,3\n";
  CHECK_THAT(InputErrorMessage([&] {
               ParseRecording(with_t, "b.csv", Map({{"u", "volts"}}, 4));
             }),
             Catch::Contains("b.csv: has a time column 't'") &&
                 Catch::Contains("--rate applies only to recordings without one"));
  const Recording kept = ParseRecording(with_t, "b.csv", Map({{"u", "volts"}}));
  CHECK(kept.names == std::vector<std::string>{"t", "u", "x"});
  CHECK_THAT(InputErrorMessage([&] {
               ParseRecording(with_t, "b.csv", Map({{"u", "volt"}}));
             }),
             Catch::Contains("b.csv: --var u=volt: no column 'volt' (columns: t, volts, x)"));
  // Time that does not increase, named by where it came from.
  CHECK_THAT(InputErrorMessage([&] {
               ParseRecording("s,u,x\n0,1,1\n0,1,1\n", "c.csv", Map({{"t", "s"}}));
             }),
             Catch::Contains("c.csv: column 's'[2]: time must be strictly increasing, found 0 "
                             "after 0"));
}

TEST_CASE("WriteRecordingMat writes a MAT v5 file that reads back bit for bit", "[io][mat]") {
  TempDir dir;
  Recording r;
  r.source = "mem";
  Eigen::VectorXd t(5), u(5);
  t << 0, 0.1, 0.2, 0.30000000000000004, 0.4;
  u << 1.0 / 3, -2e-300, 5e300, 0, -0.0;
  r.SetColumn("t", t);
  r.SetColumn("u", u);
  r.SetColumn("x", u * 7);
  WriteRecordingByExtension(dir / "out.mat", r);
  CHECK(DescribeFileFormat(dir / "out.mat") == "MAT v5");
  const Recording back = ReadRecording(dir / "out.mat");
  CHECK(back.names == r.names);
  CHECK(back.data == r.data);
  r.names[2] = "x.y";
  CHECK_THAT(InputErrorMessage([&] { WriteRecordingMat(dir / "bad.mat", r); }),
             Catch::Contains("column 'x.y' is not a MATLAB variable name"));
  CHECK_FALSE(std::filesystem::exists(dir / "bad.mat"));
}

TEST_CASE("ListVariables describes every variable with its class, dims and range", "[io][info]") {
  TempDir dir;
  WriteMat(dir / "l.mat", MatVersion::kV5Compressed,
           {{"u", 1, 4, {1, -2, 3, 0.5}}, {"m", 2, 2, {1, 2, 3, 4}}});
  const auto vars = ListVariables(dir / "l.mat");
  REQUIRE(vars.size() == 2);
  CHECK(vars[0].name == "u");
  CHECK(vars[0].type == "double");
  CHECK(vars[0].dims == std::vector<std::uint64_t>{1, 4});
  CHECK(vars[0].numeric_vector);
  CHECK(vars[0].length == 4);
  CHECK(vars[0].min == -2);
  CHECK(vars[0].max == 3);
  CHECK_FALSE(vars[1].numeric_vector);
  CHECK(vars[1].dims == std::vector<std::uint64_t>{2, 2});
}

}  // namespace
}  // namespace sysid::test
