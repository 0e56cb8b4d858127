// Private: temporary files removed when the process is interrupted. A file being written
// atomically (".out.csv.tmp.XXXXXX") is registered while it exists; SIGINT, SIGTERM or SIGHUP
// then unlinks it before the signal's default action, so Ctrl-C leaves nothing behind.
#ifndef SYSID_SRC_IO_TEMP_FILES_HPP_
#define SYSID_SRC_IO_TEMP_FILES_HPP_

#include <functional>
#include <string>

namespace sysid::internal {

/// Registers `path` until the guard is destroyed. The signal handlers are installed at
/// registration, only where the program left the default disposition (its own handlers win). Paths longer than 4095 bytes, or more than 64 at once, are simply not registered.
class TempFileGuard {
 public:
  explicit TempFileGuard(const std::string& path);
  ~TempFileGuard();
  TempFileGuard(const TempFileGuard&) = delete;
  TempFileGuard& operator=(const TempFileGuard&) = delete;

 private:
  int slot_ = -1;
};

/// Writes `path` atomically: `write(fd, tmp)` fills a new temporary file `tmp` beside it (open
/// as `fd`; a library that opens files by name may write `tmp` itself), which then gets the
/// umask's permissions and is renamed over `path`. On any exception, or a failed rename, the
/// temporary file is removed and `path` is untouched. Throws InputError "PATH: cannot write: ...".
void WriteThroughTempFile(const std::string& path,
                          const std::function<void(int fd, const std::string& tmp)>& write);

}  // namespace sysid::internal

#endif  // SYSID_SRC_IO_TEMP_FILES_HPP_
