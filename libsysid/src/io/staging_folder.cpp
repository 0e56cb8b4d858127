#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
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
  const std::string prefix = "." + target.filename().string() + ".tmp." + std::to_string(::getpid());
  std::string tmpl = (dir / (prefix + ".XXXXXX")).string();
  const internal::InterruptsBlocked blocked;  // until the folder is registered
  if (!::mkdtemp(tmpl.data()))
    throw InputError(target.string() + ": cannot create a staging folder beside it: " +
                     std::strerror(errno));
  // mkdtemp creates 0700; a result folder should be readable like any other output.
  const mode_t mask = ::umask(0);
  ::umask(mask);
  ::chmod(tmpl.c_str(), 0777 & ~mask);
  path_ = tmpl;
  run_id_ = tmpl.substr(tmpl.size() - 6 - std::to_string(::getpid()).size() - 1);
  guard_ = std::make_unique<Guard>(tmpl);
}

StagingFolder::~StagingFolder() {
  std::error_code ec;
  std::filesystem::remove_all(path_, ec);  // nothing there once published (renamed away)
  guard_.reset();  // only now: a signal during the removal still finishes it
}

}  // namespace sysid
