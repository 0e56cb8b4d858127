#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>

#include "io/temp_files.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"

namespace sysid {

std::string ReadFile(const std::string& path) {
  std::string text;
  ReadFile(path, &text);
  return text;
}

void ReadFile(const std::string& path, std::string* out) {
  std::string& text = *out;
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw InputError(path + ": cannot open: is a directory");
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) throw InputError(path + ": cannot open: " + std::strerror(errno));
  // One allocation of the file's size (none when `text` already holds as much), then one
  // read: no regrowth for large recordings.
  const auto size = std::filesystem::file_size(path, ec);
  if (!ec) text.resize(static_cast<size_t>(size));
  size_t got = ec ? 0 : std::fread(text.data(), 1, text.size(), f);
  text.resize(got);
  char buf[1 << 16];
  size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, f)) > 0) text.append(buf, n);  // grew meanwhile
  const bool failed = std::ferror(f) != 0;
  std::fclose(f);
  if (failed) throw InputError(path + ": read error");
}

namespace internal {

void WriteThroughTempFile(const std::string& path,
                          const std::function<void(int fd, const std::string& tmp)>& write) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  std::string tmpl = (dir / ("." + target.filename().string() + ".tmp.XXXXXX")).string();
  const int fd = mkstemp(tmpl.data());
  if (fd < 0) throw InputError(path + ": cannot write: " + std::strerror(errno));
  const TempFileGuard interrupted(tmpl);  // Ctrl-C while writing removes it
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
  if (::close(fd) != 0 || std::rename(tmpl.c_str(), path.c_str()) != 0) {
    const std::string reason = std::strerror(errno);
    ::unlink(tmpl.c_str());
    throw InputError(path + ": cannot write: " + reason);
  }
}

}  // namespace internal

void WriteFileAtomically(const std::string& path, std::string_view content) {
  internal::WriteThroughTempFile(path, [&](int fd, const std::string&) {
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
  });
}

}  // namespace sysid
