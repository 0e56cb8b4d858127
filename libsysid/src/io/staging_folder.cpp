#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <random>
#include <string>

#include "io/temp_files.hpp"
#include "sysid/error.hpp"
#include "sysid/io_output.hpp"

namespace sysid {

struct StagingFolder::Guard {
  explicit Guard(const std::string& p) : guard(p, internal::TempKind::kFolder) {}
  internal::TempFileGuard guard;
};

StagingFolder::StagingFolder(const std::filesystem::path& target) {
  namespace fs = std::filesystem;
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  const std::string pid = std::to_string(::getpid());
  std::string prefix = "." + target.filename().string() + ".tmp." + pid + ".";
  // Past the 255 bytes a name may have (a legal 240-byte folder name): a fixed prefix.
  if (prefix.size() + 6 > 255) prefix = ".sysid.tmp." + pid + ".";
  // The name is registered before the folder exists, so that a signal to any thread finds it
  // (mkdtemp would leave a gap). Names carrying this process id are this run's, or a dead
  // process's leftovers: removing either on a signal harms no one.
  static constexpr char kChars[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789";
  std::random_device random;
  std::uniform_int_distribution<int> pick(0, sizeof kChars - 2);
  for (int attempt = 0; attempt < 100; ++attempt) {
    std::string suffix(6, ' ');
    for (char& c : suffix) c = kChars[pick(random)];
    const std::string path = (dir / (prefix + suffix)).string();
    auto guard = std::make_unique<Guard>(path);
    if (::mkdir(path.c_str(), 0777) == 0) {  // the umask applies, as to any output folder
      path_ = path;
      run_id_ = pid + "." + suffix;
      guard_ = std::move(guard);
      return;
    }
    if (errno != EEXIST)
      throw InputError(target.string() + ": cannot create a staging folder beside it: " +
                       std::strerror(errno));
  }
  throw InputError(target.string() + ": cannot create a staging folder beside it: 100 names "
                   "taken");
}

StagingFolder::~StagingFolder() {
  std::error_code ec;
  std::filesystem::remove_all(path_, ec);  // nothing there once published (renamed away)
  guard_.reset();  // only now: a signal during the removal still finishes it
}

}  // namespace sysid
