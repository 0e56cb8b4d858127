// Private: temporary files and staging folders removed when the process is interrupted. A file
// being written atomically (".out.csv.tmp.XXXXXX") or a folder being filled before it is
// renamed into place (".rep.tmp.PID.XXXXXX") is registered while it exists; SIGINT, SIGTERM or
// SIGHUP then removes it (a folder with everything in it) before the signal's default action,
// so Ctrl-C leaves nothing behind.
#ifndef SYSID_SRC_IO_TEMP_FILES_HPP_
#define SYSID_SRC_IO_TEMP_FILES_HPP_

#include <signal.h>

#include <functional>
#include <string>

namespace sysid::internal {

/// What a TempFileGuard removes on a signal.
enum class TempKind { kFile, kFolder };

/// Registers `path` until the guard is destroyed. The signal handlers are installed at
/// registration, only where the program left the default disposition (its own handlers win).
/// Paths longer than 4095 bytes, or more than 64 at once, are simply not registered. A folder
/// is removed with its content (symbolic links inside it are removed, never followed; at most
/// 16 levels of subfolders).
class TempFileGuard {
 public:
  explicit TempFileGuard(const std::string& path, TempKind kind = TempKind::kFile);
  ~TempFileGuard();
  TempFileGuard(const TempFileGuard&) = delete;
  TempFileGuard& operator=(const TempFileGuard&) = delete;

 private:
  int slot_ = -1;
};

/// Blocks SIGINT, SIGTERM and SIGHUP in the calling thread while it lives, so that a temporary
/// file or folder is created and registered with no gap in which a signal would leave it
/// behind; a signal arriving meanwhile is delivered when the block ends.
class InterruptsBlocked {
 public:
  InterruptsBlocked();
  ~InterruptsBlocked();
  InterruptsBlocked(const InterruptsBlocked&) = delete;
  InterruptsBlocked& operator=(const InterruptsBlocked&) = delete;

 private:
  sigset_t old_;
};

/// Removes `path` and everything below it the way the signal handler does (no allocation,
/// async-signal-safe system calls only); for tests. Returns false when something remained.
bool RemoveTreeSignalSafe(const char* path);
/// Writes `path` atomically: `write(fd, tmp)` fills a new temporary file `tmp` beside it (open
/// as `fd`; a library that opens files by name may write `tmp` itself), which then gets the
/// umask's permissions and is renamed over `path`. On any exception, or a failed rename, the
/// temporary file is removed and `path` is untouched. Throws InputError "PATH: cannot write: ...".
void WriteThroughTempFile(const std::string& path,
                          const std::function<void(int fd, const std::string& tmp)>& write);

}  // namespace sysid::internal

#endif  // SYSID_SRC_IO_TEMP_FILES_HPP_
