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
