#include "io/temp_files.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <atomic>
#include <csignal>
#include <cstddef>
#include <cstdint>
#include <cstring>

namespace sysid::internal {
namespace {

constexpr int kSlots = 64;
constexpr std::size_t kPathBytes = 4096;
constexpr int kMaxDepth = 16;

// Slot states: 0 free, 1 being filled, 2 live file, 3 live folder (the handler removes live
// slots only).
std::atomic<int> g_state[kSlots];
char g_path[kSlots][kPathBytes];

// The entries of an open folder as the kernel lists them (getdents64's record layout).
struct LinuxDirent64 {
  std::uint64_t d_ino;
  std::int64_t d_off;
  unsigned short d_reclen;
  unsigned char d_type;
  char d_name[1];
};

bool IsDotOrDotDot(const char* name) {
  return name[0] == '.' && (name[1] == '\0' || (name[1] == '.' && name[2] == '\0'));
}

// Empties the folder open as `dir` (async-signal-safe: getdents64, openat, unlinkat, close).
// Entries are unlinked as files first; a folder (EISDIR) is emptied recursively, then removed.
void EmptyFolder(int dir, int depth) {
  alignas(8) char buf[4096];
  // Deleting while listing can make the listing skip entries: list again until a pass
  // removes nothing.
  for (bool removed = true; removed;) {
    removed = false;
    if (::lseek(dir, 0, SEEK_SET) < 0) return;
    for (;;) {
      const long n = ::syscall(SYS_getdents64, dir, buf, sizeof buf);
      if (n <= 0) break;
      for (long off = 0; off < n;) {
        const auto* e = reinterpret_cast<const LinuxDirent64*>(buf + off);
        off += e->d_reclen;
        if (IsDotOrDotDot(e->d_name)) continue;
        if (::unlinkat(dir, e->d_name, 0) == 0) {
          removed = true;
          continue;
        }
        if (depth >= kMaxDepth) continue;
        const int sub = ::openat(dir, e->d_name, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
        if (sub < 0) continue;
        EmptyFolder(sub, depth + 1);
        ::close(sub);
        if (::unlinkat(dir, e->d_name, AT_REMOVEDIR) == 0) removed = true;
      }
    }
  }
}

extern "C" void RemoveTempFilesAndReraise(int sig) {
  // Async-signal-safe: atomic loads, unlink, the folder walk above, signal, raise.
  for (int i = 0; i < kSlots; ++i) {
    const int state = g_state[i].load();
    if (state == 2) ::unlink(g_path[i]);
    if (state == 3) RemoveTreeSignalSafe(g_path[i]);
  }
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}

void InstallHandlers() {
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
    struct sigaction old {};
    if (sigaction(sig, nullptr, &old) != 0 || old.sa_handler != SIG_DFL) continue;
    struct sigaction sa {};
    sa.sa_handler = &RemoveTempFilesAndReraise;
    sigemptyset(&sa.sa_mask);
    sigaction(sig, &sa, nullptr);
  }
}

}  // namespace

bool RemoveTreeSignalSafe(const char* path) {
  const int dir = ::open(path, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (dir < 0) return ::unlink(path) == 0;  // gone already, or not a folder
  EmptyFolder(dir, 0);
  ::close(dir);
  return ::rmdir(path) == 0;
}

InterruptsBlocked::InterruptsBlocked() {
  sigset_t block;
  sigemptyset(&block);
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&block, sig);
  pthread_sigmask(SIG_BLOCK, &block, &old_);
}

InterruptsBlocked::~InterruptsBlocked() { pthread_sigmask(SIG_SETMASK, &old_, nullptr); }

TempFileGuard::TempFileGuard(const std::string& path, TempKind kind) {
  // Checked at every registration (two sigaction calls beside a file write): a program that
  // sets its own handlers later keeps them, one that restores the defaults gets ours again.
  InstallHandlers();
  if (path.size() >= kPathBytes) return;
  for (int i = 0; i < kSlots; ++i) {
    int expected = 0;
    if (!g_state[i].compare_exchange_strong(expected, 1)) continue;
    std::memcpy(g_path[i], path.c_str(), path.size() + 1);
    g_state[i].store(kind == TempKind::kFolder ? 3 : 2);
    slot_ = i;
    return;
  }
}

TempFileGuard::~TempFileGuard() {
  if (slot_ >= 0) g_state[slot_].store(0);
}

}  // namespace sysid::internal
