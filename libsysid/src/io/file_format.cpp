// DetectFileFormat: the file's first bytes decide how it is read.
#include <sys/stat.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstring>
#include <string>

#include "sysid/io_containers.hpp"

namespace sysid {
namespace {

constexpr char kHdf5Signature[] = "\x89HDF\r\n\x1a\n";

struct Probe {
  bool opened = false;
  bool mat5 = false;        // "MI"/"IM" endian mark at byte 126
  bool mat73_text = false;  // header text "MATLAB 7.3 MAT-file"
  long hdf5_at = -1;        // offset of the HDF5 signature, -1 if none
  bool binary_start = false;
};

Probe ProbeFile(const std::string& path) {
  Probe p;
  // A pipe (`cat rec.csv | sysid derive /dev/stdin`) can be read once: probing it here would
  // eat its first bytes before the reader gets them. MAT and HDF5 readers need a regular
  // file, so anything else is text, read whole by ReadFile (bounded by kMaxInputFileBytes).
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) return p;
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) return p;
  p.opened = true;
  unsigned char head[128] = {};
  const size_t n = std::fread(head, 1, sizeof head, f);
  if (n == sizeof head &&
      ((head[126] == 'I' && head[127] == 'M') || (head[126] == 'M' && head[127] == 'I')))
    p.mat5 = true;
  if (n >= 19 && std::memcmp(head, "MATLAB 7.3 MAT-file", 19) == 0) p.mat73_text = true;
  for (size_t i = 0; i < std::min<size_t>(n, 64); ++i)
    if (head[i] == 0 || (head[i] < 32 && !std::isspace(head[i]))) p.binary_start = true;
  // HDF5 looks for its superblock at 0, 512, 1024, 2048, ... (a user block before it).
  for (long off = 0;; off = off == 0 ? 512 : off * 2) {
    if (std::fseek(f, off, SEEK_SET) != 0) break;
    char sig[8];
    if (std::fread(sig, 1, 8, f) != 8) break;
    if (std::memcmp(sig, kHdf5Signature, 8) == 0) {
      p.hdf5_at = off;
      break;
    }
    if (off > (1L << 40)) break;
  }
  std::fclose(f);
  return p;
}

bool EndsWithMat(const std::string& path) {
  if (path.size() < 4) return false;
  std::string ext = path.substr(path.size() - 4);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".mat";
}

}  // namespace

FileFormat DetectFileFormat(const std::string& path) {
  const Probe p = ProbeFile(path);
  if (!p.opened) return FileFormat::kText;  // the text reader reports why it cannot open
  if (p.hdf5_at >= 0) return (p.hdf5_at == 512 && p.mat5) ? FileFormat::kMat : FileFormat::kHdf5;
  if (p.mat5) return FileFormat::kMat;
  if (EndsWithMat(path) && p.binary_start) return FileFormat::kMat;  // MAT v4: no magic
  return FileFormat::kText;
}

std::string DescribeFileFormat(const std::string& path) {
  const Probe p = ProbeFile(path);
  if (p.hdf5_at >= 0) return (p.hdf5_at == 512 && p.mat5) ? "MAT v7.3" : "HDF5";
  if (p.mat5) return "MAT v5";
  if (p.opened && EndsWithMat(path) && p.binary_start) return "MAT v4";
  return "text";
}

}  // namespace sysid
