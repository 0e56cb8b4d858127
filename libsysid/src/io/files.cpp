#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>

#include "io/temp_files.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"
#include "sysid/io_output.hpp"

namespace sysid {
namespace {

const char* KindOf(mode_t mode) {
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISFIFO(mode)) return "a pipe (FIFO)";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

std::string TooLarge(const std::string& path, std::uint64_t bytes, bool exact) {
  return path + ": " + std::to_string(bytes) + (exact ? " bytes" : " bytes or more") +
         ", past the " +
         std::to_string(kMaxInputFileBytes >> 30) +
         " GiB a file may have (sysid::kMaxInputFileBytes); nothing was loaded";
}

// Writes `content` through an open descriptor (all of it, retrying short writes).
void WriteAll(int fd, const std::string& path, std::string_view content) {
  const char* p = content.data();
  size_t left = content.size();
  while (left > 0) {
    const ssize_t w = ::write(fd, p, left);
    if (w < 0) {
      if (errno == EINTR) continue;
      throw InputError(path + ": cannot write: " + std::strerror(errno));
    }
    p += w;
    left -= static_cast<size_t>(w);
  }
}

// A pipe or a device (-o /dev/stdout, a FIFO, /dev/null) is written through, never replaced.
void WriteThrough(const std::string& path, std::string_view content) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC);
  if (fd < 0) throw InputError(path + ": cannot write: " + std::strerror(errno));
  try {
    WriteAll(fd, path, content);
  } catch (...) {
    ::close(fd);
    throw;
  }
  if (::close(fd) != 0) throw InputError(path + ": cannot write: " + std::strerror(errno));
}

// The descriptor a path names directly: /dev/stdout, /dev/stderr, /dev/fd/N and
// /proc/self/fd/N are this process's own descriptors; -1 for any other path. Writing to the
// descriptor itself keeps the shell's redirection as it is (`>> log` appends, `> f` is not
// replaced by a new file).
int OwnDescriptor(const std::string& path) {
  if (path == "/dev/stdout") return 1;
  if (path == "/dev/stderr") return 2;
  for (const char* prefix : {"/dev/fd/", "/proc/self/fd/"}) {
    const std::string_view p(path);
    if (p.rfind(prefix, 0) != 0) continue;
    const std::string_view digits = p.substr(std::strlen(prefix));
    if (digits.empty() || digits.size() > 6 ||
        digits.find_first_not_of("0123456789") != std::string_view::npos)
      return -1;
    return std::atoi(std::string(digits).c_str());
  }
  return -1;
}

}  // namespace

bool WritesThrough(const std::string& path) {
  if (const int own = OwnDescriptor(path); own >= 0 && ::fcntl(own, F_GETFD) != -1) return true;
  struct stat st {};
  return ::stat(path.c_str(), &st) == 0 && (S_ISFIFO(st.st_mode) || S_ISCHR(st.st_mode));
}

std::string ReadFile(const std::string& path) {
  std::string text;
  ReadFile(path, &text);
  return text;
}

void ReadFile(const std::string& path, std::string* out) {
  std::string& text = *out;
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0)
    throw InputError(path + ": cannot open: " + std::strerror(errno));
  // A device (/dev/zero, a terminal) or a socket is no recording and may never end; a pipe
  // (a shell's <(...)) is read up to kMaxInputFileBytes.
  if (!S_ISREG(st.st_mode) && !S_ISFIFO(st.st_mode))
    throw InputError(path + ": cannot open: is " + std::string(KindOf(st.st_mode)) +
                     ", not a file");
  if (S_ISREG(st.st_mode) && static_cast<std::uint64_t>(st.st_size) > kMaxInputFileBytes)
    throw InputError(TooLarge(path, static_cast<std::uint64_t>(st.st_size), true));
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) throw InputError(path + ": cannot open: " + std::strerror(errno));
  // One allocation of the file's size (none when `text` already holds as much), then one
  // read: no regrowth for large recordings.
  text.resize(S_ISREG(st.st_mode) ? static_cast<size_t>(st.st_size) : 0);
  size_t got = std::fread(text.data(), 1, text.size(), f);
  text.resize(got);
  char buf[1 << 16];
  size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, f)) > 0) {  // a pipe, or a file that grew
    if (text.size() + n > kMaxInputFileBytes) {
      std::fclose(f);
      throw InputError(TooLarge(path, text.size() + n, false));
    }
    text.append(buf, n);
  }
  const bool failed = std::ferror(f) != 0;
  std::fclose(f);
  if (failed) throw InputError(path + ": read error");
}

namespace internal {

void WriteThroughTempFile(const std::string& path,
                          const std::function<void(int fd, const std::string& tmp)>& write) {
  namespace fs = std::filesystem;
  std::string file = path;
  // A pipe, a device or standard output cannot take a file that is written whole and renamed
  // (MAT): refused, never replaced. Text output streams there instead (WriteFileAtomically).
  if (WritesThrough(path))
    throw OptionsError(path + ": is a pipe, a device or standard output; this format is written "
                              "whole to a file: give a file name");
  struct stat lst {}, st {};
  if (::lstat(path.c_str(), &lst) == 0) {
    if (::stat(path.c_str(), &st) != 0) {
      const bool loop = errno == ELOOP;
      throw OptionsError(path + ": a symbolic link " +
                         (loop ? "in a loop" : "to a missing file") +
                         "; sysid follows links but never replaces one: give another name");
    }
    if (!S_ISREG(st.st_mode))
      throw OptionsError(path + ": exists and is " + KindOf(st.st_mode) +
                         "; choose a file name");
    // A link to a file: the file it names is replaced, the link stays.
    if (S_ISLNK(lst.st_mode)) file = fs::canonical(path).string();
  } else if (errno == ELOOP) {
    throw OptionsError(path + ": a symbolic link in a loop; give another name");
  }
  const fs::path target(file);
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  // ".NAME.tmp.XXXXXX" says what is being written; past the 255 bytes a name may have (a legal
  // 240-byte NAME) the fixed ".sysid.tmp.XXXXXX" does, so any legal name can be written.
  std::string name = "." + target.filename().string() + ".tmp.XXXXXX";
  if (name.size() > 255) name = ".sysid.tmp.XXXXXX";
  std::string tmpl = (dir / name).string();
  std::optional<InterruptsBlocked> blocked(std::in_place);  // until registered
  const int fd = mkstemp(tmpl.data());
  if (fd < 0) throw InputError(path + ": cannot write: " + std::strerror(errno));
  const TempFileGuard interrupted(tmpl);  // Ctrl-C while writing removes it
  blocked.reset();
  try {
    write(fd, tmpl);
  } catch (...) {
    ::close(fd);
    ::unlink(tmpl.c_str());
    throw;
  }
  // mkstemp creates 0600; a result file should be readable like any other output.
  const mode_t mask = ::umask(0);
  ::umask(mask);
  ::fchmod(fd, 0666 & ~mask);
  if (::close(fd) != 0 || std::rename(tmpl.c_str(), file.c_str()) != 0) {
    const std::string reason = std::strerror(errno);
    ::unlink(tmpl.c_str());
    throw InputError(path + ": cannot write: " + reason);
  }
}

}  // namespace internal

void WriteFileAtomically(const std::string& path, std::string_view content) {
  if (const int own = OwnDescriptor(path); own >= 0 && ::fcntl(own, F_GETFD) != -1) {
    std::fflush(stdout);  // what the program printed before stays before
    return WriteAll(own, path, content);
  }
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0 && (S_ISFIFO(st.st_mode) || S_ISCHR(st.st_mode)))
    return WriteThrough(path, content);
  internal::WriteThroughTempFile(path,
                                 [&](int fd, const std::string&) { WriteAll(fd, path, content); });
}

}  // namespace sysid
