// Helpers shared by the test suites: running the sysid program, temporary folders, paths.
#ifndef SYSID_TESTS_SUPPORT_TEST_SUPPORT_HPP_
#define SYSID_TESTS_SUPPORT_TEST_SUPPORT_HPP_

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace sysid::test {

struct CliResult {
  int exit_code = -1;
  std::string out;  ///< stdout
  std::string err;  ///< stderr
};

/// Runs the sysid program with `args` (no shell: arguments are passed as they are).
CliResult RunCli(const std::vector<std::string>& args);
/// The sysid program's path (for tests that run it under their own limits).
std::string SysidExe();

/// A fresh, empty folder under the system temp dir, removed when the object dies.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }
  std::string operator/(const std::string& name) const { return (path_ / name).string(); }
 private:
  std::filesystem::path path_;
};

/// Writes `content` to `path` (test fixtures; not atomic).
void WriteText(const std::string& path, const std::string& content);
std::string ReadText(const std::string& path);

/// The message of the InputError that `f` throws; fails the test when it throws none.
std::string InputErrorMessage(const std::function<void()>& f);

/// Path of a file in the source tree, e.g. SourcePath("datasets/paper/pulse_table.csv").
std::string SourcePath(const std::string& relative);
/// Path of a file in tests/data.
std::string TestData(const std::string& relative);

}  // namespace sysid::test

#endif  // SYSID_TESTS_SUPPORT_TEST_SUPPORT_HPP_
