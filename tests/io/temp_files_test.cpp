// A temporary file registered by an atomic write is removed when the process is interrupted
// (issue #14: Ctrl-C used to leave .out.csv.tmp.XXXXXX behind).
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <csignal>
#include <filesystem>
#include <fstream>

#include "io/temp_files.hpp"
#include "support/test_support.hpp"

TEST_CASE("SIGINT and SIGTERM remove registered temporary files", "[io][signals]") {
  sysid::test::TempDir dir;
  for (int sig : {SIGINT, SIGTERM}) {
    const std::string tmp = (dir.path() / (".out.csv.tmp." + std::to_string(sig))).string();
    const std::string kept = (dir.path() / ("unregistered." + std::to_string(sig))).string();
    const pid_t pid = fork();
    REQUIRE(pid >= 0);
    if (pid == 0) {
      // Catch2 has its own handlers; a program with the default disposition gets ours.
      std::signal(SIGINT, SIG_DFL);
      std::signal(SIGTERM, SIG_DFL);
      std::ofstream(tmp) << "half";
      std::ofstream(kept) << "user";
      const sysid::internal::TempFileGuard guard(tmp);
      std::raise(sig);
      _exit(0);  // not reached: the default action ends the process
    }
    int status = 0;
    REQUIRE(waitpid(pid, &status, 0) == pid);
    CHECK(WIFSIGNALED(status));
    CHECK(WTERMSIG(status) == sig);
    CHECK_FALSE(std::filesystem::exists(tmp));
    CHECK(std::filesystem::exists(kept));  // only registered files are removed
  }
}

TEST_CASE("SIGHUP removes a registered staging folder with its content, not what links name",
          "[io][signals]") {
  // Issue #29: an interrupted `excite tracking -o T` left its staging folder.
  sysid::test::TempDir dir;
  const std::filesystem::path staging = dir.path() / ".T.tmp.1.abcdef";
  const std::filesystem::path outside = dir.path() / "user.csv";
  std::ofstream(outside) << "user data";
  const pid_t pid = fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    std::signal(SIGHUP, SIG_DFL);
    std::filesystem::create_directories(staging / "plots" / "deeper");
    std::ofstream(staging / "a.csv") << "half";
    std::ofstream(staging / "plots" / "deeper" / "b.svg") << "<svg/>";
    std::filesystem::create_symlink(outside, staging / "link.csv");
    std::filesystem::create_directory_symlink(dir.path(), staging / "dirlink");
    const sysid::internal::TempFileGuard guard(staging.string(),
                                               sysid::internal::TempKind::kFolder);
    std::raise(SIGHUP);
    _exit(0);
  }
  int status = 0;
  REQUIRE(waitpid(pid, &status, 0) == pid);
  CHECK(WIFSIGNALED(status));
  CHECK_FALSE(std::filesystem::exists(staging));
  // Links inside were removed, never followed.
  CHECK(std::filesystem::exists(outside));
  CHECK(std::filesystem::exists(dir.path()));
}
