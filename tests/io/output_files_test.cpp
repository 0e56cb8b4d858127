// Writers never replace what is not a regular file, readers never load an endless or huge
// input, and the rows of a recording know their file lines (issue #29).
#include <sys/stat.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>

#include "support/test_support.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"
#include "sysid/io_output.hpp"

namespace fs = std::filesystem;

TEST_CASE("WriteFileAtomically writes through devices, follows links, replaces no node",
          "[io][output]") {
  sysid::test::TempDir dir;
  sysid::WriteFileAtomically("/dev/null", "discarded\n");  // written through, not replaced
  struct stat st {};
  REQUIRE(::stat("/dev/null", &st) == 0);
  CHECK(S_ISCHR(st.st_mode));
  CHECK_THROWS_WITH(sysid::WriteFileAtomically("/dev/full", "x\n"),
                    Catch::Contains("/dev/full: cannot write: No space left on device"));
  // A link to a file: the file is replaced, the link stays.
  sysid::WriteFileAtomically(dir / "target.csv", "old\n");
  fs::create_symlink(dir / "target.csv", dir / "link.csv");
  sysid::WriteFileAtomically(dir / "link.csv", "new\n");
  CHECK(fs::is_symlink(dir / "link.csv"));
  CHECK(sysid::ReadFile(dir / "target.csv") == "new\n");
  // A dangling link, a loop, a folder: refused, untouched.
  fs::create_symlink(dir / "missing.csv", dir / "dangling.csv");
  CHECK_THROWS_AS(sysid::WriteFileAtomically(dir / "dangling.csv", "x"), sysid::OptionsError);
  CHECK_FALSE(fs::exists(dir / "missing.csv"));
  fs::create_symlink(dir / "loop.csv", dir / "loop.csv");
  CHECK_THROWS_WITH(sysid::WriteFileAtomically(dir / "loop.csv", "x"), Catch::Contains("loop"));
  fs::create_directory(dir / "sub");
  CHECK_THROWS_WITH(sysid::WriteFileAtomically(dir / "sub", "x"),
                    Catch::Contains("exists and is a folder"));
}

TEST_CASE("ReadFile refuses devices and files past kMaxInputFileBytes before reading",
          "[io][output]") {
  CHECK_THROWS_WITH(sysid::ReadFile("/dev/zero"),
                    Catch::Contains("/dev/zero: cannot open: is a character device"));
  sysid::test::TempDir dir;
  const std::string big = dir / "big.csv";
  {
    std::ofstream(big) << "t\n";
  }
  // A sparse file one byte past the limit: refused from its size, nothing allocated.
  if (::truncate(big.c_str(), static_cast<off_t>(sysid::kMaxInputFileBytes + 1)) == 0) {
    CHECK_THROWS_WITH(sysid::ReadFile(big), Catch::Contains("past the 4 GiB"));
  }
}

TEST_CASE("recording rows know their file lines, comments between rows included", "[io]") {
  const sysid::Recording r = sysid::ParseRecording(
      "# a: 1\n# b: 2\nt,u,x\n0,0,0\n0.001,0,0\n# note\n0.002,0,0\n\n", "r.csv", {});
  CHECK(r.line_of(0) == 4);
  CHECK(r.line_of(1) == 5);
  CHECK(r.line_of(2) == 7);
  CHECK(r.where(2) == "r.csv:7");
  sysid::Recording copy = r;
  copy.data.conservativeResize(2, 3);  // rows changed: lines no longer claimed
  CHECK(copy.line_of(1) == 0);
  CHECK(copy.where(1) == "r.csv: row 2");
}

TEST_CASE("Resample bounds rate x duration before allocating", "[io]") {
  const sysid::Recording r =
      sysid::ParseRecording("t,u,x\n0,0,0\n0.001,0,0\n1000000,0,0\n", "gap.csv", {});
  CHECK_THROWS_WITH(sysid::Resample(r, 1000),
                    Catch::Contains("(1e+09 samples over the 1e+06 s of gap.csv)") &&
                        Catch::Contains("kMaxSignalSamples"));
  CHECK(sysid::Resample(r, 1e-3).rows() == 1001);  // 1e6 s at 1 mHz: fine
}
