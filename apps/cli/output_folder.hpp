// The rule for every "-o DIR" of the CLI: a folder is written whole or not at all, and only a
// new folder, an empty one, or one this toolkit wrote before (it holds the .sysid-output marker)
// is ever replaced, the last only with --force. Inputs are never inside it. Each run stages
// into its own hidden sibling folder and publishes only if the folder is still as it found it,
// so two runs at once never publish a mix.
#ifndef SYSID_APPS_CLI_OUTPUT_FOLDER_HPP_
#define SYSID_APPS_CLI_OUTPUT_FOLDER_HPP_

#include <sys/types.h>

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace sysid::cli {

/// Marker file of a folder written by sysid.
inline constexpr const char* kOutputMarker = ".sysid-output";

class OutputFolder {
 public:
  /// Checks `dir` before any work (throws OptionsError, exit 1): trailing slashes are dropped;
  /// `inputs` (files or folders) must not be the folder or inside it; an existing non-empty
  /// folder needs the marker and `force`. `command` names the writer in the marker. The state
  /// of the folder (absent, or its identity and marker) is remembered for Write.
  OutputFolder(const std::string& dir, bool force, const std::vector<std::string>& inputs,
               std::string command);
  /// The final folder (absolute, normalised).
  const std::filesystem::path& path() const { return out_; }
  /// Calls `write(folder)` on a new staging folder beside the target (".DIR.tmp.PID.XXXXXX",
  /// holding the marker with this run's id), then renames it into place. On any error, or
  /// Ctrl-C, the staging folder is removed and the previous folder is untouched. When the
  /// folder changed since the constructor looked (another run published it meanwhile), nothing
  /// is published and InputError (exit 2) says so.
  void Write(const std::function<void(const std::filesystem::path&)>& write) const;

 private:
  /// What the folder is now: absent, or (device, inode, marker text).
  struct State {
    bool exists = false;
    dev_t dev = 0;
    ino_t ino = 0;
    std::string marker;
    bool operator==(const State& o) const {
      return exists == o.exists && dev == o.dev && ino == o.ino && marker == o.marker;
    }
  };
  State Observe() const;

  std::string given_;
  std::string command_;
  std::filesystem::path out_;
  State initial_;
};

/// The OutputFolder of an optional "-o DIR": none when `dir` is empty. Entries of `inputs`
/// that are empty or name no existing file or folder (e.g. a preset name) are skipped.
std::optional<OutputFolder> OptionalOutputFolder(const std::string& dir, bool force,
                                                 const std::vector<std::string>& inputs,
                                                 const std::string& command);

/// True when `p` is a folder holding the sysid marker.
bool HasOutputMarker(const std::filesystem::path& p);

}  // namespace sysid::cli

#endif  // SYSID_APPS_CLI_OUTPUT_FOLDER_HPP_
