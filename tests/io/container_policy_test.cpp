// Hostile MAT and HDF5 files (the container policy, libsysid/src/io/container_policy.hpp): each
// case is the file the bad-input probe made, written here with the HDF5 C API, matio and zlib,
// and the command it broke, run as a child process under a stated bound: kSeconds of wall time
// and kAddressSpace of address space (setrlimit, as `ulimit -v` in tests/robustness). Each must
// end with exit 2 or 0 and no signal; a read of another file shows as a hang on a FIFO.
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <cmath>
#include <fstream>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include "container_fixtures.hpp"
#include "support/test_support.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"
#include "sysid/io_containers.hpp"

#if defined(__SANITIZE_ADDRESS__)
#define SYSID_TEST_SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define SYSID_TEST_SANITIZED 1
#endif
#endif

namespace sysid::test {
namespace {

#ifdef SYSID_TEST_SANITIZED
// A sanitizer reserves terabytes of address space and runs several times slower.
constexpr double kSeconds = 20;
constexpr bool kLimitAddressSpace = false;
#else
constexpr double kSeconds = 5;
constexpr bool kLimitAddressSpace = true;
#endif
constexpr rlim_t kAddressSpace = rlim_t{1} << 30;  // 1 GiB, as tests/robustness/bounded_memory.sh

struct Bounded {
  int exit_code = -1;  ///< -1 when killed by a signal
  int signal = 0;
  double seconds = 0;
  std::string out, err;
};

// sysid ARGS as a child under kSeconds (then SIGKILL) and kAddressSpace.
Bounded RunBounded(const std::vector<std::string>& args) {
  TempDir dir;
  const std::string out_path = dir / "stdout", err_path = dir / "stderr";
  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("fork failed");
  if (pid == 0) {
    if (!std::freopen(out_path.c_str(), "w", stdout) ||
        !std::freopen(err_path.c_str(), "w", stderr))
      _exit(126);
    if (kLimitAddressSpace) {
      const rlimit limit{kAddressSpace, kAddressSpace};
      setrlimit(RLIMIT_AS, &limit);
    }
    std::vector<std::string> copy = args;
    std::string exe = SysidExe();
    std::vector<char*> argv{exe.data()};
    for (auto& a : copy) argv.push_back(a.data());
    argv.push_back(nullptr);
    execv(exe.c_str(), argv.data());
    _exit(127);
  }
  Bounded r;
  int status = 0;
  while (waitpid(pid, &status, WNOHANG) == 0) {
    const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
    if (elapsed.count() > kSeconds) {
      kill(pid, SIGKILL);
      waitpid(pid, &status, 0);
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (WIFEXITED(status)) r.exit_code = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) r.signal = WTERMSIG(status);
  r.out = ReadText(out_path);
  r.err = ReadText(err_path);
  return r;
}

std::string Describe(const std::vector<std::string>& args, const Bounded& r) {
  std::string cmd = "sysid";
  for (const auto& a : args) cmd += " " + a;
  return cmd + "\nexit " + std::to_string(r.exit_code) + ", signal " + std::to_string(r.signal) +
         ", " + std::to_string(r.seconds) + " s\nstderr: " + r.err;
}

// Runs sysid ARGS under the bound: no signal (a crash, or the kill at kSeconds), no exit 4,
// the expected exit code and message.
void Expect(int code, const std::string& message, const std::vector<std::string>& args) {
  const Bounded r = RunBounded(args);
  INFO(Describe(args, r));
  CHECK(r.signal == 0);
  CHECK(r.exit_code == code);
  CHECK(r.err.find("internal error") == std::string::npos);
  if (!message.empty()) CHECK(r.err.find(message) != std::string::npos);
}

TEST_CASE("HDF5: a virtual dataset is refused before a value is read, also through ListVariables",
          "[io][policy]") {
  TempDir dir;
  // The probe's file: u mapped from s.h5:u, itself (HDF5 1.10 crashed reading it).
  const std::string s = dir / "s.h5";
  WriteH5Virtual(s, s, "u");
  const std::string why = "s.h5:/u: refused: a virtual dataset";
  Expect(2, why, {"info", s});
  Expect(2, why, {"info", s, "--var", "u=u", "--rate", "1"});
  Expect(2, why, {"import", "--column", "u=" + s + ":t", "--rate", "1", "-o", dir / "o.csv"});
  CHECK(!std::filesystem::exists(dir / "o.csv"));
  // In the process itself (Python's sysid.list_variables): an exception, not a crash.
  CHECK(InputErrorMessage([&] { ListVariables(s); }).find(why) != std::string::npos);
  // Mapped from a FIFO: a read would block for ever.
  const std::string fifo = dir / "fifo";
  REQUIRE(mkfifo(fifo.c_str(), 0600) == 0);
  WriteH5Virtual(dir / "f.h5", fifo, "u");
  Expect(2, "refused: a virtual dataset", {"info", dir / "f.h5"});
  // Extendible, its sources fifo0, fifo1, ...: HDF5 opens them to learn its size.
  REQUIRE(mkfifo((dir / "fifo0").c_str(), 0600) == 0);
  WriteH5Virtual(dir / "x.h5", dir / "fifo%b", "u", true);
  Expect(2, "x.h5:/u: refused: a virtual dataset", {"info", dir / "x.h5"});
}

TEST_CASE("HDF5: external storage is refused naming the other file, and a FIFO there never blocks",
          "[io][policy]") {
  TempDir dir;
  const std::string e = dir / "e.h5";
  WriteH5External(e, "/etc/passwd");
  const std::string why = "e.h5:/u: refused: a dataset with external storage";
  Expect(2, why, {"import", "--column", "u=" + e + ":u", "--rate", "1", "-o", dir / "o.csv"});
  Expect(2, "'/etc/passwd'", {"info", e});
  CHECK(!std::filesystem::exists(dir / "o.csv"));
  const std::string fifo = dir / "fifo";
  REQUIRE(mkfifo(fifo.c_str(), 0600) == 0);
  WriteH5External(dir / "f.h5", fifo);
  Expect(2, why.substr(4), {"info", dir / "f.h5"});
  Expect(2, why.substr(4), {"info", dir / "f.h5", "--var", "u=t", "--rate", "1"});
}

TEST_CASE("MAT v7.3: a self-referencing cell, external storage and a virtual dataset are refused",
          "[io][policy]") {
  TempDir dir;
  const std::string r = dir / "r.mat";
  WriteMat73Hostile(r, Mat73Hostile::kSelfReference);
  // matio recursed until its stack ended (SIGSEGV) even for t, a variable not asked for.
  const std::string cycle = "r.mat:c{1}: refused: leads back to an object it is inside of";
  Expect(2, cycle, {"info", r});
  Expect(2, cycle, {"import", "--column", "u=" + r + ":t", "--rate", "1", "-o", dir / "o.csv"});
  WriteMat73Hostile(dir / "e.mat", Mat73Hostile::kExternal, "/etc/passwd");
  Expect(2, "e.mat:u: refused: a dataset with external storage",
         {"import", "--column", "u=" + (dir / "e.mat") + ":u", "--rate", "1", "-o", dir / "o.csv"});
  WriteMat73Hostile(dir / "v.mat", Mat73Hostile::kVirtual, r);
  Expect(2, "v.mat:u: refused: a virtual dataset", {"info", dir / "v.mat"});
  CHECK(!std::filesystem::exists(dir / "o.csv"));
  // The same file without the hostile part reads.
  WriteMatNestedStructs(dir / "ok.mat", MatVersion::kV73, 3);
  Expect(0, "", {"info", dir / "ok.mat"});
}

TEST_CASE("HDF5: 200 hard links to one chunked dataset are listed reading it once",
          "[io][policy]") {
  TempDir dir;
  const std::string h = dir / "links.h5";
  // 1e5 values in 1e4 deflated chunks: reading them took 0.06 s, once per link (12 s in all).
  WriteH5HardLinks(h, 100000, 200);
  const Bounded r = RunBounded({"info", h, "--json"});
  INFO(Describe({"info", h}, r));
  REQUIRE(r.exit_code == 0);
  CHECK(r.out.find("\"/l200\"") != std::string::npos);
  CHECK(r.out.find("\"max\": 0.5") != std::string::npos);
}

TEST_CASE("HDF5 and MAT: nesting past 32 levels is refused before it is walked", "[io][policy]") {
  TempDir dir;
  // 3000 nested groups took 104-120 s.
  WriteH5DeepGroups(dir / "deep.h5", 3000);
  Expect(2, "nested more than 32 levels deep", {"info", dir / "deep.h5"});
  Expect(2, "nested more than 32 levels deep",
         {"info", dir / "deep.h5", "--var", "u=t", "--rate", "1"});
  WriteH5DeepGroups(dir / "32.h5", 32);  // the bound itself is legal
  Expect(0, "", {"info", dir / "32.h5"});
  WriteH5DeepGroups(dir / "33.h5", 33);
  Expect(2, "33.h5:/g/g/g/g/g/g/g/g/g/g/g/g/g/g/g/g/g/g/g/g/g/g/g/g/g/g/g/g/g/g/g/g/g: nested more",
         {"info", dir / "33.h5"});
  WriteMatNestedStructs(dir / "s73.mat", MatVersion::kV73, 40);
  Expect(2, "s73.mat:s.a.a", {"info", dir / "s73.mat"});
  WriteMatNestedStructs(dir / "s5.mat", MatVersion::kV5Compressed, 40);
  Expect(2, "nested more than 32 levels deep", {"info", dir / "s5.mat"});
}

TEST_CASE("HDF5 and MAT v7.3: a null dataspace is an empty variable, listed without a range",
          "[io][policy]") {
  TempDir dir;
  const std::string n = dir / "n.h5";
  WriteH5Null(n);
  const auto vars = ListVariables(n);
  REQUIRE(vars.size() == 2);
  CHECK(vars[0].name == "/e");
  CHECK(vars[0].dims == std::vector<std::uint64_t>{0});
  CHECK(vars[0].length == 0);
  Expect(2, "n.h5:e: is empty (double 0)", {"info", n, "--var", "u=e", "--rate", "1"});
  // The same in a MAT v7.3 file: matio reads it as rank 0, one value it never fills.
  const std::string m = dir / "n.mat";
  WriteMat73Hostile(m, Mat73Hostile::kNull);
  int listed = 0;
  for (const auto& v : ListVariables(m))
    if (v.name == "e") {
      ++listed;
      CHECK(v.dims == std::vector<std::uint64_t>{0});
      CHECK(v.length == 0);
    }
  CHECK(listed == 1);
  Expect(2, "n.mat:e: is empty", {"info", m, "--var", "u=e", "--rate", "1"});
  const Bounded r = RunBounded({"info", n, "--json"});
  INFO(Describe({"info", n, "--json"}, r));
  CHECK(r.exit_code == 0);
  CHECK(r.out.find("\"length\": 0,\n      \"min\": null,\n      \"max\": null") !=
        std::string::npos);
}

TEST_CASE("MAT v5: 2e7 empty cells in 233 KB are refused at the object bound, unallocated",
          "[io][policy]") {
  TempDir dir;
  const std::string c = dir / "cells.mat";
  WriteMatEmptyCells(c, 20000000);
  CHECK(std::filesystem::file_size(c) < 240000);
  // 55-72 s and 2 GB in matio before.
  Expect(2, "cells.mat:c: more than 100000 objects to walk", {"info", c});
  WriteMatEmptyCells(dir / "few.mat", 1000);  // below the bound: a cell, listed
  Expect(0, "", {"info", dir / "few.mat"});
}

TEST_CASE("MAT v5: the layout check holds whatever a name's size", "[io][policy]") {
  TempDir dir;
  // u declares 1x100 and holds 3: with its name padded past the inflate budget (387 MB) it was
  // read with t's samples after its own, exit 0.
  const std::string big = dir / "pad.mat";
  WriteMatPaddedName(big, 403000000);
  Expect(2, "a name element of 403000000 bytes, more than the 4096",
         {"import", "--column", "u=" + big + ":u", "--rate", "1", "-o", dir / "o.csv"});
  CHECK(!std::filesystem::exists(dir / "o.csv"));
  const std::string padded = dir / "pad4k.mat";
  WriteMatPaddedName(padded, 4000);
  Expect(2, "pad4k.mat:u: malformed or truncated MAT file: declares 1x100 (100 elements), holds 3",
         {"info", padded});
}

TEST_CASE("MAT v5: past an inflate bound a file is refused, never left unchecked", "[io][policy]") {
  TempDir dir;
  // One variable inflating past 387 MB (2e7 complex values and 64 MiB), and three below it
  // each but past 1 GiB together.
  WriteMatZeros(dir / "z1.mat", 1, 49000000);
  Expect(2, "z1.mat:a: refused: a compressed variable inflating past 387108864 bytes",
         {"info", dir / "z1.mat"});
  WriteMatZeros(dir / "z3.mat", 3, 46000000);
  Expect(2, "z3.mat: refused: its compressed variables inflate past 1073741824 bytes in all",
         {"info", dir / "z3.mat"});
}

TEST_CASE("reading a file without a mapping touches only the datasets it takes", "[io][policy]") {
  TempDir dir;
  std::vector<double> t(16), u(16), bad(16);
  for (size_t i = 0; i < 16; ++i) {
    t[i] = 0.01 * static_cast<double>(i);
    u[i] = std::sin(static_cast<double>(i));
  }
  // /g/m's dataspace claims 16x17 over storage for 16x1: reading it reads past its storage.
  const std::string h = dir / "m.h5";
  WriteH5PatchedDims(h, {{"/t", {16}, t}, {"/u", {16}, u}, {"/x", {16}, u}, {"/g/m", {16, 1}, bad}},
                     16, 1, 17);
  const Recording rec = ReadRecording(h);
  CHECK(rec.names == std::vector<std::string>{"t", "u", "x"});
  CHECK(InputErrorMessage([&] { ListVariables(h); }).find("m.h5:/g/m: malformed HDF5 dataset") !=
        std::string::npos);
}

TEST_CASE("HDF5: more than 100000 links are refused at the object bound", "[io][policy]") {
  TempDir dir;
  const std::string h = dir / "many.h5";
  WriteH5HardLinks(h, 10, 100000);
  Expect(2, "more than 100000 objects to walk", {"info", h});
  WriteH5HardLinks(dir / "fewer.h5", 10, 1000);
  Expect(0, "", {"info", dir / "fewer.h5"});
}

}  // namespace
}  // namespace sysid::test
