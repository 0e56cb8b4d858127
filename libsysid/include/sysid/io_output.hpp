// Output safety shared by every writer: staging folders that an interrupted run removes, and
// the limits on what a reader loads into memory.
#ifndef SYSID_IO_OUTPUT_HPP_
#define SYSID_IO_OUTPUT_HPP_

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>

namespace sysid {

/// The most bytes ReadFile loads from one file (4 GiB): a recording of kMaxSignalSamples rows
/// in five columns is about 2 GB of text. A larger regular file is refused before anything is
/// allocated; a pipe is refused when it passes this many bytes.
inline constexpr std::uint64_t kMaxInputFileBytes = std::uint64_t{4} << 30;

/// [s] The shortest step of a recording's time column: the smallest normal double, so that the
/// sample rate 1/step is finite. Every reader refuses a smaller step, and a span t_last - t_first
/// past the largest double.
inline constexpr double kMinTimeStep_s = 2.2250738585072014e-308;

// WriteFileAtomically (sysid/io.hpp) replaces nothing but a regular file: a FIFO or a character
// device (/dev/null) is written through, /dev/stdout and /dev/fd/N write to the program's own
// descriptor, a symbolic link is followed (the file it names is replaced, the link stays); a
// dangling link, a link loop, a folder, a socket or a block device throws OptionsError.
// ReadFile refuses a device or a socket, and more than kMaxInputFileBytes: a regular file from
// its size before anything is read, a pipe when it passes the limit.

/// "sysid VERSION": the generator every file sysid writes names, so that "-o FILE" replaces only
/// files sysid wrote (a mark a user's file carries only by copying one of sysid's): a CSV's first
/// line is "# generator: sysid VERSION" (WriteRecording, the CLI's tables); a JSON file's first
/// key is "_generator": "sysid VERSION" (model, network, stage and hysteresis files; readers skip
/// keys starting with '_'); a MAT file's header text starts "MATLAB 5.0 MAT-file, sysid".
std::string GeneratorName();
/// The CSV mark line, "# generator: sysid VERSION\n".
std::string GeneratorLine();
/// `json_text`, a JSON object as nlohmann dumps it (indent 2 or none), with "_generator" as its
/// first key; text that is not an object is returned unchanged.
std::string WithGeneratorKey(std::string_view json_text);
/// True when `head`, the first bytes of a file, starts with one of the marks above.
bool HasGeneratorMark(std::string_view head);

/// True when WriteFileAtomically(path, ...) writes through `path` instead of replacing a file:
/// the program's own descriptors (/dev/stdout, /dev/stderr, /dev/fd/N, /proc/self/fd/N), a
/// FIFO, a character device, or a link to one of these.
bool WritesThrough(const std::string& path);

/// A new folder beside `target`, named ".NAME.tmp.PID.XXXXXX" (unique per run: the process id
/// and a random suffix), that SIGINT, SIGTERM or SIGHUP removes with its content while
/// this object lives. The destructor removes it too unless it was renamed away (published).
/// Throws InputError when the folder cannot be created.
class StagingFolder {
 public:
  explicit StagingFolder(const std::filesystem::path& target);
  ~StagingFolder();
  StagingFolder(const StagingFolder&) = delete;
  StagingFolder& operator=(const StagingFolder&) = delete;
  const std::filesystem::path& path() const { return path_; }
  /// A token unique to this run ("PID.XXXXXX"), for markers that tell runs apart.
  const std::string& run_id() const { return run_id_; }

 private:
  struct Guard;
  std::filesystem::path path_;
  std::string run_id_;
  std::unique_ptr<Guard> guard_;
};

}  // namespace sysid

#endif  // SYSID_IO_OUTPUT_HPP_
